#include "lw/core/png_io.h"

#include "lw/core/error.h"
#include "lw/core/file_util.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <zlib.h>

namespace lw::core {

namespace {

constexpr std::array<std::uint8_t, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
// Refuse absurd headers before allocating: 2^28 pixels is 1 GiB of RGBA, far beyond any baseline.
constexpr std::uint64_t kMaxPixels = std::uint64_t(1) << 28;

int channelsOf(PngFormat format) {
    switch (format) {
    case PngFormat::Gray:
        return 1;
    case PngFormat::Rgb:
        return 3;
    case PngFormat::Rgba:
        return 4;
    }
    return 4;
}

std::uint8_t colourTypeOf(PngFormat format) {
    switch (format) {
    case PngFormat::Gray:
        return 0;
    case PngFormat::Rgb:
        return 2;
    case PngFormat::Rgba:
        return 6;
    }
    return 6;
}

void putU32(std::vector<std::byte>& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8)
        out.push_back(std::byte((v >> shift) & 0xff));
}

std::uint32_t getU32(const std::byte* p) {
    return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) |
           std::uint32_t(p[3]);
}

void putChunk(std::vector<std::byte>& out, const char type[4], const std::byte* data,
              std::size_t size) {
    putU32(out, static_cast<std::uint32_t>(size));
    const std::size_t typeAt = out.size();
    for (int i = 0; i < 4; ++i)
        out.push_back(std::byte(type[i]));
    out.insert(out.end(), data, data + size);
    const auto crc =
        crc32(0L, reinterpret_cast<const Bytef*>(out.data() + typeAt), static_cast<uInt>(size + 4));
    putU32(out, static_cast<std::uint32_t>(crc));
}

int paeth(int a, int b, int c) {
    const int p = a + b - c;
    const int pa = std::abs(p - a);
    const int pb = std::abs(p - b);
    const int pc = std::abs(p - c);
    if (pa <= pb && pa <= pc)
        return a;
    return pb <= pc ? b : c;
}

// The value PNG filter `type` (0 none, 1 sub, 2 up, 3 average, 4 Paeth) predicts from the
// left (a), upper (b) and upper-left (c) bytes; encoder and decoder must agree on it exactly.
int filterPredictor(int type, int a, int b, int c) {
    switch (type) {
    case 1:
        return a;
    case 2:
        return b;
    case 3:
        return (a + b) / 2;
    case 4:
        return paeth(a, b, c);
    default:
        return 0;
    }
}

// Filters one row with filter `type`; `prev` is the unfiltered previous row (zeros for row 0).
void filterRow(int type, const std::uint8_t* row, const std::uint8_t* prev, std::size_t length,
               int bpp, std::uint8_t* out) {
    for (std::size_t i = 0; i < length; ++i) {
        const int a = i >= std::size_t(bpp) ? row[i - bpp] : 0;
        const int b = prev[i];
        const int c = i >= std::size_t(bpp) ? prev[i - bpp] : 0;
        out[i] = static_cast<std::uint8_t>(row[i] - filterPredictor(type, a, b, c));
    }
}

std::vector<std::byte> deflateBytes(const std::vector<std::uint8_t>& raw) {
    uLongf size = compressBound(static_cast<uLong>(raw.size()));
    std::vector<std::byte> out(size);
    if (compress2(reinterpret_cast<Bytef*>(out.data()), &size, raw.data(),
                  static_cast<uLong>(raw.size()), 6) != Z_OK)
        throw Error("PNG encoder", "zlib compression failed");
    out.resize(size);
    return out;
}

std::vector<std::uint8_t> inflateExactly(const std::vector<std::uint8_t>& compressed,
                                         std::size_t expected, const std::string& subject) {
    std::vector<std::uint8_t> out(expected);
    z_stream stream{};
    if (inflateInit(&stream) != Z_OK)
        throw Error(subject, "zlib initialisation failed");
    stream.next_in = const_cast<Bytef*>(compressed.data());
    stream.avail_in = static_cast<uInt>(compressed.size());
    stream.next_out = out.data();
    stream.avail_out = static_cast<uInt>(out.size());
    const int status = inflate(&stream, Z_FINISH);
    const std::size_t produced = stream.total_out;
    const std::string message = stream.msg ? stream.msg : "";
    inflateEnd(&stream);
    if (status == Z_STREAM_END && produced == expected)
        return out;
    if (status == Z_BUF_ERROR && stream.avail_out == 0)
        throw Error(subject, "PNG image data is longer than the header's size");
    if (status == Z_BUF_ERROR || (status == Z_STREAM_END && produced < expected))
        throw Error(subject, "PNG image data is truncated");
    throw Error(subject,
                "PNG image data is corrupt" + (message.empty() ? std::string() : ": " + message));
}

} // namespace

