#pragma once

// Internal to lw::dicom: one JPEG 2000 frame decoded with OpenJPEG straight from the bytes of
// its encapsulated fragments. Nothing re-parses the DICOM file (GDCM, which did, asserts on
// damaged data sets and aborts the process), and every call has its own codec, so frames decode
// in parallel without a lock.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace lw::dicom::detail {

// What the SIZ marker of a codestream declares (ISO 15444-1 A.5.1).
struct Jpeg2000Size {
    std::uint32_t width = 0;  // Xsiz - XOsiz
    std::uint32_t height = 0; // Ysiz - YOsiz
    std::uint64_t tiles = 0;
    int components = 0;
    int precision = 0; // of the first component, in bits
    bool isSigned = false;
};

// The SIZ marker of a raw codestream or of one inside a JP2 box (searched in the first 4 KiB).
// nullopt when there is none or it is cut short.
std::optional<Jpeg2000Size> readJpeg2000Size(std::span<const std::uint8_t> codestream);

// The frame the DICOM header describes: the codestream must match it.
struct Jpeg2000Frame {
    int rows = 0;
    int columns = 0;
    int bitsAllocated = 0; // 8 or 16: the width of one output sample
};

// Decodes `codestream` into rows x columns samples of bitsAllocated bits (host order) at
// `out`, each the component's value in two's complement truncated to the sample width, the
// same layout as native pixel data. The SIZ marker is checked against `frame` before OpenJPEG
// allocates anything. Throws core::Error(subject, reason) when the codestream is damaged or
// does not match the header.
void decodeJpeg2000(std::span<const std::uint8_t> codestream, const Jpeg2000Frame& frame,
                    std::span<std::byte> out, const std::string& subject);

} // namespace lw::dicom::detail
