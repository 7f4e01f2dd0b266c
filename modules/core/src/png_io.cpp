#include "lw/core/png_io.h"

#include "lw/core/error.h"
#include "lw/core/file_util.h"

#include <cstdint>
#include <cstdio>
#include <new>
#include <png.h>
#include <string>
#include <zlib.h>

namespace lw::core {

namespace {

// Refuse absurd headers before allocating: 2^28 pixels is 1 GiB of RGBA, far beyond any baseline.
constexpr std::uint64_t kMaxPixels = std::uint64_t(1) << 28;

int colourTypeOf(PngFormat format) {
    switch (format) {
    case PngFormat::Gray:
        return PNG_COLOR_TYPE_GRAY;
    case PngFormat::Rgb:
        return PNG_COLOR_TYPE_RGB;
    case PngFormat::Rgba:
        return PNG_COLOR_TYPE_RGBA;
    }
    return PNG_COLOR_TYPE_RGBA;
}

std::size_t channelsOf(PngFormat format) {
    return format == PngFormat::Gray ? 1 : format == PngFormat::Rgb ? 3 : 4;
}

// The pixels as libpng takes rows of `format`: Gray keeps the red channel, Rgb drops alpha.
std::vector<std::uint8_t> packedSamples(const ImageRgba8& image, PngFormat format) {
    const std::size_t channels = channelsOf(format);
    const std::uint8_t* rgba = image.bytes();
    std::vector<std::uint8_t> packed(image.pixelCount() * channels);
    for (std::size_t i = 0; i < image.pixelCount(); ++i)
        for (std::size_t c = 0; c < channels; ++c)
            packed[i * channels + c] = rgba[i * 4 + c];
    return packed;
}

// What libpng's callbacks share while writing: libpng leaves writeRows by longjmp on an error,
// so everything here is trivially destructible and the output vector lives outside.
struct WriteState {
    std::vector<std::byte>* out;
    char message[160] = "";
    bool outOfMemory = false;
};

[[noreturn]] void onWriteError(png_structp png, png_const_charp message) {
    auto* state = static_cast<WriteState*>(png_get_error_ptr(png));
    std::snprintf(state->message, sizeof state->message, "%s", message);
    png_longjmp(png, 1);
}

void onWriteWarning(png_structp, png_const_charp) {} // nothing a user could act on

void appendBytes(png_structp png, png_bytep data, std::size_t size) {
    auto* state = static_cast<WriteState*>(png_get_io_ptr(png));
    try {
        const auto* bytes = reinterpret_cast<const std::byte*>(data);
        state->out->insert(state->out->end(), bytes, bytes + size);
    } catch (const std::bad_alloc&) {
        state->outOfMemory = true;
    }
    if (state->outOfMemory) // outside the handler: png_error does not return
        png_error(png, "out of memory");
}

void flushNothing(png_structp) {}

// libpng's classic writer, for the setting its simplified API lacks: zlib's default strategy
// (libpng's own, Z_FILTERED, makes our line drawings 10-15% larger), with every filter at level
// 6. No object with a destructor lives in this frame after setjmp. Returns false with
// state.message set on failure.
bool writeRows(WriteState& state, png_bytep* rows, png_uint_32 width, png_uint_32 height,
               int colourType) {
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, onWriteError, onWriteWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_set_write_fn(png, &state, appendBytes, flushNothing);
    png_set_IHDR(png, info, width, height, 8, colourType, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
    png_set_compression_level(png, 6);
    png_set_compression_strategy(png, Z_DEFAULT_STRATEGY);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

// libpng's simplified API keeps its setjmp inside: errors come back as a message in the
// png_image, so none has to be longjmp'ed or thrown through C frames here.
struct PngImage {
    png_image image{};
    PngImage() { image.version = PNG_IMAGE_VERSION; }
    ~PngImage() { png_image_free(&image); }
    PngImage(const PngImage&) = delete;
    PngImage& operator=(const PngImage&) = delete;
    std::string message() const { return image.message[0] ? image.message : "unknown error"; }
};

} // namespace

std::vector<std::byte> encodePng(const ImageRgba8& image, PngFormat format) {
    if (image.isEmpty())
        throw Error("PNG encoder", "cannot encode an empty image");
    const std::vector<std::uint8_t> packed =
        format == PngFormat::Rgba ? std::vector<std::uint8_t>() : packedSamples(image, format);
    // libpng's row pointers are not const, though writing only reads them.
    auto* samples =
        const_cast<std::uint8_t*>(format == PngFormat::Rgba ? image.bytes() : packed.data());
    const std::size_t rowBytes = std::size_t(image.width()) * channelsOf(format);
    std::vector<png_bytep> rows(std::size_t(image.height()));
    for (std::size_t y = 0; y < rows.size(); ++y)
        rows[y] = samples + y * rowBytes;
    std::vector<std::byte> out;
    WriteState state{&out};
    if (!writeRows(state, rows.data(), png_uint_32(image.width()), png_uint_32(image.height()),
                   colourTypeOf(format)))
        throw Error("PNG encoder", state.message[0] ? state.message : "libpng failed");
    return out;
}

void writePng(const std::filesystem::path& path, const ImageRgba8& image, PngFormat format) {
    if (image.isEmpty())
        throw Error(path.string(), "cannot write an empty image as PNG");
    const auto bytes = encodePng(image, format);
    writeFileAtomically(path, bytes.data(), bytes.size());
}

ImageRgba8 decodePng(const std::byte* data, std::size_t size, const std::string& subject,
                     PngFormat* storedFormat) {
    PngImage png;
    if (!png_image_begin_read_from_memory(&png.image, data, size))
        throw Error(subject, "not a readable PNG: " + png.message());
    // The header is read, nothing is allocated yet: the place to refuse absurd sizes.
    const std::uint64_t pixels = std::uint64_t(png.image.width) * png.image.height;
    if (pixels == 0 || pixels > kMaxPixels)
        throw Error(subject, "PNG size " + std::to_string(png.image.width) + "x" +
                                 std::to_string(png.image.height) + " is empty or too large");
    // libpng would convert 16-bit samples (taken as linear light) to sRGB: a baseline compared
    // pixel by pixel must be read as stored, so they are refused as before.
    if (png.image.format & PNG_FORMAT_FLAG_LINEAR)
        throw Error(subject, "unsupported PNG bit depth 16 (only 8 bits a sample are read)");
    const png_uint_32 stored = png.image.format;
    png.image.format = PNG_FORMAT_RGBA;
    ImageRgba8 image(static_cast<int>(png.image.width), static_cast<int>(png.image.height));
    if (!png_image_finish_read(&png.image, nullptr, image.bytes(), 0, nullptr))
        throw Error(subject, "PNG image data is corrupt: " + png.message());
    if (storedFormat)
        *storedFormat = (stored & PNG_FORMAT_FLAG_ALPHA)   ? PngFormat::Rgba
                        : (stored & PNG_FORMAT_FLAG_COLOR) ? PngFormat::Rgb
                                                           : PngFormat::Gray;
    return image;
}

ImageRgba8 readPng(const std::filesystem::path& path, PngFormat* storedFormat) {
    const auto bytes = readFileBytes(path);
    return decodePng(bytes.data(), bytes.size(), path.string(), storedFormat);
}

} // namespace lw::core
