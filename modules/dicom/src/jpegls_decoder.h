#pragma once

// JPEG-LS (1.2.840.10008.1.2.4.80 / .81) frames decoded with the system CharLS 2 through its C
// API (charls_jpegls_decoder_*), several times faster than DCMTK 3.6.7's bundled CharLS. The
// library is opened at run time with RTLD_LOCAL (not linked), so its legacy JpegLsDecode never
// displaces DCMTK's copy of that symbol. Internal to lw_dicom; the tests include it directly.

#include <cstddef>
#include <cstdint>
#include <string>

namespace lw::dicom::jpegls {

// True when lw_dicom was built with CharLS (LINEWORK_HAVE_CHARLS); otherwise decodeFrame always
// fails and FrameDecoder uses DCMTK / GDCM.
bool available();

// Decodes one single-component JPEG-LS codestream of `rows` x `columns` samples into
// `destination` (rows * columns samples of bitsAllocated (8 or 16) bits, host order). Each call
// owns its decoder: safe to call from several threads. Returns an empty string on success,
// otherwise why it failed (nothing useful is in `destination` then).
std::string decodeFrame(const std::uint8_t* data, std::size_t size, int rows, int columns, int bitsAllocated,
                        void* destination);

// Frames decoded successfully by decodeFrame since the process started (all threads): lets
// tests check which path handled a file.
std::uint64_t framesDecoded();

} // namespace lw::dicom::jpegls
