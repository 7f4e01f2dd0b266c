#include "jpegls_decoder.h"

#include <atomic>
#include <cstring>
#include <memory>
#include <type_traits>
#include <vector>

#ifdef LINEWORK_HAVE_CHARLS
#include <charls/charls.h>
#include <dlfcn.h>
#endif

namespace lw::dicom::jpegls {

namespace {
std::atomic<std::uint64_t> g_framesDecoded{0};
} // namespace

std::uint64_t framesDecoded() { return g_framesDecoded.load(std::memory_order_relaxed); }

#ifdef LINEWORK_HAVE_CHARLS

namespace {

constexpr charls_jpegls_errc kSuccess = charls::jpegls_errc::success; // C++ view of the C enum

// The C API, from the system library opened with RTLD_LOCAL: its legacy JpegLsDecode never
// enters the global scope, so DCMTK keeps binding to its own copy (see frame_decoder.cpp).
// Where GDCM has loaded the same library already, dlopen returns that one.
struct CharlsApi {
    decltype(&charls_jpegls_decoder_create) create = nullptr;
    decltype(&charls_jpegls_decoder_destroy) destroy = nullptr;
    decltype(&charls_jpegls_decoder_set_source_buffer) setSourceBuffer = nullptr;
    decltype(&charls_jpegls_decoder_read_header) readHeader = nullptr;
    decltype(&charls_jpegls_decoder_get_frame_info) getFrameInfo = nullptr;
    decltype(&charls_jpegls_decoder_get_destination_size) getDestinationSize = nullptr;
    decltype(&charls_jpegls_decoder_decode_to_buffer) decodeToBuffer = nullptr;
    decltype(&charls_get_error_message) errorMessage = nullptr;
    bool ok = false;
};

const CharlsApi& charlsApi() {
    static const CharlsApi api = [] {
        CharlsApi a;
        void* library = dlopen(LINEWORK_CHARLS_SONAME, RTLD_NOW | RTLD_LOCAL);
        if (!library)
            return a;
        auto load = [library](auto& function, const char* name) {
            function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(dlsym(library, name));
            return function != nullptr;
        };
        a.ok = load(a.create, "charls_jpegls_decoder_create") && load(a.destroy, "charls_jpegls_decoder_destroy") &&
               load(a.setSourceBuffer, "charls_jpegls_decoder_set_source_buffer") &&
               load(a.readHeader, "charls_jpegls_decoder_read_header") &&
               load(a.getFrameInfo, "charls_jpegls_decoder_get_frame_info") &&
               load(a.getDestinationSize, "charls_jpegls_decoder_get_destination_size") &&
               load(a.decodeToBuffer, "charls_jpegls_decoder_decode_to_buffer") &&
               load(a.errorMessage, "charls_get_error_message");
        return a; // the library stays loaded for the process's lifetime
    }();
    return api;
}

} // namespace

bool available() { return charlsApi().ok; }

std::string decodeFrame(const std::uint8_t* data, std::size_t size, int rows, int columns, int bitsAllocated,
                        void* destination) {
    if (!data || size == 0)
        return "empty JPEG-LS codestream";
    const CharlsApi& api = charlsApi();
    if (!api.ok)
        return "the system CharLS (" LINEWORK_CHARLS_SONAME ") cannot be loaded";
    if (bitsAllocated != 8 && bitsAllocated != 16)
        return "unsupported BitsAllocated " + std::to_string(bitsAllocated);
    auto destroy = [&api](charls_jpegls_decoder* d) { api.destroy(d); };
    std::unique_ptr<charls_jpegls_decoder, decltype(destroy)> decoder(api.create(), destroy);
    if (!decoder)
        return "cannot create a CharLS decoder";
    auto failed = [&api](const char* step, charls_jpegls_errc code) {
        return std::string("CharLS ") + step + ": " + api.errorMessage(code);
    };
    charls_jpegls_errc code = api.setSourceBuffer(decoder.get(), data, size);
    if (code != kSuccess)
        return failed("set_source_buffer", code);
    if ((code = api.readHeader(decoder.get())) != kSuccess)
        return failed("read_header", code);
    charls_frame_info frame{};
    if ((code = api.getFrameInfo(decoder.get(), &frame)) != kSuccess)
        return failed("get_frame_info", code);
    if (frame.component_count != 1)
        return std::to_string(frame.component_count) + " components in the codestream, 1 expected";
    if (frame.width != std::uint32_t(columns) || frame.height != std::uint32_t(rows))
        return "codestream is " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
               ", the header says " + std::to_string(columns) + "x" + std::to_string(rows);
    if (frame.bits_per_sample < 2 || frame.bits_per_sample > bitsAllocated)
        return "codestream precision " + std::to_string(frame.bits_per_sample) + " does not fit BitsAllocated " +
               std::to_string(bitsAllocated);
    std::size_t needed = 0;
    if ((code = api.getDestinationSize(decoder.get(), 0, &needed)) != kSuccess)
        return failed("get_destination_size", code);
    const std::size_t pixels = std::size_t(rows) * std::size_t(columns);
    const std::size_t sampleBytes = frame.bits_per_sample > 8 ? 2 : 1; // CharLS's output sample size
    if (needed != pixels * sampleBytes)
        return "CharLS wants " + std::to_string(needed) + " bytes for " + std::to_string(pixels) + " samples";

    if (sampleBytes == std::size_t(bitsAllocated / 8)) {
        // CharLS writes 16-bit samples in host order, as the native path expects.
        code = api.decodeToBuffer(decoder.get(), destination, needed, 0);
        if (code != kSuccess)
            return failed("decode_to_buffer", code);
    } else {
        // A precision of 8 bits or less in 16-bit samples: CharLS writes bytes, widen them.
        std::vector<std::uint8_t> narrow(needed);
        code = api.decodeToBuffer(decoder.get(), narrow.data(), needed, 0);
        if (code != kSuccess)
            return failed("decode_to_buffer", code);
        auto* out = static_cast<std::uint16_t*>(destination);
        for (std::size_t i = 0; i < pixels; ++i)
            out[i] = narrow[i];
    }
    g_framesDecoded.fetch_add(1, std::memory_order_relaxed);
    return {};
}

#else

bool available() { return false; }

std::string decodeFrame(const std::uint8_t*, std::size_t, int, int, int, void*) {
    return "this build has no CharLS";
}

#endif

} // namespace lw::dicom::jpegls
