// PVM volumes from Stefan Roettger's Volume Library (the datasets of Morar et al.), raw or
// wrapped in his DDS ("differential data stream") compression.
//
// DDS layout, as decoded here: after the 8-byte magic comes a bit stream read MSB first in
// big-endian 32-bit words (zero-padded at the end). It starts with skip-1 (2 bits, the byte
// interleave stride, e.g. 2 for 16-bit data) and strip-1 (16 bits, the row length used for
// the 2D predictor). Then runs follow: a 7-bit length (0 ends the stream), a 3-bit code for
// the bit width w of the run (0 -> 0, c -> c+1), then per byte a w-bit value v. Each byte is
// previous + v - 2^w/2, plus (once past the first row) the difference between the bytes one
// row back, all mod 256. Finally the bytes are de-interleaved by `skip`; "v3e" does that in
// blocks of 2^24 * skip bytes so huge volumes need no second full-size buffer.
#include "lw/core/file_util.h"
#include "lw/volume/volume_reader.h"
#include "reader_util.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace lw::volume {
namespace {

using detail::fail;

constexpr std::string_view kDdsMagic = "DDS v3d\n";
constexpr std::string_view kDdsMagicBlocked = "DDS v3e\n";
constexpr std::size_t kDdsInterleaveBlock = std::size_t(1) << 24;

class BitReader {
public:
    BitReader(const std::byte* data, std::size_t size) : m_data(data), m_size(size) {}

    // Reads up to 32 bits MSB first; past the end the stream reads as zeros, which ends the
    // run loop with a zero length, the way the format terminates.
    std::uint32_t read(unsigned bits) {
        std::uint32_t value = 0;
        for (unsigned remaining = bits; remaining > 0;) {
            if (m_available == 0) {
                refill();
                if (m_available == 0)
                    return value << remaining;
            }
            const unsigned take = std::min(remaining, m_available);
            m_available -= take;
            const std::uint32_t chunk =
                std::uint32_t((m_buffer >> m_available) & ((std::uint64_t(1) << take) - 1));
            value = (take == 32 ? 0 : value << take) | chunk;
            remaining -= take;
        }
        return value;
    }

private:
    void refill() {
        if (m_pos >= m_size)
            return;
        // Words are big-endian; a short last word is padded with zero bytes.
        std::uint32_t word = 0;
        for (int i = 0; i < 4; ++i) {
            word <<= 8;
            if (m_pos + std::size_t(i) < m_size)
                word |= std::uint32_t(m_data[m_pos + std::size_t(i)]);
        }
        m_pos += 4;
        m_buffer = word;
        m_available = 32;
    }

    const std::byte* m_data;
    std::size_t m_size;
    std::size_t m_pos = 0;
    std::uint64_t m_buffer = 0;
    unsigned m_available = 0;
};

// Restores the byte order the encoder interleaved: the stream holds all bytes with index
// i mod skip == 0 first, then those with 1, and so on (per block when block > 0).
void restoreInterleave(std::vector<std::byte>& data, std::size_t skip, std::size_t block) {
    if (skip <= 1 || data.empty())
        return;
    const std::size_t span = block == 0 ? data.size() : skip * block;
    std::vector<std::byte> scratch(std::min(span, data.size()));
    for (std::size_t start = 0; start < data.size(); start += span) {
        const std::size_t length = std::min(span, data.size() - start);
        const std::byte* in = data.data() + start;
        for (std::size_t lane = 0; lane < skip; ++lane)
            for (std::size_t j = lane; j < length; j += skip)
                scratch[j] = *in++;
        std::memcpy(data.data() + start, scratch.data(), length);
    }
}

std::vector<std::byte> decodeDds(const std::filesystem::path& path, const std::byte* data,
                                 std::size_t size, bool blocked, const core::ImportLimits& limits) {
    BitReader bits(data, size);
    const std::size_t skip = bits.read(2) + 1;
    const std::size_t strip = bits.read(16) + 1;
    std::vector<std::byte> out;
    // An encoder never emits more than 127 bytes per 10 bits; a stream that claims more output
    // than that bound is corrupt. The import limit caps it too: the header comes after it.
    const std::size_t limit = std::min((size * 8 / 10 + 1) * 127, limits.maxBytes);
    out.reserve(std::min(size * 4, limit));
    int value = 0;
    while (true) {
        const std::uint32_t run = bits.read(7);
        if (run == 0)
            break;
        const std::uint32_t code = bits.read(3);
        const unsigned width = code >= 1 ? code + 1 : 0;
        const int half = (1 << width) / 2;
        if (out.size() + run > limit)
            fail(path,
                 out.size() + run > limits.maxBytes
                     ? "DDS stream decodes to more than the import limit of " +
                           std::to_string(limits.maxBytes >> 20) + " MB"
                     : std::string("corrupt DDS stream (decodes to more data than it can hold)"));
        for (std::uint32_t r = 0; r < run; ++r) {
            int delta = int(bits.read(width)) - half;
            const std::size_t count = out.size();
            if (strip > 1 && count > strip)
                delta += int(out[count - strip]) - int(out[count - strip - 1]);
            value = (value + delta) & 0xff;
            out.push_back(std::byte(value));
        }
    }
    if (out.empty())
        fail(path, "DDS stream decodes to no data");
    restoreInterleave(out, skip, blocked ? kDdsInterleaveBlock : 0);
    return out;
}

// Reads "W H D\n" style numbers from the PVM header text, bounded by the buffer.
class HeaderCursor {
public:
    HeaderCursor(const std::filesystem::path& path, const std::byte* data, std::size_t size,
                 std::size_t pos)
        : m_path(path), m_data(reinterpret_cast<const char*>(data)), m_size(size), m_pos(pos) {}

