// `linework-cli info PATH [--json]`: what a DICOM input or a volume file holds.
#include "arguments.h"
#include "commands.h"
#include "lw/core/error.h"
#include "lw/core/json_writer.h"
#include "lw/volume/volume_reader.h"

#ifdef LINEWORK_HAVE_DICOM
#include "lw/dicom/dicom_scanner.h"
#include "lw/dicom/volume_assembler.h"
#endif

#include <cstdlib>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace lw::cli {
namespace {

void printVolumeFile(const std::string& path, const volume::Volume& v, bool json,
                     std::ostream& out) {
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

// "512x512x28" -> dims; the raw reader cannot guess them.
glm::ivec3 parseDims(const std::string& text) {
    glm::ivec3 dims{0};
    std::istringstream in(text);
    char x1 = 0, x2 = 0;
    if (!(in >> dims.x >> x1 >> dims.y >> x2 >> dims.z) || (x1 != 'x' && x1 != 'X') ||
        (x2 != 'x' && x2 != 'X') || dims.x <= 0 || dims.y <= 0 || dims.z <= 0 || !in.eof())
        throw UsageError("--raw", "expected WxHxD with positive integers, got '" + text + "'");
    return dims;
}

glm::dvec3 parseSpacing(const std::string& text) {
    glm::dvec3 spacing{1.0};
    std::istringstream in(text);
    char c1 = 0, c2 = 0;
    if (!(in >> spacing.x >> c1 >> spacing.y >> c2 >> spacing.z) || c1 != ',' || c2 != ',' ||
        spacing.x <= 0 || spacing.y <= 0 || spacing.z <= 0)
        throw UsageError("--spacing", "expected X,Y,Z in mm (positive), got '" + text + "'");
    return spacing;
}

#ifdef LINEWORK_HAVE_DICOM

// Names for the transfer syntaxes seen in practice; people read these, scripts use the UID.
std::string transferSyntaxName(const std::string& uid) {
    static const std::pair<const char*, const char*> kNames[] = {
        {"1.2.840.10008.1.2", "Implicit VR Little Endian"},
        {"1.2.840.10008.1.2.1", "Explicit VR Little Endian"},
        {"1.2.840.10008.1.2.1.99", "Deflated Explicit VR Little Endian"},
        {"1.2.840.10008.1.2.2", "Explicit VR Big Endian"},
        {"1.2.840.10008.1.2.4.50", "JPEG Baseline (8-bit)"},
        {"1.2.840.10008.1.2.4.51", "JPEG Extended (12-bit)"},
        {"1.2.840.10008.1.2.4.57", "JPEG Lossless"},
        {"1.2.840.10008.1.2.4.70", "JPEG Lossless SV1"},
        {"1.2.840.10008.1.2.4.80", "JPEG-LS Lossless"},
        {"1.2.840.10008.1.2.4.81", "JPEG-LS Near-Lossless"},
        {"1.2.840.10008.1.2.4.90", "JPEG 2000 Lossless"},
        {"1.2.840.10008.1.2.4.91", "JPEG 2000"},
        {"1.2.840.10008.1.2.5", "RLE Lossless"},
    };
    for (const auto& [known, name] : kNames)
        if (uid == known)
            return name;
    return uid.empty() ? "none (no file meta: ACR-NEMA or raw data set)" : "unknown";
}

struct SeriesReport {
    const dicom::SeriesInfo* series = nullptr;
    dicom::SeriesAssembly assembly;
    std::string planError; // planVolumes itself failed
};

std::string optionalNumber(const std::optional<int>& number) {
    return number ? std::to_string(*number) : std::string("-");
}

void writeStrings(core::JsonWriter& w, std::string_view name,
                  const std::vector<std::string>& items) {
    w.key(name).beginArray();
    for (const auto& item : items)
        w.value(item);
    w.endArray();
}

void writeVolumeJson(core::JsonWriter& w, const dicom::VolumePlan& plan) {
    const auto spacing = plan.geometry.spacing();
    w.beginObject();
    w.field("label", plan.label);
    w.key("dims").beginArray().value(plan.dims.x).value(plan.dims.y).value(plan.dims.z).endArray();
    w.key("spacing").beginArray().value(spacing.x).value(spacing.y).value(spacing.z).endArray();
    w.field("slice_step_along_normal_mm", plan.geometry.sliceStepAlongNormal());
    w.field("voxel_type", std::string(volume::voxelTypeName(plan.voxelType)));
    w.key("rescale")
        .beginObject()
        .field("slope", plan.valueMapping.slope)
        .field("intercept", plan.valueMapping.intercept)
        .endObject();
    w.field("tilt_deg", plan.tiltDegrees);
    w.field("uneven_gaps", plan.unevenGaps);
    w.key("gaps_mm").beginArray().value(plan.minGap).value(plan.maxGap).endArray();
    w.field("missing_slices", plan.missingSlices);
    w.key("transfer_syntaxes").beginArray();
    for (const auto& uid : plan.transferSyntaxes)
        w.beginObject().field("uid", uid).field("name", transferSyntaxName(uid)).endObject();
    w.endArray();
    writeStrings(w, "warnings", plan.warnings);
    w.endObject();
}

void writeDicomJson(const std::string& path, const dicom::DicomIndex& index,
                    const std::vector<SeriesReport>& reports,
                    const std::vector<dicom::FileError>& errors, std::ostream& out) {
    core::JsonWriter w;
    w.beginObject();
    w.field("path", path).field("kind", "dicom");
    w.field("from_dicomdir", index.fromDicomdir);
    w.field("files_examined", index.filesExamined);
    w.field("series_count", index.seriesCount());
    w.field("instance_count", index.instanceCount());
    std::size_t next = 0; // reports follow allSeries() order, which is the tree order below
    w.key("patients").beginArray();
    for (const auto& patient : index.patients) {
        w.beginObject();
        w.field("patient_id", patient.patientId).field("name", patient.name);
        w.field("birth_date", patient.birthDate).field("sex", patient.sex);
        w.key("studies").beginArray();
        for (const auto& study : patient.studies) {
            w.beginObject();
            w.field("study_instance_uid", study.studyInstanceUid).field("study_id", study.studyId);
            w.field("description", study.description)
                .field("date", study.date)
                .field("time", study.time);
            w.field("accession_number", study.accessionNumber);
            w.key("series").beginArray();
            for (const auto& series : study.series) {
                const SeriesReport& report = reports[next++];
                w.beginObject();
                w.field("series_instance_uid", series.seriesInstanceUid);
                w.field("modality", series.modality).field("description", series.description);
                w.key("number");
                if (series.seriesNumber)
                    w.value(*series.seriesNumber);
                else
                    w.null();
                w.field("instances", series.instances.size());
                if (series.referencedFiles > 0) // read from a DICOMDIR
                    w.field("referenced_files", series.referencedFiles)
                        .field("missing_files", series.missingFiles);
                w.key("volumes").beginArray();
                for (const auto& plan : report.assembly.volumes)
                    writeVolumeJson(w, plan);
                w.endArray();
                auto warnings = report.assembly.warnings;
                if (!report.planError.empty())
                    warnings.push_back(report.planError);
                writeStrings(w, "warnings", warnings);
                w.endObject();
            }
            w.endArray();
            w.endObject();
        }
        w.endArray();
        w.endObject();
    }
    w.endArray();
    writeStrings(w, "warnings", index.warnings);
    w.key("errors").beginArray();
    for (const auto& error : errors)
        w.beginObject().field("file", error.file).field("reason", error.reason).endObject();
    w.endArray();
    w.endObject();
    out << w.str() << "\n";
}

void writeDicomText(const std::string& path, const dicom::DicomIndex& index,
                    const std::vector<SeriesReport>& reports,
                    const std::vector<dicom::FileError>& errors, std::ostream& out) {
    out << path << (index.fromDicomdir ? " (DICOMDIR)" : "") << ": " << index.filesExamined
        << " files examined, " << index.instanceCount() << " instances in " << index.seriesCount()
        << " series, " << errors.size() << " errors\n";
    std::size_t next = 0;
    for (const auto& patient : index.patients) {
        out << "patient " << (patient.name.empty() ? "(no name)" : patient.name) << "  id "
            << (patient.patientId.empty() ? "-" : patient.patientId) << "\n";
        for (const auto& study : patient.studies) {
            out << "  study " << study.studyInstanceUid << "  " << study.date << "  "
                << study.description << "\n";
            for (const auto& series : study.series) {
                const SeriesReport& report = reports[next++];
                out << "    series " << optionalNumber(series.seriesNumber) << "  "
                    << series.modality << "  '" << series.description << "'  "
                    << series.instances.size() << " instances";
                if (series.missingFiles > 0)
                    out << " (" << series.missingFiles << " of " << series.referencedFiles
                        << " files the DICOMDIR references are missing)";
                out << "\n      uid " << series.seriesInstanceUid << "\n";
                for (const auto& plan : report.assembly.volumes) {
                    const auto s = plan.geometry.spacing();
                    out << "      volume " << plan.dims.x << " x " << plan.dims.y << " x "
                        << plan.dims.z << "  " << volume::voxelTypeName(plan.voxelType)
                        << "  spacing " << s.x << " x " << s.y << " x " << s.z << " mm";
                    if (!plan.label.empty())
                        out << "  [" << plan.label << "]";
                    out << "\n";
                    if (plan.tiltDegrees > 0.01)
                        out << "        tilt " << std::fixed << std::setprecision(2)
                            << plan.tiltDegrees << std::defaultfloat << " deg\n";
                    if (plan.unevenGaps)
                        out << "        uneven gaps " << plan.minGap << " .. " << plan.maxGap
                            << " mm\n";
                    if (plan.missingSlices > 0)
                        out << "        missing slices " << plan.missingSlices << "\n";
                    for (const auto& uid : plan.transferSyntaxes)
                        out << "        transfer syntax " << transferSyntaxName(uid) << " (" << uid
                            << ")\n";
                    for (const auto& warning : plan.warnings)
                        out << "        warning: " << warning << "\n";
                }
                for (const auto& warning : report.assembly.warnings)
                    out << "      warning: " << warning << "\n";
                if (!report.planError.empty())
                    out << "      error: " << report.planError << "\n";
            }
        }
    }
    for (const auto& warning : index.warnings)
        out << "warning: " << warning << "\n";
    for (const auto& error : errors)
        out << "error: " << error.file << ": " << error.reason << "\n";
}

int runDicomInfo(const std::string& path, bool json, std::ostream& out) {
    const dicom::DicomIndex index = dicom::scanDicom(path);
    std::vector<SeriesReport> reports;
    std::vector<dicom::FileError> errors = index.errors;
    bool anyVolume = false;
    for (const auto* series : index.allSeries()) {
        SeriesReport report;
        report.series = series;
        try {
            report.assembly = dicom::planVolumes(*series);
        } catch (const core::Error& error) {
            // One series that cannot be planned must not hide the others.
            report.planError = error.what();
        }
        errors.insert(errors.end(), report.assembly.errors.begin(), report.assembly.errors.end());
        anyVolume = anyVolume || !report.assembly.volumes.empty();
        reports.push_back(std::move(report));
    }
    if (json)
        writeDicomJson(path, index, reports, errors, out);
    else
        writeDicomText(path, index, reports, errors, out);
    // 0 as long as something can be shown as a volume; per-file errors are reported, not fatal.
    return anyVolume ? 0 : 1;
}

#endif // LINEWORK_HAVE_DICOM

} // namespace

int runInfo(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {"json", "big-endian"}, {"raw", "type", "spacing"});
    if (arguments.positionals().size() != 1)
        throw UsageError("info", "expects exactly one PATH");
    const std::string path = arguments.positionals()[0];
    const bool json = arguments.flag("json");

