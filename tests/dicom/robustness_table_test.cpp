// docs/robustness.md: what Linework does with every file of ../shared/data/dicom-odd and every
// hostile input under tests/data/fuzz, generated here so it cannot go stale (issue 10). The test
// fails when the page differs from what the code does now; LINEWORK_UPDATE_DOCS=1 rewrites it
// (look at the diff before committing it).
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/dicom/dicom_scanner.h"
#include "lw/dicom/volume_assembler.h"
#include "lw/volume/volume_reader.h"
#include "test_support.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

using namespace lw;
namespace fs = std::filesystem;

namespace {

const char* const kPage = "docs/robustness.md";

// Table cells: one line, no column breaks, paths relative to the folder they were found in.
std::string cell(std::string text, const fs::path& folder) {
    for (std::size_t at; (at = text.find(folder.string() + "/")) != std::string::npos;)
        text.erase(at, folder.string().size() + 1);
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::string escaped;
    for (const char c : text)
        escaped += c == '|' ? std::string("\\|") : std::string(1, c);
    return escaped;
}

std::string joined(const std::vector<std::string>& parts) {
    std::string text;
    for (const auto& part : parts)
        text += (text.empty() ? "" : "; ") + part;
    return text;
}

// The same outcome for many files (a DICOMDIR whose 31 references are missing) once, counted.
std::string counted(const std::vector<std::string>& outcomes) {
    std::vector<std::pair<std::string, int>> distinct;
    for (const auto& outcome : outcomes) {
        auto found = std::find_if(distinct.begin(), distinct.end(),
                                  [&](const auto& entry) { return entry.first == outcome; });
        if (found == distinct.end())
            distinct.push_back({outcome, 1});
        else
            ++found->second;
    }
    std::vector<std::string> parts;
    for (const auto& entry : distinct)
        parts.push_back(entry.second == 1 ? entry.first
                                          : std::to_string(entry.second) + " × " + entry.first);
    return joined(parts);
}

std::string describeVolume(const dicom::SeriesInfo& series, const dicom::VolumePlan& plan) {
    try {
        const volume::Volume loaded = dicom::loadVolume(series, plan);
        const glm::ivec3 d = loaded.dims();
        std::string text = "loads " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" +
                           std::to_string(d.z) + " " +
                           std::string(volume::voxelTypeName(loaded.voxelType()));
        if (!plan.warnings.empty())
            text += " (warning: " + joined(plan.warnings) + ")";
        return text;
    } catch (const core::Error& error) {
        return "error: " + error.reason();
    }
}

// An import of this one DICOM file (or DICOMDIR) as the workstation does it: scan, plan, load.
std::string importOutcome(const fs::path& file) {
    std::vector<std::string> outcomes;
    try {
        const bool isDicomdir = file.filename().string().rfind("DICOMDIR", 0) == 0 ||
                                file.parent_path().filename() == "dicomdir";
        const dicom::DicomIndex index =
            isDicomdir ? dicom::scanDicom(file) : dicom::scanDicomFiles({file});
        for (const auto& error : index.errors)
            outcomes.push_back("error: " + error.reason);
        for (const dicom::SeriesInfo* series : index.allSeries()) {
            const dicom::SeriesAssembly assembly = dicom::planVolumes(*series);
            for (const auto& error : assembly.errors)
                outcomes.push_back("error: " + error.reason);
            for (const auto& plan : assembly.volumes)
                outcomes.push_back(describeVolume(*series, plan));
            if (assembly.volumes.empty() && assembly.errors.empty())
                outcomes.push_back("no volume" + (assembly.warnings.empty()
                                                      ? std::string()
                                                      : ": " + joined(assembly.warnings)));
        }
    } catch (const core::Error& error) {
        outcomes.push_back("error: " + error.reason());
    }
    return outcomes.empty() ? "nothing to import" : counted(outcomes);
}

std::string volumeOutcome(const fs::path& file) {
    try {
        const volume::Volume loaded = volume::readVolumeFile(file);
        const glm::ivec3 d = loaded.dims();
        return "loads " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" +
               std::to_string(d.z) + " " + std::string(volume::voxelTypeName(loaded.voxelType()));
    } catch (const core::Error& error) {
        return "error: " + error.reason();
    }
}

std::vector<fs::path> filesUnder(const fs::path& folder) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder))
        if (entry.is_regular_file() && entry.path().filename() != "README.md")
            files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

