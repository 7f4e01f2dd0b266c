// The exports' PNG encoder (png_io.h, encodePngFastFromBgrx): the picture's rows filtered
// ("up") and deflated in bands on several threads, joined into one zlib stream as pigz joins
// them. Each band is a raw deflate stream of its own, ended by a sync flush (byte-aligned, not
// final) -- the last band by a finish -- so the bands' bytes concatenate into one valid stream;
// the Adler-32 of the whole is combined from the bands' (adler32_combine). The bands are fixed
// in rows, so the file does not depend on the number of threads.
//
//   signature | IHDR | IDAT: 78 01, band 0 ... band n-1 (final), Adler-32 | IEND

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/core/png_io.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <string>
#include <zlib.h>

namespace lw::core {
namespace {

// Rows a band: 4096-wide rows at 3 bytes a pixel make 1.5 MiB a band, enough to amortise the
// deflate stream's start and small enough for 32 bands in a 2048-row picture.
constexpr int kBandRows = 64;
constexpr std::uint8_t kFilterUp = 2;

void appendBigEndian(std::vector<std::byte>& out, std::uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8)
        out.push_back(std::byte((value >> shift) & 0xff));
}

void appendChunk(std::vector<std::byte>& out, const char type[4], const std::byte* data,
                 std::size_t size) {
    if (size > std::size_t(std::numeric_limits<std::int32_t>::max()))
        throw Error("PNG encoder", "a chunk over 2 GiB");
    appendBigEndian(out, std::uint32_t(size));
    const std::size_t typeAt = out.size();
    for (int i = 0; i < 4; ++i)
        out.push_back(std::byte(type[i]));
    out.insert(out.end(), data, data + size);
    uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(out.data() + typeAt), 4);
    if (size > 0) // crc32_z of a null buffer returns the initial value, not `crc`
        crc = crc32_z(crc, reinterpret_cast<const Bytef*>(data), size);
    appendBigEndian(out, std::uint32_t(crc));
}

// One band's filtered rows, deflated: its bytes and the Adler-32 of the filtered rows.
struct Band {
    std::vector<std::byte> deflated;
    uLong adler = 1;
    std::size_t filteredBytes = 0;
};

// Row y as PNG's filter "up" writes it: the filter byte, then R, G, B less the row above's.
void filterRow(const std::uint8_t* pixels, std::size_t bytesPerLine, int width, int y,
               std::uint8_t* out) {
    const std::uint8_t* row = pixels + std::size_t(y) * bytesPerLine;
    const std::uint8_t* above = y > 0 ? row - bytesPerLine : nullptr;
    *out++ = kFilterUp;
    for (int x = 0; x < width; ++x, out += 3) {
        const std::uint8_t* p = row + 4 * std::size_t(x); // B, G, R, X
        const std::uint8_t* q = above ? above + 4 * std::size_t(x) : nullptr;
        out[0] = std::uint8_t(p[2] - (q ? q[2] : 0));
        out[1] = std::uint8_t(p[1] - (q ? q[1] : 0));
        out[2] = std::uint8_t(p[0] - (q ? q[0] : 0));
    }
}

// Deflates rows [first, last) at level 1 with run-length matching, as one raw stream ended by a
// sync flush, or by a finish for the picture's last band.
Band deflateBand(const std::uint8_t* pixels, std::size_t bytesPerLine, int width, int first,
                 int last, bool final) {
    const std::size_t rowBytes = 1 + 3 * std::size_t(width);
    std::vector<std::uint8_t> filtered(rowBytes * std::size_t(last - first));
    for (int y = first; y < last; ++y)
        filterRow(pixels, bytesPerLine, width, y, filtered.data() + rowBytes * (y - first));
    Band band;
    band.filteredBytes = filtered.size();
    band.adler = adler32_z(1L, filtered.data(), filtered.size());
    z_stream stream{};
    if (deflateInit2(&stream, 1, Z_DEFLATED, -MAX_WBITS, 8, Z_RLE) != Z_OK)
        throw Error("PNG encoder", "zlib could not start a stream");
    // Room for the whole band: deflateBound plus the sync flush's empty block.
    band.deflated.resize(deflateBound(&stream, uLong(filtered.size())) + 16);
    stream.next_in = filtered.data();
    stream.avail_in = uInt(filtered.size());
    stream.next_out = reinterpret_cast<Bytef*>(band.deflated.data());
    stream.avail_out = uInt(band.deflated.size());
    const int result = deflate(&stream, final ? Z_FINISH : Z_SYNC_FLUSH);
    const bool done = final ? result == Z_STREAM_END : result == Z_OK && stream.avail_in == 0;
    band.deflated.resize(band.deflated.size() - stream.avail_out);
    deflateEnd(&stream);
    if (!done)
        throw Error("PNG encoder", "zlib could not deflate a band");
    return band;
}

} // namespace

std::vector<std::byte> encodePngFastFromBgrx(const std::uint8_t* pixels, int width, int height,
                                             std::size_t bytesPerLine) {
    if (!pixels || width <= 0 || height <= 0)
        throw Error("PNG encoder", "cannot encode an empty image");
    if (std::size_t(width) > (std::size_t(std::numeric_limits<uInt>::max()) / 3 - 1) / kBandRows)
        throw Error("PNG encoder", "the picture is too wide");
    const int bands = (height + kBandRows - 1) / kBandRows;
    std::vector<Band> deflated(static_cast<std::size_t>(bands));
    parallelFor(std::size_t(bands), [&](std::size_t b) {
        const int first = int(b) * kBandRows;
        deflated[b] = deflateBand(pixels, bytesPerLine, width, first,
                                  std::min(height, first + kBandRows), int(b) + 1 == bands);
    });
    std::vector<std::byte> zlibStream = {std::byte(0x78), std::byte(0x01)}; // deflate, 32 KiB
    uLong adler = 1;
    for (const Band& band : deflated) {
        zlibStream.insert(zlibStream.end(), band.deflated.begin(), band.deflated.end());
        adler = adler32_combine(adler, band.adler, z_off_t(band.filteredBytes));
    }
    appendBigEndian(zlibStream, std::uint32_t(adler));

    std::vector<std::byte> out;
    out.reserve(zlibStream.size() + 64);
    constexpr std::array<std::uint8_t, 8> kSignature = {0x89, 'P',  'N',  'G',
                                                        '\r', '\n', 0x1a, '\n'};
    for (const std::uint8_t byte : kSignature)
        out.push_back(std::byte(byte));
    std::vector<std::byte> header;
    appendBigEndian(header, std::uint32_t(width));
    appendBigEndian(header, std::uint32_t(height));
    // 8 bits a sample, truecolour (RGB), deflate, adaptive filtering, not interlaced.
    for (const std::uint8_t byte : {8, 2, 0, 0, 0})
        header.push_back(std::byte(byte));
    appendChunk(out, "IHDR", header.data(), header.size());
    appendChunk(out, "IDAT", zlibStream.data(), zlibStream.size());
    appendChunk(out, "IEND", nullptr, 0);
    return out;
}

} // namespace lw::core