    std::string line(const char* what) {
        const void* newline =
            m_pos < m_size ? std::memchr(m_data + m_pos, '\n', m_size - m_pos) : nullptr;
        if (!newline)
            fail(m_path, std::string("PVM header ends before the ") + what + " line");
        const auto end = std::size_t(static_cast<const char*>(newline) - m_data);
        std::string text(m_data + m_pos, end - m_pos);
        m_pos = end + 1;
        ++m_line;
        return text;
    }
    void skipComments() {
        while (m_pos < m_size && m_data[m_pos] == '#')
            line("comment");
    }
    std::size_t pos() const { return m_pos; }
    int lineNumber() const { return m_line; }

private:
    const std::filesystem::path& m_path;
    const char* m_data;
    std::size_t m_size;
    std::size_t m_pos;
    int m_line = 1;
};

std::string readCString(const std::byte* data, std::size_t size, std::size_t& pos) {
    if (pos >= size)
        return {};
    const char* start = reinterpret_cast<const char*>(data + pos);
    const std::size_t length = strnlen(start, size - pos);
    pos += length + 1;
    return std::string(start, length);
}

bool startsWith(const std::vector<std::byte>& bytes, std::string_view magic) {
    return bytes.size() >= magic.size() &&
           std::memcmp(bytes.data(), magic.data(), magic.size()) == 0;
}

// The PVM version from the magic: 1, 2 or 3.
int pvmVersion(const std::filesystem::path& path, const std::vector<std::byte>& bytes) {
    if (startsWith(bytes, "PVM\n"))
        return 1;
    if (startsWith(bytes, "PVM2\n"))
        return 2;
    if (startsWith(bytes, "PVM3\n"))
        return 3;
    fail(path, "not a PVM file (expected PVM, PVM2 or PVM3, raw or DDS-compressed)");
}

// What the header lines declare; the data follows at dataStart.
struct PvmHeader {
    int version = 0;
    glm::ivec3 dims{0};
    glm::dvec3 spacing{1.0};
    VoxelType type = VoxelType::UInt8;
    std::size_t dataStart = 0;
};

PvmHeader parsePvmHeader(const std::filesystem::path& path, const std::vector<std::byte>& bytes) {
    PvmHeader header;
    header.version = pvmVersion(path, bytes);
    HeaderCursor cursor(path, bytes.data(), bytes.size(), header.version == 1 ? 4 : 5);
    if (header.version == 1)
        cursor.skipComments();
    const auto badLine = [&](const std::string& what, const std::string& text) {
        fail(path, "bad header line " + std::to_string(cursor.lineNumber()) + ": " + what + " '" +
                       text.substr(0, 60) + "'");
    };
    const std::string dimsLine = cursor.line("dimensions");
    const auto dimParts = detail::splitWhitespace(dimsLine);
    if (dimParts.size() != 3)
        badLine("expected 'width height depth', got", dimsLine);
    for (int a = 0; a < 3; ++a) {
        const auto n = detail::parseInteger(dimParts[std::size_t(a)]);
        if (!n || *n < 1 || *n > 1 << 20)
            badLine("bad dimension in", dimsLine);
        header.dims[a] = int(*n);
    }
    if (header.version >= 2) {
        const std::string scaleLine = cursor.line("scale");
        const auto parts = detail::splitWhitespace(scaleLine);
        if (parts.size() != 3)
            badLine("expected 'sx sy sz', got", scaleLine);
        for (int a = 0; a < 3; ++a) {
            const auto s = detail::parseDouble(parts[std::size_t(a)]);
            if (!s || !std::isfinite(*s) || *s <= 0.0)
                badLine("bad scale in", scaleLine);
            header.spacing[a] = *s;
        }
    }
    const std::string componentsLine = cursor.line("components");
    const auto components = detail::parseInteger(componentsLine);
    if (!components || *components < 1)
        badLine("bad component count", componentsLine);
    if (*components > 2)
        fail(path,
             std::to_string(*components) +
                 "-component (colour) PVM volumes are not supported; only 8 and 16 bit scalars");
    header.type = *components == 1 ? VoxelType::UInt8 : VoxelType::UInt16;
    header.dataStart = cursor.pos();
    return header;
}

Volume readPvmUnguarded(const std::filesystem::path& path, const core::ImportLimits& limits) {
    std::vector<std::byte> bytes = core::readFileBytes(path);
    if (startsWith(bytes, kDdsMagic) || startsWith(bytes, kDdsMagicBlocked)) {
        const bool blocked = startsWith(bytes, kDdsMagicBlocked);
        bytes = decodeDds(path, bytes.data() + 8, bytes.size() - 8, blocked, limits);
    }
    const PvmHeader header = parsePvmHeader(path, bytes);
    const std::size_t expected =
        detail::checkVolumeSize(path, header.dims, voxelSize(header.type), header.type, limits);
    if (bytes.size() - header.dataStart < expected)
        fail(path, "truncated volume data: " + std::to_string(bytes.size() - header.dataStart) +
                       " bytes, expected " + std::to_string(expected) + " for " +
                       detail::describeShape(header.dims, header.type));

    Volume volume(header.dims, header.type,
                  VolumeGeometry::regular(glm::dvec3(0.0), header.spacing));
    // 16-bit PVM stores the high byte first.
    detail::fillVolume(volume, bytes.data() + header.dataStart, true);
    if (header.version == 3) {
        std::size_t pos = header.dataStart + expected;
        volume.setDescription(readCString(bytes.data(), bytes.size(), pos));
    }
    return volume;
}

} // namespace

Volume readPvm(const std::filesystem::path& path, const core::ImportLimits& limits) {
    return core::atModuleBoundary(path.string(), [&] { return readPvmUnguarded(path, limits); });
}

} // namespace lw::volume
