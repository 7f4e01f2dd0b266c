#pragma once

// Internal to lw::dicom: Deflated Explicit VR Little Endian (1.2.840.10008.1.2.1.99) read with
// bounded memory. DCMTK inflates such a data set while it parses and, since an inflating stream
// cannot be re-opened later, loads every value into memory: a 4 MB file declaring 4 GiB of
// pixels cost 19 s and 4.2 GB just to read its header. Here the data set is inflated with zlib
// under a bound and DCMTK parses the inflated bytes from memory.

#include "lw/core/limits.h"

#include <cstddef>
#include <cstdint>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <optional>
#include <string>
#include <vector>

namespace lw::dicom {

// What a deflated read learnt beyond the data set DCMTK holds.
struct DeflatedRead {
    // Header reads stop in front of the pixel data; its presence and declared length come from
    // the element header where parsing stopped.
    bool pixelDataSkipped = false;
    std::optional<std::uint64_t> pixelDataLength;
};

// Reads `fileBytes` (a whole DICOM file, gzip wrapper removed) into `file` when its meta group
// names the deflated transfer syntax; std::nullopt (and `file` unspecified) otherwise.
// headerOnly: the data set is inflated only up to the pixel data, at most limits.maxBytes.
// Otherwise the whole data set is inflated, at most the header's share plus
// core::inflateBound(expectedPixelBytes) when that is given (else limits.maxBytes).
// Throws core::Error(subject, reason) for a corrupt stream or one inflating past its bound.
std::optional<DeflatedRead> readIfDeflated(const std::vector<std::byte>& fileBytes,
                                           DcmFileFormat& file, bool headerOnly,
                                           std::optional<std::size_t> expectedPixelBytes,
                                           const std::string& subject,
                                           const core::ImportLimits& limits);

// Cheap test on a file on disk: its meta group names the deflated transfer syntax.
bool isDeflatedFile(const std::string& path);

} // namespace lw::dicom
