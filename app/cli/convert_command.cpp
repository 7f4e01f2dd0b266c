// `linework-cli convert`: any INPUT `render` reads (a DICOM folder, DICOMDIR or file, a volume
// file, a phantom spec) written as an NRRD file, for the commands and tools that read files only
// (`bench --input`, older builds of linework-cli, other programs).
#include "arguments.h"
#include "cli_inputs.h"
#include "commands.h"
#include "lw/volume/volume_reader.h"

#include <ostream>

namespace lw::cli {

int runConvert(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {}, {"series", kMaxVolumeOption});
    const auto output = arguments.option("output");
    if (arguments.positionals().size() != 1 || !output)
        throw UsageError("convert", "expects exactly one INPUT and -o OUT.nrrd");
    const std::string& input = arguments.positionals()[0];
    const std::string suffix = ".nrrd";
    if (output->size() <= suffix.size() ||
        output->compare(output->size() - suffix.size(), suffix.size(), suffix) != 0)
        throw UsageError("-o " + *output, "writes NRRD only: expected a name ending in .nrrd");
    const volume::Volume volume =
        loadInput(input, arguments.option("series"), importLimits(arguments));
    volume::writeNrrd(*output, volume);
    // NRRD holds one slice step: uneven gaps become their mean (a gantry tilt is kept).
    out << "wrote " << *output << " (" << dimsText(volume.dims())
        << (volume.geometry().hasUniformSlices() ? "" : ", uneven slice gaps as their mean step")
        << ")\n";
    return 0;
}

} // namespace lw::cli
