// `linework-cli info PATH [--json]`: what a DICOM input or a volume file holds.
#include "arguments.h"
#include "commands.h"

#include "lw/core/error.h"
#include "lw/core/json_writer.h"
#include "lw/volume/volume_reader.h"

#include <ostream>

namespace lw::cli {
namespace {

void printVolumeFile(const std::string& path, const volume::Volume& v, bool json, std::ostream& out) {
    const auto range = v.realRange();
    const auto spacing = v.geometry().spacing();
    if (json) {
        core::JsonWriter w;
        w.beginObject();
        w.field("path", path).field("kind", "volume");
        w.key("dims").beginArray().value(v.dims().x).value(v.dims().y).value(v.dims().z).endArray();
        w.field("voxel_type", std::string(volume::voxelTypeName(v.voxelType())));
        w.key("spacing").beginArray().value(spacing.x).value(spacing.y).value(spacing.z).endArray();
        w.key("value_range").beginArray().value(range.min).value(range.max).endArray();
        w.field("tilt_deg", v.geometry().tiltDegrees());
        w.endObject();
        out << w.str() << "\n";
        return;
    }
    out << path << "\n"
        << "  dims        " << v.dims().x << " x " << v.dims().y << " x " << v.dims().z << "\n"
        << "  voxel type  " << volume::voxelTypeName(v.voxelType()) << "\n"
        << "  spacing     " << spacing.x << " x " << spacing.y << " x " << spacing.z << " mm\n"
        << "  values      " << range.min << " .. " << range.max << "\n";
}

} // namespace

int runInfo(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {"json", "big-endian"}, {"raw", "type", "spacing"});
    if (arguments.positionals().size() != 1)
        throw core::Error("info", "expects exactly one PATH");
    const std::string path = arguments.positionals()[0];
    const volume::Volume v = volume::readVolumeFile(path);
    printVolumeFile(path, v, arguments.flag("json"), out);
    return 0;
}

} // namespace lw::cli
