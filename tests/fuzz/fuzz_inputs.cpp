#include "fuzz_inputs.h"

#include "dicom_file.h"
#include "lw/core/error.h"
#include "lw/core/limits.h"
#include "lw/dicom/dicom_scanner.h"
#include "lw/dicom/volume_assembler.h"
#include "lw/volume/volume_reader.h"

#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace lw::fuzz {
namespace {

namespace fs = std::filesystem;

// Small enough that libFuzzer's 2 GB RSS limit is never the finding, large enough for every
// seed (the largest shared DICOM volume is 512x512x54 int16, 28 MB).
core::ImportLimits fuzzLimits() {
    core::ImportLimits limits;
    limits.maxBytes = std::size_t(256) << 20;
    limits.maxFrames = 4096;
    limits.maxDimension = 65536;
    return limits;
}

fs::path writeInput(Bytes data, const fs::path& path) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size()));
    return path;
}

// Runs `read`; core::Error (a bad file, reported) is the expected outcome of most inputs.
template <typename Read> void expectingErrors(Read&& read) {
    try {
        read();
    } catch (const core::Error&) {
    }
}

void loadEverySeries(const dicom::DicomIndex& index, const core::ImportLimits& limits) {
    for (const auto& patient : index.patients)
        for (const auto& study : patient.studies)
            for (const auto& series : study.series) {
                const dicom::SeriesAssembly assembly = dicom::planVolumes(series);
                for (const auto& plan : assembly.volumes)
                    expectingErrors(
                        [&] { (void)dicom::loadVolume(series, plan, nullptr, limits); });
            }
}

void decodeEveryFrame(const fs::path& path, const core::ImportLimits& limits) {
    const dicom::InstanceInfo info = dicom::readInstanceHeader(path, limits);
    const volume::VoxelType type = dicom::storedVoxelType(info);
    std::vector<std::byte> frame(std::size_t(info.rows) * std::size_t(info.columns) *
                                 volume::voxelSize(type));
    dicom::FrameDecoder decoder(info, limits);
    for (int f = 0; f < info.numberOfFrames; ++f)
        decoder.decodeFrame(f, type, frame.data());
}

// Removed when the process ends normally (libFuzzer's time limit ends in exit(), which runs
// static destructors); a crash leaves it for the OS's tmp cleaning, with the input in it.
struct ScratchFolder {
    fs::path path;
    ScratchFolder()
        : path(fs::temp_directory_path() / ("linework-fuzz-" + std::to_string(getpid()))) {
        fs::create_directories(path);
    }
    ~ScratchFolder() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

} // namespace

const fs::path& scratchFolder() {
    static const ScratchFolder folder;
    return folder.path;
}

const fs::path& fileSetRoot(const fs::path& sharedData) {
    static const fs::path root = [&] {
        const fs::path folder = scratchFolder() / "file-set";
        fs::create_directories(folder);
        const fs::path tree = sharedData / "dicom/dicomdir_pydicom_tiny_tree";
        std::error_code ec;
        if (fs::is_directory(tree, ec))
            fs::copy(tree, folder,
                     fs::copy_options::recursive | fs::copy_options::overwrite_existing, ec);
        fs::remove(folder / "DICOMDIR", ec);
        return folder;
    }();
    return root;
}

void importDicomFile(Bytes data) {
    const core::ImportLimits limits = fuzzLimits();
    const fs::path path = writeInput(data, scratchFolder() / "input.dcm");
    expectingErrors(
        [&] { loadEverySeries(dicom::scanDicomFiles({path}, nullptr, limits), limits); });
    expectingErrors([&] { decodeEveryFrame(path, limits); });
}

void importDicomdir(Bytes data, const fs::path& fileSetRoot) {
    const core::ImportLimits limits = fuzzLimits();
    const fs::path path = writeInput(data, fileSetRoot / "DICOMDIR");
    expectingErrors([&] { loadEverySeries(dicom::scanDicom(path, nullptr, limits), limits); });
}

void readNrrdFile(Bytes data) {
    const fs::path path = writeInput(data, scratchFolder() / "input.nrrd");
    expectingErrors([&] { (void)volume::readNrrd(path, fuzzLimits()); });
}

void readNiftiFile(Bytes data) {
    // The reader tells gzip by its magic, not by the name.
    const fs::path path = writeInput(data, scratchFolder() / "input.nii");
    expectingErrors([&] { (void)volume::readNifti(path, fuzzLimits()); });
}

void readPvmFile(Bytes data) {
    const fs::path path = writeInput(data, scratchFolder() / "input.pvm");
    expectingErrors([&] { (void)volume::readPvm(path, fuzzLimits()); });
}

bool runTarget(std::string_view target, Bytes data, const fs::path& fileSetRoot) {
    if (target == "dicom_file")
        importDicomFile(data);
    else if (target == "dicomdir")
        importDicomdir(data, fileSetRoot);
    else if (target == "nrrd")
        readNrrdFile(data);
    else if (target == "nifti")
        readNiftiFile(data);
    else if (target == "pvm")
        readPvmFile(data);
    else
        return false;
    return true;
}

} // namespace lw::fuzz