std::vector<std::byte> encodePng(const ImageRgba8& image, PngFormat format) {
    if (image.isEmpty())
        throw Error("PNG encoder", "cannot encode an empty image");
    const int channels = channelsOf(format);
    const std::size_t rowBytes = std::size_t(image.width()) * std::size_t(channels);

    std::vector<std::uint8_t> row(rowBytes), prev(rowBytes, 0), candidate(rowBytes), best(rowBytes);
    std::vector<std::uint8_t> raw;
    raw.reserve((rowBytes + 1) * std::size_t(image.height()));
    for (int y = 0; y < image.height(); ++y) {
        const Rgba8* src = image.row(y);
        for (int x = 0; x < image.width(); ++x) {
            const std::uint8_t rgba[4] = {src[x].r, src[x].g, src[x].b, src[x].a};
            std::memcpy(row.data() + std::size_t(x) * std::size_t(channels), rgba,
                        std::size_t(channels));
        }
        // The usual heuristic (minimum sum of absolute filtered bytes): small files for line
        // drawings and, as a side effect, every filter type gets exercised by the round-trip tests.
        int bestType = 0;
        std::uint64_t bestCost = std::numeric_limits<std::uint64_t>::max();
        for (int type = 0; type <= 4; ++type) {
            filterRow(type, row.data(), prev.data(), rowBytes, channels, candidate.data());
            std::uint64_t cost = 0;
            for (std::uint8_t v : candidate)
                cost += v < 128 ? v : 256 - v;
            if (cost < bestCost) {
                bestCost = cost;
                bestType = type;
                best.swap(candidate);
            }
        }
        raw.push_back(static_cast<std::uint8_t>(bestType));
        raw.insert(raw.end(), best.begin(), best.end());
        prev.swap(row);
    }

    std::vector<std::byte> out(kSignature.size());
    std::memcpy(out.data(), kSignature.data(), kSignature.size());
    std::vector<std::byte> header;
    putU32(header, static_cast<std::uint32_t>(image.width()));
    putU32(header, static_cast<std::uint32_t>(image.height()));
    for (std::uint8_t v :
         {std::uint8_t(8), colourTypeOf(format), std::uint8_t(0), std::uint8_t(0), std::uint8_t(0)})
        header.push_back(std::byte(v));
    putChunk(out, "IHDR", header.data(), header.size());
    const auto compressed = deflateBytes(raw);
    putChunk(out, "IDAT", compressed.data(), compressed.size());
    putChunk(out, "IEND", nullptr, 0);
    return out;
}

void writePng(const std::filesystem::path& path, const ImageRgba8& image, PngFormat format) {
    if (image.isEmpty())
        throw Error(path.string(), "cannot write an empty image as PNG");
    const auto bytes = encodePng(image, format);
    writeFileAtomically(path, bytes.data(), bytes.size());
}

