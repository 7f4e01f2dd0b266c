// Scanner, planner and loader on the shared third-party data (SOURCES.md says what each folder
// holds; the expected numbers below come from there).
#include "lw/core/error.h"
#include "lw/dicom/dicom_scanner.h"
#include "lw/dicom/volume_assembler.h"
#include "test_support.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <gtest/gtest.h>
#include <set>

namespace fs = std::filesystem;
using namespace lw;

namespace {

fs::path dataDir() {
    const auto dir = test::sharedDataDir();
    if (!dir)
        throw std::runtime_error("shared data missing (the data main should have skipped)");
    return *dir;
}

std::size_t countReason(const dicom::DicomIndex& index, const std::string& reason) {
    return std::size_t(
        std::count_if(index.errors.begin(), index.errors.end(),
                      [&](const dicom::FileError& e) { return e.reason == reason; }));
}

std::size_t studyCount(const dicom::DicomIndex& index) {
    std::size_t count = 0;
    for (const auto& p : index.patients)
        count += p.studies.size();
    return count;
}

const std::string kMissing = "referenced by DICOMDIR but missing";

// All volume plans of every series in `dir` (folder scan).
std::vector<dicom::VolumePlan> plansOf(const fs::path& dir,
                                       std::vector<std::string>* warnings = nullptr) {
    const dicom::DicomIndex index = dicom::scanDicom(dir);
    std::vector<dicom::VolumePlan> plans;
    for (const auto* series : index.allSeries()) {
        auto assembly = dicom::planVolumes(*series);
        for (auto& plan : assembly.volumes) {
            if (warnings)
                warnings->insert(warnings->end(), plan.warnings.begin(), plan.warnings.end());
            plans.push_back(std::move(plan));
        }
        if (warnings)
            warnings->insert(warnings->end(), assembly.warnings.begin(), assembly.warnings.end());
    }
    return plans;
}

} // namespace

TEST(DicomScannerData, PhilipsExportRootDicomdir) {
    const auto index =
        dicom::scanDicom(dataDir() / "dicom/ct_headphantom_philips_dicomdir_export/DICOMDIR");
    EXPECT_TRUE(index.fromDicomdir);
    EXPECT_EQ(countReason(index, kMissing), 338u);
    EXPECT_EQ(index.errors.size(), 338u);
    EXPECT_EQ(index.instanceCount(), 95u);
    EXPECT_EQ(studyCount(index), 2u);
    // 9 series listed; the held-back S2020, S2030 and S3010 have no file at all: they are
    // listed from the DICOMDIR's records, with no instances and all their files missing.
    EXPECT_EQ(index.seriesCount(), 9u);
    std::size_t emptySeries = 0, missingFiles = 0;
    for (const auto* series : index.allSeries()) {
        missingFiles += series->missingFiles;
        EXPECT_EQ(series->referencedFiles, series->instances.size() + series->missingFiles)
            << series->seriesInstanceUid;
        if (series->instances.empty()) {
            ++emptySeries;
            EXPECT_EQ(series->missingFiles, series->referencedFiles);
            EXPECT_EQ(series->modality, "CT");
        }
    }
    EXPECT_EQ(emptySeries, 3u);
    EXPECT_EQ(missingFiles, 338u);
    EXPECT_TRUE(std::any_of(index.warnings.begin(), index.warnings.end(), [](const std::string& w) {
        return w.find("lists 9 series; 3 of them") != std::string::npos;
    }));
}

TEST(DicomScannerData, PhilipsNestedDirfilesAreFollowed) {
    // DICOM/DICOMDIR references only the per-study DIRFILEs, which reference per-series ones.
    const auto index =
        dicom::scanDicom(dataDir() / "dicom/ct_headphantom_philips_dicomdir_export/DICOM/DICOMDIR");
    EXPECT_EQ(index.instanceCount(), 95u);
    EXPECT_EQ(studyCount(index), 2u);
    // The held-back series' DIRFILEs are missing, nothing else.
    EXPECT_EQ(countReason(index, kMissing), index.errors.size());
    EXPECT_EQ(index.errors.size(), 3u);
}

