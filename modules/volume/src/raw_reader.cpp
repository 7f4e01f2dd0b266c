#include "lw/core/file_util.h"
#include "lw/volume/volume_reader.h"
#include "reader_util.h"

#include <limits>

namespace lw::volume {
namespace {

Volume readRawUnguarded(const std::filesystem::path& path, const RawOptions& options,
                        const core::ImportLimits& limits) {
    using detail::fail;
    const std::size_t size = voxelSize(options.type);
    const auto expected =
        std::optional(detail::checkVolumeSize(path, options.dims, size, options.type, limits));
    if (!(options.spacing.x > 0.0 && options.spacing.y > 0.0 && options.spacing.z > 0.0))
        fail(path, "raw spacing must be positive");
    if (options.headerBytes > std::numeric_limits<std::size_t>::max() - *expected)
        fail(path, "raw header size is too large");
    // The size on disk first: a wrong -raw size must not read a large file to find out.
    std::error_code ec;
    const auto onDisk = std::filesystem::file_size(path, ec);
    if (!ec && onDisk != options.headerBytes + *expected)
        fail(path, "file has " + std::to_string(onDisk) + " bytes, expected " +
                       std::to_string(options.headerBytes + *expected) + " for " +
                       detail::describeShape(options.dims, options.type));
    const std::vector<std::byte> bytes = core::readFileBytes(path);
    // Exact size: a mismatch almost always means wrong dims or type, and silently reading a
    // prefix would hide that.
    if (bytes.size() != options.headerBytes + *expected)
        fail(path, "file has " + std::to_string(bytes.size()) + " bytes, expected " +
                       std::to_string(options.headerBytes + *expected) + " for " +
                       detail::describeShape(options.dims, options.type) +
                       (options.headerBytes
                            ? " after a " + std::to_string(options.headerBytes) + "-byte header"
                            : std::string()));
    Volume volume(options.dims, options.type,
                  VolumeGeometry::regular(glm::dvec3(0.0), options.spacing));
    detail::fillVolume(volume, bytes.data() + options.headerBytes, options.bigEndian);
    return volume;
}

} // namespace

Volume readRawVolume(const std::filesystem::path& path, const RawOptions& options,
                     const core::ImportLimits& limits) {
    return core::atModuleBoundary(path.string(),
                                  [&] { return readRawUnguarded(path, options, limits); });
}

} // namespace lw::volume
