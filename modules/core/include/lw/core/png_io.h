#pragma once

#include "lw/core/image.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace lw::core {

// The colour type a PNG is written with (or was stored in). Gray stores the red channel, so
// callers pass grey images with r == g == b; Rgb drops alpha.
enum class PngFormat { Gray, Rgb, Rgba };

// Encodes 8-bit, non-interlaced PNG bytes (per-row adaptive filtering, zlib deflate).
std::vector<std::byte> encodePng(const ImageRgba8& image, PngFormat format = PngFormat::Rgba);

// Writes a PNG atomically (temporary sibling + rename), so a crash never leaves half an image.
// Throws Error naming the file on failure or for an empty image.
void writePng(const std::filesystem::path& path, const ImageRgba8& image,
              PngFormat format = PngFormat::Rgba);

// Decodes 8-bit, non-interlaced gray, gray+alpha, RGB and RGBA PNGs into RGBA (gray expands to
// r = g = b, missing alpha becomes 255). Anything else (palette, 16-bit, interlaced, corrupt,
// truncated, CRC mismatch) throws Error naming `subject` and the reason. `storedFormat`, when
// given, receives the stored colour type (gray+alpha reports Rgba).
ImageRgba8 decodePng(const std::byte* data, std::size_t size, const std::string& subject,
                     PngFormat* storedFormat = nullptr);
ImageRgba8 readPng(const std::filesystem::path& path, PngFormat* storedFormat = nullptr);

} // namespace lw::core