    if (const auto raw = arguments.option("raw")) {
        volume::RawOptions options;
        options.dims = parseDims(*raw);
        const auto type = arguments.option("type");
        if (!type)
            throw UsageError("--raw", "needs --type (uint8, int16, uint16, float32)");
        options.type = parseUsage([&] { return volume::parseVoxelType(*type); });
        options.bigEndian = arguments.flag("big-endian");
        if (const auto spacing = arguments.option("spacing"))
            options.spacing = parseSpacing(*spacing);
        printVolumeFile(path, volume::readRawVolume(path, options), json, out);
        return 0;
    }

#ifdef LINEWORK_HAVE_DICOM
    // Folders, DICOMDIRs and DICOM files go to the scanner; so do files no volume reader claims,
    // because DICOM without preamble or suffix is only recognised by parsing it.
    if (dicom::looksLikeDicomInput(path))
        return runDicomInfo(path, json, out);
    if (volume::detectVolumeFormat(path) == volume::VolumeFormat::Unknown) {
        try {
            return runDicomInfo(path, json, out);
        } catch (const core::Error& error) {
            // Only a guess: say what was tried rather than just "not DICOM".
            throw core::Error(path,
                              "neither a known volume format (NRRD, NIfTI, PVM; raw data needs "
                              "--raw WxHxD --type T) nor readable DICOM (" +
                                  error.reason() + ")");
        }
    }
#endif
    const volume::Volume v = volume::readVolumeFile(path);
    printVolumeFile(path, v, json, out);
    return 0;
}

} // namespace lw::cli
