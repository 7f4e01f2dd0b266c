#pragma once

// What an import may cost, in one place: every reader (DICOM, NRRD, NIfTI, PVM, raw, gzip)
// checks the sizes a header declares here BEFORE it allocates anything, so a 630-byte header
// claiming 2^31 frames or a gzip bomb is refused in milliseconds with the reason, instead of
// costing minutes and gigabytes first.

#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>

namespace lw::core {

// Patient positions and stack extents beyond this (10 m) are not a patient: the header is damaged.
inline constexpr double kMaxPlausibleExtentMm = 10000.0;

struct ImportLimits {
    // Largest allocation one import may make for one volume, one file's pixel data or one
    // decompressed stream. Default: half the physical memory (defaultMaxBytes()).
    std::size_t maxBytes = defaultMaxBytes();
    // Most frames one file or one volume may declare. Real enhanced multi-frame objects have
    // thousands; each declared frame costs bookkeeping before any pixel is read.
    std::size_t maxFrames = 100000;
    // Most voxels along one axis of a volume (NRRD, NIfTI, PVM, raw, DICOM rows and columns).
    std::size_t maxDimension = std::size_t(1) << 20;

    // How a user raises maxBytes, said with every refusal of a volume or mesh (the CLI:
    // "--max-volume-gib raises it"); empty: nothing is said.
    std::string raiseHint;

    // Half the physical memory (sysconf), computed once; 4 GiB where it cannot be determined.
    static std::size_t defaultMaxBytes();

    // "the limit of 11.7 GiB (half this machine's memory; --max-volume-gib raises it)".
    std::string describeLimit() const;
    // Throws Error(subject, "<what> (<shape>) = 8.0 GiB is more than the limit of ...") when
    // `bytes` is over maxBytes: what the volume and mesh paths call before they allocate.
    void checkAllocation(std::size_t bytes, std::string_view shape, const std::string& subject,
                         std::string_view what) const;
    // The bytes of an nx x ny x nz grid of `elementBytes`-byte `elementName` values, checked for
    // overflow and with checkAllocation ("the volume (1024×1024×4096 int16) = 8.0 GiB ...").
    std::size_t checkedVolumeBytes(std::size_t nx, std::size_t ny, std::size_t nz,
                                   std::size_t elementBytes, std::string_view elementName,
                                   const std::string& subject, std::string_view what) const;

    // Throws Error(subject, "<what> needs N MB, more than the import limit of M MB").
    void checkBytes(std::size_t bytes, const std::string& subject, std::string_view what) const;
    // The product of `factors` (dimensions x element size), checked for overflow and against
    // maxBytes; throws Error naming `subject` and `what` otherwise.
    std::size_t checkedBytes(std::initializer_list<std::size_t> factors, const std::string& subject,
                             std::string_view what) const;
    // Throws Error when a declared frame count is below 1 or above maxFrames.
    void checkFrames(long long frames, const std::string& subject) const;
    // Throws Error when a declared size along one axis is below 1 or above maxDimension.
    void checkDimension(long long size, const std::string& subject, std::string_view axis) const;
};

// The product of `factors`; throws Error(subject, "<what> overflows: a x b x c") when it does not
// fit in size_t (hostile headers multiply huge dimensions).
std::size_t checkedProduct(std::initializer_list<std::size_t> factors, const std::string& subject,
                           std::string_view what);

// "8.0 GiB", "512.0 MiB", "3.5 KiB" or "12 bytes" (binary units, one decimal).
std::string byteSizeText(std::size_t bytes);

// How much a stream may inflate to when its header says `expected` bytes: a little more, so a
// trailing pad or a rounding in the header is accepted but a bomb is stopped right after it.
std::size_t inflateBound(std::size_t expected);

} // namespace lw::core
