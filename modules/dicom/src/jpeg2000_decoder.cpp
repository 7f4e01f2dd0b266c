#include "jpeg2000_decoder.h"

#include "lw/core/error.h"

#include <algorithm>
#include <cstring>
#include <memory>
#include <openjpeg.h>

namespace lw::dicom::detail {
namespace {

// One tile header of OpenJPEG costs a few KiB before any pixel is decoded; real files have one
// tile or a few hundred. More than this is a damaged or hostile SIZ marker.
constexpr std::uint64_t kMaxTiles = 16384;

std::uint32_t bigEndian32(const std::uint8_t* p) {
    return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 |
           std::uint32_t(p[3]);
}

std::uint64_t tilesAlong(std::uint32_t end, std::uint32_t tileOrigin, std::uint32_t tileSize) {
    if (tileSize == 0 || end <= tileOrigin)
        return 0;
    return (std::uint64_t(end - tileOrigin) + tileSize - 1) / tileSize;
}

// The bytes OpenJPEG reads, served from memory (the fragments DCMTK already parsed).
struct MemoryStream {
    std::span<const std::uint8_t> bytes;
    std::size_t offset = 0;
};

OPJ_SIZE_T readFromMemory(void* buffer, OPJ_SIZE_T count, void* user) {
    auto& stream = *static_cast<MemoryStream*>(user);
    if (stream.offset >= stream.bytes.size())
        return OPJ_SIZE_T(-1); // OpenJPEG's end-of-stream value
    const std::size_t n = std::min<std::size_t>(count, stream.bytes.size() - stream.offset);
    std::memcpy(buffer, stream.bytes.data() + stream.offset, n);
    stream.offset += n;
    return n;
}

OPJ_OFF_T skipInMemory(OPJ_OFF_T count, void* user) {
    auto& stream = *static_cast<MemoryStream*>(user);
    if (count < 0)
        return -1; // OpenJPEG only skips forward while decoding
    const std::size_t n =
        std::min<std::size_t>(std::size_t(count), stream.bytes.size() - stream.offset);
    stream.offset += n;
    return OPJ_OFF_T(n);
}

OPJ_BOOL seekInMemory(OPJ_OFF_T position, void* user) {
    auto& stream = *static_cast<MemoryStream*>(user);
    if (position < 0 || std::size_t(position) > stream.bytes.size())
        return OPJ_FALSE;
    stream.offset = std::size_t(position);
    return OPJ_TRUE;
}

// OpenJPEG reports through callbacks; the first error becomes the reason of core::Error.
void keepFirstError(const char* message, void* user) {
    auto& reason = *static_cast<std::string*>(user);
    if (reason.empty() && message) {
        reason = message;
        while (!reason.empty() && (reason.back() == '\n' || reason.back() == ' '))
            reason.pop_back();
    }
}

void ignoreMessage(const char*, void*) {}

struct CodecDeleter {
    void operator()(opj_codec_t* codec) const { opj_destroy_codec(codec); }
};
struct StreamDeleter {
    void operator()(opj_stream_t* stream) const { opj_stream_destroy(stream); }
};
struct ImageDeleter {
    void operator()(opj_image_t* image) const { opj_image_destroy(image); }
};
using CodecPtr = std::unique_ptr<opj_codec_t, CodecDeleter>;
using StreamPtr = std::unique_ptr<opj_stream_t, StreamDeleter>;
using ImagePtr = std::unique_ptr<opj_image_t, ImageDeleter>;

bool isJp2File(std::span<const std::uint8_t> bytes) {
    static constexpr std::uint8_t kJp2Signature[] = {0, 0, 0, 0x0C, 'j', 'P', ' ', ' '};
    return bytes.size() >= sizeof kJp2Signature &&
           std::memcmp(bytes.data(), kJp2Signature, sizeof kJp2Signature) == 0;
}

StreamPtr openMemoryStream(MemoryStream& memory) {
    StreamPtr stream(opj_stream_create(OPJ_J2K_STREAM_CHUNK_SIZE, OPJ_TRUE));
    if (!stream)
        return nullptr;
    opj_stream_set_user_data(stream.get(), &memory, nullptr);
    opj_stream_set_user_data_length(stream.get(), memory.bytes.size());
    opj_stream_set_read_function(stream.get(), readFromMemory);
    opj_stream_set_skip_function(stream.get(), skipInMemory);
    opj_stream_set_seek_function(stream.get(), seekInMemory);
    return stream;
}

// The rule a codestream must pass before OpenJPEG sees it: its SIZ marker describes the frame
// the DICOM header does (one component, the same size, samples that fit), in few tiles.
void checkSizeAgainstHeader(const Jpeg2000Size& size, const Jpeg2000Frame& frame,
                            const std::string& subject) {
    if (size.width != std::uint32_t(frame.columns) || size.height != std::uint32_t(frame.rows))
        throw core::Error(subject, "the JPEG 2000 codestream is " + std::to_string(size.width) +
                                       "x" + std::to_string(size.height) +
                                       " where the header says " + std::to_string(frame.columns) +
                                       "x" + std::to_string(frame.rows));
    if (size.components != 1)
        throw core::Error(subject, "the JPEG 2000 codestream has " +
                                       std::to_string(size.components) +
                                       " components where SamplesPerPixel is 1");
    if (size.precision < 1 || size.precision > frame.bitsAllocated)
        throw core::Error(subject, "the JPEG 2000 codestream holds " +
                                       std::to_string(size.precision) +
                                       "-bit samples where BitsAllocated is " +
                                       std::to_string(frame.bitsAllocated));
    if (size.tiles == 0 || size.tiles > kMaxTiles)
        throw core::Error(subject, "the JPEG 2000 codestream declares " +
                                       std::to_string(size.tiles) + " tiles (at most " +
                                       std::to_string(kMaxTiles) + " are accepted)");
}

// OpenJPEG's first component, as decoded, against what the SIZ check promised.
const opj_image_comp_t& decodedComponent(const opj_image_t& image, const Jpeg2000Frame& frame,
                                         const std::string& subject) {
    if (image.numcomps < 1 || !image.comps || !image.comps[0].data)
        throw core::Error(subject, "OpenJPEG decoded no samples");
    const opj_image_comp_t& component = image.comps[0];
    if (component.w != OPJ_UINT32(frame.columns) || component.h != OPJ_UINT32(frame.rows))
        throw core::Error(subject,
                          "OpenJPEG decoded " + std::to_string(component.w) + "x" +
                              std::to_string(component.h) + " samples where the header says " +
                              std::to_string(frame.columns) + "x" + std::to_string(frame.rows));
    return component;
}

template <typename Sample>
void storeSamples(const opj_image_comp_t& component, std::span<std::byte> out) {
    const std::size_t count = std::size_t(component.w) * component.h;
    auto* samples = reinterpret_cast<Sample*>(out.data());
    // Two's complement truncated to the sample width: the bit pattern native pixel data has.
    for (std::size_t i = 0; i < count; ++i)
        samples[i] = Sample(std::uint32_t(component.data[i]));
}

} // namespace

std::optional<Jpeg2000Size> readJpeg2000Size(std::span<const std::uint8_t> codestream) {
    // FF4F (SOC) FF51 (SIZ), Lsiz, Rsiz, Xsiz, Ysiz, XOsiz, YOsiz, XTsiz, YTsiz, XTOsiz, YTOsiz
    // (4 bytes each), Csiz (2 bytes), then Ssiz of each component.
    constexpr std::size_t kSizFromMarker = 40 + 1; // through the first component's Ssiz
    const std::size_t searchEnd = std::min<std::size_t>(codestream.size(), 4096);
    for (std::size_t i = 0; i + 4 <= searchEnd; ++i) {
        const std::uint8_t* p = codestream.data() + i;
        if (p[0] != 0xFF || p[1] != 0x4F || p[2] != 0xFF || p[3] != 0x51)
            continue;
        const std::size_t siz = i + 2;
        if (codestream.size() - siz < kSizFromMarker)
            return std::nullopt;
        const std::uint8_t* s = codestream.data() + siz;
        const std::uint32_t xsiz = bigEndian32(s + 6), ysiz = bigEndian32(s + 10);
        const std::uint32_t xosiz = bigEndian32(s + 14), yosiz = bigEndian32(s + 18);
        Jpeg2000Size size;
        size.width = xsiz > xosiz ? xsiz - xosiz : 0;
        size.height = ysiz > yosiz ? ysiz - yosiz : 0;
        size.tiles = tilesAlong(xsiz, bigEndian32(s + 30), bigEndian32(s + 22)) *
                     tilesAlong(ysiz, bigEndian32(s + 34), bigEndian32(s + 26));
        size.components = int(s[38]) << 8 | int(s[39]);
        size.precision = int(s[40] & 0x7F) + 1;
        size.isSigned = (s[40] & 0x80) != 0;
        return size;
    }
    return std::nullopt;
}

void decodeJpeg2000(std::span<const std::uint8_t> codestream, const Jpeg2000Frame& frame,
                    std::span<std::byte> out, const std::string& subject) {
    const auto size = readJpeg2000Size(codestream);
    if (!size)
        throw core::Error(subject, "no JPEG 2000 image header (SIZ marker) in the pixel data");
    checkSizeAgainstHeader(*size, frame, subject);
    const std::size_t sampleBytes = frame.bitsAllocated == 16 ? 2 : 1;
    if (out.size() < std::size_t(frame.rows) * std::size_t(frame.columns) * sampleBytes)
        throw core::Error(subject, "JPEG 2000 output buffer too small"); // a caller's mistake

    std::string reason;
    CodecPtr codec(opj_create_decompress(isJp2File(codestream) ? OPJ_CODEC_JP2 : OPJ_CODEC_J2K));
    MemoryStream memory{codestream};
    StreamPtr stream = openMemoryStream(memory);
    if (!codec || !stream)
        throw core::Error(subject, "OpenJPEG could not start a decoder");
    opj_set_error_handler(codec.get(), keepFirstError, &reason);
    opj_set_warning_handler(codec.get(), ignoreMessage, nullptr);
    opj_set_info_handler(codec.get(), ignoreMessage, nullptr);
    opj_dparameters_t parameters;
    opj_set_default_decoder_parameters(&parameters);
    opj_image_t* rawImage = nullptr;
    const bool headerRead = opj_setup_decoder(codec.get(), &parameters) &&
                            opj_read_header(stream.get(), codec.get(), &rawImage);
    ImagePtr image(rawImage);
    if (!headerRead || !image || !opj_decode(codec.get(), stream.get(), image.get()) ||
        !opj_end_decompress(codec.get(), stream.get()))
        throw core::Error(subject, "damaged JPEG 2000 codestream" +
                                       (reason.empty() ? std::string() : ": " + reason));
    const opj_image_comp_t& component = decodedComponent(*image, frame, subject);
    if (sampleBytes == 2)
        storeSamples<std::uint16_t>(component, out);
    else
        storeSamples<std::uint8_t>(component, out);
}

} // namespace lw::dicom::detail