TEST(DicomScannerData, PydicomTinyTree) {
    const auto index = dicom::scanDicom(dataDir() / "dicom/dicomdir_pydicom_tiny_tree/DICOMDIR");
    EXPECT_EQ(index.instanceCount(), 31u);
    EXPECT_EQ(index.seriesCount(), 13u);
    EXPECT_EQ(studyCount(index), 6u);
    EXPECT_EQ(index.patients.size(), 2u);
    EXPECT_TRUE(index.errors.empty())
        << index.errors.front().file << ": " << index.errors.front().reason;
}

TEST(DicomScannerData, TinyAlphaWithoutPixelDataIsReportedNotLoaded) {
    const auto index =
        dicom::scanDicom(dataDir() / "dicom/dicomdir_pydicom_tiny_tree/TINY_ALPHA/DICOMDIR");
    EXPECT_EQ(index.instanceCount(), 50u);
    ASSERT_EQ(index.seriesCount(), 1u);
    const auto assembly = dicom::planVolumes(*index.allSeries()[0]);
    EXPECT_TRUE(assembly.volumes.empty());
    EXPECT_FALSE(assembly.warnings.empty() && assembly.errors.empty())
        << "a series without pixel data must say so";
}

TEST(DicomScannerData, DicomdirVariantsGiveAResultOrAClearError) {
    const fs::path dir = dataDir() / "dicom-odd/dicomdir_variants_pydicom";
    std::size_t checked = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        SCOPED_TRACE(entry.path().string());
        ++checked;
        dicom::DicomIndex index;
        try {
            index = dicom::scanDicom(entry.path());
        } catch (const core::Error& error) {
            EXPECT_FALSE(error.subject().empty());
            EXPECT_FALSE(error.reason().empty());
            continue;
        }
        EXPECT_TRUE(index.fromDicomdir);
        // The images live in dicom/dicomdir_pydicom_tiny_tree, not next to these files.
        EXPECT_EQ(index.instanceCount(), 0u);
        if (entry.path().filename() == "DICOMDIR-empty.dcm") {
            EXPECT_TRUE(index.errors.empty());
        } else {
            EXPECT_EQ(countReason(index, kMissing), 31u);
        }
    }
    EXPECT_EQ(checked, 6u);
}

TEST(DicomScannerData, SeriesDefectsDicom2nifti) {
    const fs::path dir = dataDir() / "dicom-odd/series_defects_dicom2nifti";

    const auto tilt = plansOf(dir / "gantrytilting");
    ASSERT_EQ(tilt.size(), 1u);
    EXPECT_GT(tilt[0].tiltDegrees, 5.0);

    std::vector<std::string> warnings;
    const auto notVolume = plansOf(dir / "notavolume", &warnings);
    EXPECT_FALSE(warnings.empty()) << "4 slices at one position must be flagged";

    const auto increment = plansOf(dir / "sliceincrement");
    ASSERT_FALSE(increment.empty());
    EXPECT_TRUE(increment[0].unevenGaps || increment[0].missingSlices > 0);

    const auto orientation = plansOf(dir / "sliceorientation");
    EXPECT_EQ(orientation.size(), 2u);
}

TEST(DicomScannerData, GeHeadTiltVariableSpacing) {
    const auto plans = plansOf(dataDir() / "dicom/ct_head_ge_hispeed_tilt_varspacing");
    ASSERT_EQ(plans.size(), 1u);
    EXPECT_EQ(plans[0].dims, glm::ivec3(512, 512, 28));
    EXPECT_NEAR(plans[0].tiltDegrees, 18.5, 0.3);
    EXPECT_TRUE(plans[0].unevenGaps);
}

