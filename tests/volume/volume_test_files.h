#pragma once

// Writers for the small volume files the reader tests create themselves: plain bytes, gzip,
// NIfTI-1 headers and Roettger's DDS stream (an independent encoder, so the decoder is tested
// against the format, not against itself).

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <vector>
#include <zlib.h>

namespace lw::volume::testfiles {

using Bytes = std::vector<std::uint8_t>;

inline void writeFile(const std::filesystem::path& path, const Bytes& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!out)
        throw std::runtime_error("cannot write " + path.string());
}

inline Bytes toBytes(const std::string& text) {
    return Bytes(text.begin(), text.end());
}

inline Bytes concat(Bytes a, const Bytes& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

inline Bytes gzipBytes(const Bytes& data) {
    z_stream s{};
    if (deflateInit2(&s, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        throw std::runtime_error("deflateInit2");
    Bytes out(deflateBound(&s, uLong(data.size())) + 64);
    s.next_in = const_cast<Bytef*>(data.data());
    s.avail_in = uInt(data.size());
    s.next_out = out.data();
    s.avail_out = uInt(out.size());
    if (deflate(&s, Z_FINISH) != Z_STREAM_END)
        throw std::runtime_error("deflate");
    out.resize(s.total_out);
    deflateEnd(&s);
    return out;
}

// Element values as bytes in the requested order.
template <typename T> Bytes encode(const std::vector<T>& values, bool bigEndian) {
    Bytes out(values.size() * sizeof(T));
    for (std::size_t i = 0; i < values.size(); ++i) {
        std::uint8_t raw[sizeof(T)];
        std::memcpy(raw, &values[i], sizeof(T));
        if (bigEndian)
            std::reverse(raw, raw + sizeof(T));
        std::memcpy(out.data() + i * sizeof(T), raw, sizeof(T));
    }
    return out;
}

// ------------------------------------------------------------------------- NIfTI-1

struct NiftiSpec {
    glm::ivec3 dims{4, 3, 2};
    int rank = 3;
    int extraDim = 1; // dim[4] when rank > 3
    int datatype = 4; // int16
    int bitpix = 16;
    glm::vec3 pixdim{1.0f, 1.0f, 1.0f};
    float qfac = 1.0f;
    float voxOffset = 352.0f;
    float sclSlope = 0.0f;
    float sclInter = 0.0f;
    int qformCode = 0;
    int sformCode = 0;
    glm::vec3 quatern{0.0f};
    glm::vec3 qoffset{0.0f};
    float srow[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    bool bigEndian = false;
    bool pair = false; // "ni1" (.hdr/.img) instead of "n+1"
    int sizeofHdr = 348;
};

class HeaderWriter {
public:
    HeaderWriter(Bytes& bytes, bool bigEndian) : m_bytes(bytes), m_big(bigEndian) {}
    template <typename T> void put(std::size_t offset, T value) {
        std::uint8_t raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        if (m_big)
            std::reverse(raw, raw + sizeof(T));
        std::memcpy(m_bytes.data() + offset, raw, sizeof(T));
    }

private:
    Bytes& m_bytes;
    bool m_big;
};

inline Bytes niftiHeader(const NiftiSpec& spec) {
    Bytes header(spec.pair ? 348 : 352, 0);
    HeaderWriter w(header, spec.bigEndian);
    w.put<std::int32_t>(0, spec.sizeofHdr);
    w.put<std::int16_t>(40, std::int16_t(spec.rank));
    w.put<std::int16_t>(42, std::int16_t(spec.dims.x));
    w.put<std::int16_t>(44, std::int16_t(spec.dims.y));
    w.put<std::int16_t>(46, std::int16_t(spec.dims.z));
    w.put<std::int16_t>(48, std::int16_t(spec.extraDim));
    for (int i = 5; i < 8; ++i)
        w.put<std::int16_t>(std::size_t(42 + 2 * (i - 1)), 1);
    w.put<std::int16_t>(70, std::int16_t(spec.datatype));
    w.put<std::int16_t>(72, std::int16_t(spec.bitpix));
    w.put<float>(76, spec.qfac);
    w.put<float>(80, spec.pixdim.x);
    w.put<float>(84, spec.pixdim.y);
    w.put<float>(88, spec.pixdim.z);
    w.put<float>(108, spec.pair ? 0.0f : spec.voxOffset);
    w.put<float>(112, spec.sclSlope);
    w.put<float>(116, spec.sclInter);
    std::memcpy(header.data() + 148, "synthetic", 9);
    w.put<std::int16_t>(252, std::int16_t(spec.qformCode));
    w.put<std::int16_t>(254, std::int16_t(spec.sformCode));
    w.put<float>(256, spec.quatern.x);
    w.put<float>(260, spec.quatern.y);
    w.put<float>(264, spec.quatern.z);
    w.put<float>(268, spec.qoffset.x);
    w.put<float>(272, spec.qoffset.y);
    w.put<float>(276, spec.qoffset.z);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
            w.put<float>(std::size_t(280 + 16 * r + 4 * c), spec.srow[r][c]);
    std::memcpy(header.data() + 344, spec.pair ? "ni1\0" : "n+1\0", 4);
    return header;
}

// ------------------------------------------------------------------------- DDS

class BitWriter {
public:
    void write(std::uint32_t value, unsigned bits) {
        for (int b = int(bits) - 1; b >= 0; --b) {
            m_current = std::uint8_t((m_current << 1) | ((value >> b) & 1u));
            if (++m_count == 8) {
                m_bytes.push_back(m_current);
                m_current = 0;
                m_count = 0;
            }
        }
    }
    Bytes finish() {
        if (m_count > 0)
            m_bytes.push_back(std::uint8_t(m_current << (8 - m_count)));
        m_count = 0;
        return m_bytes;
    }

private:
    Bytes m_bytes;
    std::uint8_t m_current = 0;
    unsigned m_count = 0;
};

// Encodes `data` as a DDS stream body (without magic): interleaved by `skip` (1..4), predicted
// along rows of `strip` bytes (1..65536), runs of up to 127 bytes, width 0 for runs of zero
// residuals and width 8 otherwise.
inline Bytes ddsEncode(const Bytes& data, unsigned skip, unsigned strip) {
    Bytes interleaved;
    interleaved.reserve(data.size());
    for (unsigned lane = 0; lane < skip; ++lane)
        for (std::size_t j = lane; j < data.size(); j += skip)
            interleaved.push_back(data[j]);
    std::vector<int> residual(interleaved.size());
    int previous = 0;
    for (std::size_t i = 0; i < interleaved.size(); ++i) {
        int predicted = previous;
        if (strip > 1 && i > strip)
            predicted += int(interleaved[i - strip]) - int(interleaved[i - strip - 1]);
        residual[i] = ((int(interleaved[i]) - predicted) % 256 + 256) % 256; // 0..255
        previous = interleaved[i];
    }
    BitWriter bits;
    bits.write(skip - 1, 2);
    bits.write(strip - 1, 16);
    std::size_t i = 0;
    while (i < residual.size()) {
        const bool zero = residual[i] == 0;
        std::size_t run = 0;
        while (i + run < residual.size() && run < 127 && (residual[i + run] == 0) == zero)
            ++run;
        bits.write(std::uint32_t(run), 7);
        if (zero) {
            bits.write(0, 3); // width 0: the value is the prediction
        } else {
            bits.write(7, 3); // width 8, values biased by 128
            for (std::size_t r = 0; r < run; ++r)
                bits.write(std::uint32_t((residual[i + r] + 128) % 256), 8);
        }
        i += run;
    }
    bits.write(0, 7);
    return bits.finish();
}

} // namespace lw::volume::testfiles
