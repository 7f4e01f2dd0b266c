#include "lw/core/limits.h"

#include "lw/core/error.h"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <limits>
#include <unistd.h>

namespace lw::core {

namespace {

std::string megabytes(std::size_t bytes) {
    const std::size_t mb = bytes / (1024 * 1024);
    return mb > 0 ? std::to_string(mb) + " MB" : std::to_string(bytes) + " bytes";
}

std::size_t physicalMemory() {
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long pageSize = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0)
        return 0;
    if (std::size_t(pages) > std::numeric_limits<std::size_t>::max() / std::size_t(pageSize))
        return std::numeric_limits<std::size_t>::max();
    return std::size_t(pages) * std::size_t(pageSize);
}

} // namespace

std::size_t ImportLimits::defaultMaxBytes() {
    // Immutable once computed: the machine's memory does not change under a running process.
    static const std::size_t value = [] {
        const std::size_t physical = physicalMemory();
        return physical > 0 ? physical / 2 : std::size_t(4) << 30;
    }();
    return value;
}

void ImportLimits::checkBytes(std::size_t bytes, const std::string& subject,
                              std::string_view what) const {
    if (bytes > maxBytes)
        throw Error(subject, std::string(what) + " needs " + megabytes(bytes) +
                                 ", more than the import limit of " + megabytes(maxBytes));
}

std::size_t ImportLimits::checkedBytes(std::initializer_list<std::size_t> factors,
                                       const std::string& subject, std::string_view what) const {
    const std::size_t bytes = checkedProduct(factors, subject, what);
    checkBytes(bytes, subject, what);
    return bytes;
}

std::string ImportLimits::describeLimit() const {
    std::string origin = maxBytes == defaultMaxBytes() ? "half this machine's memory" : "as set";
    if (!raiseHint.empty())
        origin += "; " + raiseHint;
    return "the limit of " + byteSizeText(maxBytes) + " (" + origin + ")";
}

void ImportLimits::checkAllocation(std::size_t bytes, std::string_view shape,
                                   const std::string& subject, std::string_view what) const {
    if (bytes > maxBytes)
        throw Error(subject, std::string(what) + " (" + std::string(shape) +
                                 ") = " + byteSizeText(bytes) + " is more than " + describeLimit());
}

std::size_t ImportLimits::checkedVolumeBytes(std::size_t nx, std::size_t ny, std::size_t nz,
                                             std::size_t elementBytes, std::string_view elementName,
                                             const std::string& subject,
                                             std::string_view what) const {
    const std::size_t bytes = checkedProduct({nx, ny, nz, elementBytes}, subject, what);
    const std::string shape = std::to_string(nx) + "×" + std::to_string(ny) + "×" +
                              std::to_string(nz) + " " + std::string(elementName);
    checkAllocation(bytes, shape, subject, what);
    return bytes;
}

void ImportLimits::checkFrames(long long frames, const std::string& subject) const {
    if (frames < 1 || static_cast<unsigned long long>(frames) > maxFrames)
        throw Error(subject, "implausible number of frames " + std::to_string(frames) + " (1 to " +
                                 std::to_string(maxFrames) + " are accepted)");
}

void ImportLimits::checkDimension(long long size, const std::string& subject,
                                  std::string_view axis) const {
    if (size < 1 || static_cast<unsigned long long>(size) > maxDimension)
        throw Error(subject, "implausible " + std::string(axis) + " " + std::to_string(size) +
                                 " (1 to " + std::to_string(maxDimension) + " are accepted)");
}

std::size_t checkedProduct(std::initializer_list<std::size_t> factors, const std::string& subject,
                           std::string_view what) {
    std::size_t product = 1;
    bool overflow = false;
    for (std::size_t factor : factors)
        overflow = overflow || __builtin_mul_overflow(product, factor, &product);
    if (!overflow)
        return product;
    std::string shape;
    for (std::size_t factor : factors)
        shape += (shape.empty() ? "" : " x ") + std::to_string(factor);
    throw Error(subject, std::string(what) + " overflows: " + shape);
}

std::string byteSizeText(std::size_t bytes) {
    static constexpr const char* kUnits[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    if (bytes < 1024)
        return std::to_string(bytes) + " bytes";
    double value = double(bytes) / 1024.0;
    std::size_t unit = 0;
    while (value >= 1024.0 && unit + 1 < std::size(kUnits)) {
        value /= 1024.0;
        ++unit;
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.1f %s", value, kUnits[unit]);
    return text;
}

std::size_t inflateBound(std::size_t expected) {
    // 1 MiB or 1/64 more, whichever is larger, saturating.
    const std::size_t margin = std::max<std::size_t>(std::size_t(1) << 20, expected / 64);
    return expected > std::numeric_limits<std::size_t>::max() - margin
               ? std::numeric_limits<std::size_t>::max()
               : expected + margin;
}

} // namespace lw::core