// Every file and every folder of the shared DICOM data, as input on its own: scan, plan, load
// everything. Each must end in a result or an error naming what failed, never a crash or a
// hang. A per-input watchdog turns a hang into a failure that names the input.
TEST(DicomScannerData, EveryFileAndFolderScansPlansAndLoadsOrFailsClearly) {
    std::vector<fs::path> inputs;
    for (const char* top : {"dicom", "dicom-odd"}) {
        const fs::path root = dataDir() / top;
        inputs.push_back(root);
        for (const auto& entry : fs::recursive_directory_iterator(root))
            inputs.push_back(entry.path());
    }
    std::sort(inputs.begin(), inputs.end());
    std::size_t loaded = 0, loadErrors = 0, scanErrors = 0;
    for (const auto& input : inputs) {
        SCOPED_TRACE(input.string());
        auto work = std::async(std::launch::async, [&input, &loaded, &loadErrors, &scanErrors] {
            dicom::DicomIndex index;
            try {
                index = dicom::scanDicom(input);
            } catch (const core::Error& error) {
                EXPECT_FALSE(error.subject().empty());
                EXPECT_FALSE(error.reason().empty());
                ++scanErrors;
                return;
            }
            for (const auto& e : index.errors) {
                EXPECT_FALSE(e.file.empty());
                EXPECT_FALSE(e.reason.empty()) << e.file;
            }
            for (const auto* series : index.allSeries()) {
                dicom::SeriesAssembly assembly;
                try {
                    assembly = dicom::planVolumes(*series);
                } catch (const core::Error& error) {
                    EXPECT_FALSE(error.reason().empty());
                    continue;
                }
                for (const auto& plan : assembly.volumes) {
                    try {
                        const auto v = dicom::loadVolume(*series, plan);
                        EXPECT_EQ(v.dims(), plan.dims);
                        ++loaded;
                    } catch (const core::Error& error) {
                        EXPECT_FALSE(error.subject().empty());
                        EXPECT_FALSE(error.reason().empty());
                        ++loadErrors;
                    }
                }
            }
        });
        if (work.wait_for(std::chrono::seconds(120)) != std::future_status::ready) {
            std::fprintf(stderr, "HANG: scanning/loading %s took over 120 s\n",
                         input.string().c_str());
            std::fflush(stderr);
            std::_Exit(1); // the stuck thread cannot be joined; fail loudly instead
        }
        work.get();
    }
    std::printf("%zu inputs: %zu volumes loaded, %zu load errors, %zu inputs rejected\n",
                inputs.size(), loaded, loadErrors, scanErrors);
    EXPECT_GT(loaded, 100u);
}

// The study database reopens a series from its stored file list: the same series as a folder scan.
TEST(DicomScannerData, ScanDicomFilesOfAStoredSeriesMatchesTheFolderScan) {
    const fs::path folder = dataDir() / "dicom/ct_head_ge_hispeed_tilt_varspacing";
    const dicom::DicomIndex byFolder = dicom::scanDicom(folder);
    ASSERT_EQ(byFolder.seriesCount(), 1u);
    const dicom::SeriesInfo& series = *byFolder.allSeries()[0];
    std::vector<fs::path> files;
    for (const auto& instance : series.instances)
        files.emplace_back(instance.path);
    const dicom::DicomIndex byFiles = dicom::scanDicomFiles(files);
    ASSERT_EQ(byFiles.seriesCount(), 1u);
    EXPECT_TRUE(byFiles.errors.empty());
    const dicom::SeriesInfo& again = *byFiles.allSeries()[0];
    EXPECT_EQ(again.seriesInstanceUid, series.seriesInstanceUid);
    ASSERT_EQ(again.instances.size(), series.instances.size());
    const auto assembly = dicom::planVolumes(again);
    ASSERT_EQ(assembly.volumes.size(), 1u);
    EXPECT_EQ(assembly.volumes[0].dims, glm::ivec3(512, 512, 28));

    const volume::Volume middle = dicom::loadSlice(again, assembly.volumes[0], 14);
    EXPECT_EQ(middle.dims(), glm::ivec3(512, 512, 1));
}
