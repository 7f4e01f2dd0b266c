#pragma once

#include "lw/core/image.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace lw::core {

// The colour type a PNG is written with (or was stored in). Gray stores the red channel, so
// callers pass grey images with r == g == b; Rgb drops alpha.
enum class PngFormat { Gray, Rgb, Rgba };

// Encodes 8-bit, non-interlaced PNG bytes with libpng (adaptive filtering, an sRGB chunk).
// Throws Error for an empty image.
std::vector<std::byte> encodePng(const ImageRgba8& image, PngFormat format = PngFormat::Rgba);

// The same for a large picture that must be written quickly (the review's exports): rows of
// 4-byte pixels in B, G, R, X byte order (a little-endian 0xffRRGGBB word, as QImage's RGB32
// holds them), `bytesPerLine` apart, written as RGB with one filter (up) and zlib level 1 with
// run-length matching, in bands of rows deflated on several threads (png_fast.cpp). On a
// 4096x2048 review export: about 2.3x faster than adaptive filtering at level 1 on one thread,
// the file about 5% larger. Throws Error for an empty image.
std::vector<std::byte> encodePngFastFromBgrx(const std::uint8_t* pixels, int width, int height,
                                             std::size_t bytesPerLine);

// Writes a PNG atomically (temporary sibling + rename), so a crash never leaves half an image.
// Throws Error naming the file on failure or for an empty image.
void writePng(const std::filesystem::path& path, const ImageRgba8& image,
              PngFormat format = PngFormat::Rgba);

// Decodes PNGs of up to 8 bits a sample with libpng: gray, gray+alpha, RGB, RGBA and palette,
// interlaced or not, into RGBA (gray expands to r = g = b, missing alpha becomes 255; a file
// with a gamma other than sRGB's is converted to sRGB). A header declaring more than 2^28 pixels
// is refused before anything is allocated; that, 16-bit samples (libpng would convert them,
// not read them as stored) and corrupt, truncated or CRC-mismatched files throw Error naming
// `subject` and the reason. `storedFormat`, when given, receives the stored colour type (gray+
// alpha and palettes with transparency report Rgba, other palettes Rgb).
ImageRgba8 decodePng(const std::byte* data, std::size_t size, const std::string& subject,
                     PngFormat* storedFormat = nullptr);
ImageRgba8 readPng(const std::filesystem::path& path, PngFormat* storedFormat = nullptr);

} // namespace lw::core