void addRows(std::ostringstream& page, const fs::path& folder, bool volumesByFolder) {
    page << "| file | what Linework does |\n|---|---|\n";
    for (const fs::path& file : filesUnder(folder)) {
        const fs::path relative = fs::relative(file, folder);
        const std::string target = relative.begin()->string();
        const bool volume =
            volumesByFolder && (target == "nrrd" || target == "nifti" || target == "pvm");
        page << "| " << relative.generic_string() << " | "
             << cell(volume ? volumeOutcome(file) : importOutcome(file), file.parent_path())
             << " |\n";
    }
}

std::string generatedPage(const fs::path& data) {
    std::ostringstream page;
    page << "# Robustness: what Linework does with broken and hostile files\n\n"
         << "Generated by `lw_dicom_robustness_table_tests` "
            "(tests/dicom/robustness_table_test.cpp), which fails when\n"
         << "this page is stale; rerun it with `LINEWORK_UPDATE_DOCS=1` to rewrite it. Each "
            "file is imported on its\n"
         << "own, as `linework FILE` would: scanned (a DICOMDIR with its file-set), every series "
            "planned, every volume\n"
         << "loaded. \"loads\" gives the volume; \"error\" the reason the user sees (paths "
            "shortened to the file's folder).\n"
         << "Nothing here may crash, abort or hang: the sanitizer build runs the same test.\n\n"
         << "What gates CI: `lw_fuzz_regression_tests` replays every file of tests/data/fuzz in "
            "the normal and the\n"
         << "sanitizer suite and fails on a crash, a sanitizer finding, an exception other than "
            "`core::Error`, more\n"
         << "than 10 s or one allocation over 1 GB. The random fuzz runs of `scripts/linework.sh "
            "test` only print\n"
         << "new findings (they fail it with `LINEWORK_FUZZ_STRICT=1`; fuzz targets that do not "
            "build always\n"
         << "fail it); a fixed finding joins tests/data/fuzz and is gated from then on "
            "(docs/architecture.md, Tests).\n\n"
         << "## ../shared/data/dicom-odd (SOURCES.md there says what each file is)\n\n";
    addRows(page, data / "dicom-odd", false);
    page << "\n## tests/data/fuzz (hostile inputs and fuzz findings; README.md there gives their "
            "origin)\n\n";
    addRows(page, lw::test::sourceDir() / "tests/data/fuzz", true);
    return page.str();
}

} // namespace

TEST(RobustnessTable, PageSaysWhatLineworkDoesWithEveryFile) {
    // Warnings are part of the table, not noise for this test's output.
    const core::LogSink previous =
        core::setLogSink([](core::LogLevel, std::string_view, const std::string&) {});
    const std::string generated = generatedPage(*lw::test::sharedDataDir());
    core::setLogSink(previous);
    const fs::path page = lw::test::sourceDir() / kPage;
    if (const char* update = std::getenv("LINEWORK_UPDATE_DOCS"); update && *update == '1') {
        std::ofstream(page, std::ios::binary) << generated;
        GTEST_SKIP() << "rewrote " << page;
    }
    std::ifstream in(page, std::ios::binary);
    const std::string committed{std::istreambuf_iterator<char>(in),
                                std::istreambuf_iterator<char>()};
    EXPECT_EQ(committed, generated) << kPage << " is stale: rerun this test with "
                                    << "LINEWORK_UPDATE_DOCS=1 and commit the page";
}
