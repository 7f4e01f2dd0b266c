#pragma once

// Internal to lw::dicom: small DCMTK helpers shared by the reader and the decoder. DCMTK types
// may appear here because this header never leaves modules/dicom/src.

#include "lw/core/limits.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcitem.h>
#include <dcmtk/dcmdata/dcmetinf.h>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lw::dicom {

// What loading learnt beyond the data set DCMTK holds.
struct LoadedDicom {
    bool isGzipWrapped = false;
    // Deflated header reads stop in front of the pixel data (see deflated_dataset.h): whether it
    // is there and the length it declares.
    bool pixelDataSkipped = false;
    std::optional<std::uint64_t> skippedPixelDataLength;
};

// Loads a DICOM file, or the DICOM file inside a gzip wrapper (then `inflated`, when given,
// keeps the bytes). headerOnly: large elements (pixel data) stay on disk until accessed; a
// deflated data set is inflated only up to its pixel data. A full load of a deflated data set
// inflates at most what `expectedPixelBytes` (the header's declaration) allows.
// Throws core::Error(path, reason) when the file is not DICOM or cannot be parsed, or when a
// gzip wrapper or a deflated data set inflates past limits.maxBytes.
LoadedDicom loadDicomFile(const std::filesystem::path& path, DcmFileFormat& file, bool headerOnly,
                          std::vector<std::byte>* inflated, const core::ImportLimits& limits,
                          std::optional<std::size_t> expectedPixelBytes = std::nullopt);

// Leading and trailing spaces and NULs removed (DICOM pads values to even length).
inline std::string trim(const std::string& text) {
    static const std::string blanks(" \t\r\n\0", 5);
    const auto first = text.find_first_not_of(blanks);
    if (first == std::string::npos)
        return {};
    const auto last = text.find_last_not_of(blanks);
    return text.substr(first, last - first + 1);
}

// Element access that never throws: a missing or malformed value is "absent".
inline std::string getString(DcmItem& item, const DcmTagKey& key) {
    OFString value;
    if (item.findAndGetOFStringArray(key, value, OFFalse).bad())
        return {};
    return trim(std::string(value.c_str(), value.length()));
}

inline std::optional<double> getDouble(DcmItem& item, const DcmTagKey& key, unsigned long pos = 0) {
    Float64 value = 0.0;
    if (item.findAndGetFloat64(key, value, pos, OFFalse).bad() || !std::isfinite(value))
        return std::nullopt;
    return value;
}

inline std::optional<std::vector<double>> getDoubles(DcmItem& item, const DcmTagKey& key, unsigned long count) {
    std::vector<double> values(count);
    for (unsigned long i = 0; i < count; ++i) {
        auto value = getDouble(item, key, i);
        if (!value)
            return std::nullopt;
        values[i] = *value;
    }
    return values;
}

inline std::optional<int> getInt(DcmItem& item, const DcmTagKey& key) {
    Sint32 value = 0;
    if (item.findAndGetSint32(key, value, 0, OFFalse).good())
        return int(value);
    // IS values with stray characters, or integers stored as DS/US: try the generic routes.
    Uint16 u16 = 0;
    if (item.findAndGetUint16(key, u16, 0, OFFalse).good())
        return int(u16);
    return std::nullopt;
}

inline std::optional<int> getUnsigned(DcmItem& item, const DcmTagKey& key) {
    Uint16 value = 0;
    if (item.findAndGetUint16(key, value, 0, OFFalse).good())
        return int(value);
    Sint32 s32 = 0;
    if (item.findAndGetSint32(key, s32, 0, OFFalse).good())
        return int(s32);
    return std::nullopt;
}

inline DcmItem* firstItem(DcmItem& item, const DcmTagKey& sequence) {
    DcmItem* found = nullptr;
    if (item.findAndGetSequenceItem(sequence, found, 0, OFFalse).bad())
        return nullptr;
    return found;
}

inline std::array<double, 6> toOrientation(const std::vector<double>& values) {
    std::array<double, 6> result{};
    for (std::size_t i = 0; i < 6; ++i)
        result[i] = values[i];
    return result;
}

} // namespace lw::dicom