namespace {

// What decoding needs of the IHDR chunk.
struct PngHeader {
    std::uint32_t width = 0, height = 0;
    int channels = 0;
    PngFormat format = PngFormat::Rgba;
};

// The colour types read (8 bits a sample): gray, RGB, gray + alpha, RGBA.
struct ColourType {
    std::uint8_t code;
    int channels;
    PngFormat format;
};
constexpr ColourType kReadColourTypes[] = {{0, 1, PngFormat::Gray},
                                           {2, 3, PngFormat::Rgb},
                                           {4, 2, PngFormat::Rgba},
                                           {6, 4, PngFormat::Rgba}};

PngHeader parsePngHeader(const std::byte* body, std::uint32_t length, const std::string& subject) {
    if (length != 13)
        throw Error(subject, "PNG header has the wrong length");
    PngHeader header;
    header.width = getU32(body);
    header.height = getU32(body + 4);
    const auto bitDepth = std::uint8_t(body[8]);
    const auto colourType = std::uint8_t(body[9]);
    if (header.width == 0 || header.height == 0 ||
        std::uint64_t(header.width) * header.height > kMaxPixels)
        throw Error(subject, "PNG size " + std::to_string(header.width) + "x" +
                                 std::to_string(header.height) + " is empty or too large");
    if (bitDepth != 8)
        throw Error(subject,
                    "unsupported PNG bit depth " + std::to_string(bitDepth) + " (only 8 is read)");
    const auto* known = std::find_if(std::begin(kReadColourTypes), std::end(kReadColourTypes),
                                     [&](const ColourType& t) { return t.code == colourType; });
    if (known == std::end(kReadColourTypes))
        throw Error(subject, "unsupported PNG colour type " + std::to_string(colourType) +
                                 " (gray, gray+alpha, RGB and RGBA are read)");
    header.channels = known->channels;
    header.format = known->format;
    if (std::uint8_t(body[10]) != 0 || std::uint8_t(body[11]) != 0)
        throw Error(subject, "unknown PNG compression or filter method");
    if (std::uint8_t(body[12]) != 0)
        throw Error(subject, "interlaced PNGs are not supported");
    return header;
}

// Walks the chunks after the signature: the header, and the IDAT chunks' bytes joined.
PngHeader readPngChunks(const std::byte* data, std::size_t size, const std::string& subject,
                        std::vector<std::uint8_t>& compressed) {
    std::size_t pos = kSignature.size();
    std::optional<PngHeader> header;
    for (;;) {
        if (size - pos < 12)
            throw Error(subject,
                        "PNG is truncated (chunk header at byte " + std::to_string(pos) + ")");
        const std::uint32_t length = getU32(data + pos);
        const std::string type(reinterpret_cast<const char*>(data + pos + 4), 4);
        if (length > size - pos - 12)
            throw Error(subject, "PNG is truncated (chunk " + type + " claims " +
                                     std::to_string(length) + " bytes)");
        const std::byte* body = data + pos + 8;
        const auto crc = crc32(0L, reinterpret_cast<const Bytef*>(data + pos + 4), length + 4);
        if (static_cast<std::uint32_t>(crc) != getU32(body + length))
            throw Error(subject, "PNG chunk " + type + " has a CRC mismatch (file is corrupt)");
        pos += std::size_t(length) + 12;

        if (type == "IHDR") {
            header = parsePngHeader(body, length, subject);
        } else if (!header) {
            throw Error(subject, "PNG does not start with an IHDR chunk");
        } else if (type == "IDAT") {
            compressed.insert(compressed.end(), reinterpret_cast<const std::uint8_t*>(body),
                              reinterpret_cast<const std::uint8_t*>(body) + length);
        } else if (type == "IEND") {
            return *header;
        } else if ((std::uint8_t(type[0]) & 0x20) == 0) {
            // Upper-case first letter: a critical chunk (e.g. PLTE) we cannot honour.
            throw Error(subject, "unsupported critical PNG chunk " + type);
        }
    }
}

Rgba8 expandPixel(const std::uint8_t* p, int channels) {
    switch (channels) {
    case 1:
        return {p[0], p[0], p[0], 255};
    case 2:
        return {p[0], p[0], p[0], p[1]};
    case 3:
        return {p[0], p[1], p[2], 255};
    default:
        return {p[0], p[1], p[2], p[3]};
    }
}

// The inflated rows, each a filter type byte and the filtered pixels, undone into RGBA.
ImageRgba8 unfilterRows(const std::vector<std::uint8_t>& raw, const PngHeader& header,
                        const std::string& subject) {
    const int channels = header.channels;
    const std::size_t rowBytes = std::size_t(header.width) * std::size_t(channels);
    ImageRgba8 image(static_cast<int>(header.width), static_cast<int>(header.height));
    std::vector<std::uint8_t> row(rowBytes), prev(rowBytes, 0);
    for (std::uint32_t y = 0; y < header.height; ++y) {
        const std::uint8_t* in = raw.data() + std::size_t(y) * (rowBytes + 1);
        const int type = in[0];
        if (type > 4)
            throw Error(subject, "PNG row " + std::to_string(y) + " has an invalid filter type " +
                                     std::to_string(type));
        ++in;
        for (std::size_t i = 0; i < rowBytes; ++i) {
            const int a = i >= std::size_t(channels) ? row[i - channels] : 0;
            const int b = prev[i];
            const int c = i >= std::size_t(channels) ? prev[i - channels] : 0;
            row[i] = static_cast<std::uint8_t>(in[i] + filterPredictor(type, a, b, c));
        }
        Rgba8* out = image.row(static_cast<int>(y));
        for (std::uint32_t x = 0; x < header.width; ++x)
            out[x] = expandPixel(row.data() + std::size_t(x) * std::size_t(channels), channels);
        prev.swap(row);
    }
    return image;
}

} // namespace

ImageRgba8 decodePng(const std::byte* data, std::size_t size, const std::string& subject,
                     PngFormat* storedFormat) {
    if (size < kSignature.size() || std::memcmp(data, kSignature.data(), kSignature.size()) != 0)
        throw Error(subject, "not a PNG file (bad signature)");
    std::vector<std::uint8_t> compressed;
    const PngHeader header = readPngChunks(data, size, subject, compressed);
    if (compressed.empty())
        throw Error(subject, "PNG has no image data");
    const std::size_t rowBytes = std::size_t(header.width) * std::size_t(header.channels);
    const auto raw = inflateExactly(compressed, (rowBytes + 1) * header.height, subject);
    ImageRgba8 image = unfilterRows(raw, header, subject);
    if (storedFormat)
        *storedFormat = header.format;
    return image;
}

ImageRgba8 readPng(const std::filesystem::path& path, PngFormat* storedFormat) {
    const auto bytes = readFileBytes(path);
    return decodePng(bytes.data(), bytes.size(), path.string(), storedFormat);
}

} // namespace lw::core
