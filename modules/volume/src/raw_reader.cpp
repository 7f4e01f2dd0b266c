#include "lw/core/file_util.h"
#include "lw/volume/volume_reader.h"
#include "reader_util.h"

#include <limits>

namespace lw::volume {

Volume readRawVolume(const std::filesystem::path& path, const RawOptions& options) {
    using detail::fail;
    const auto expected = detail::checkedByteCount(options.dims, voxelSize(options.type));
    if (!expected)
        fail(path, "invalid raw dimensions " + detail::describeShape(options.dims, options.type));
    if (!(options.spacing.x > 0.0 && options.spacing.y > 0.0 && options.spacing.z > 0.0))
        fail(path, "raw spacing must be positive");
    if (options.headerBytes > std::numeric_limits<std::size_t>::max() - *expected)
        fail(path, "raw header size is too large");
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

} // namespace lw::volume
