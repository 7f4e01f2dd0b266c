// The third-party volumes under ../shared/data/volumes load with the dims, types, spacing and
// values that SOURCES.md states. Skipped (exit 77) when the shared data is missing.
#include "lw/core/error.h"
#include "lw/volume/volume_reader.h"
#include "test_support.h"

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <set>

namespace lw::volume {
namespace {

std::filesystem::path volumesDir() {
    return *test::sharedDataDir() / "volumes";
}

struct Expected {
    const char* file;
    glm::ivec3 dims;
    VoxelType type;
    glm::dvec3 spacing;
    double spacingTolerance;
};

void checkVolume(const Expected& e, const Volume& v) {
    SCOPED_TRACE(e.file);
    EXPECT_EQ(v.dims(), e.dims);
    EXPECT_EQ(v.voxelType(), e.type);
    const glm::dvec3 s = v.geometry().spacing();
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(s[a], e.spacing[a], e.spacingTolerance) << "axis " << a;
}

const Expected kExpected[] = {
    {"vtk_headsq_quarter_64x64x93_int16le/quarter.nhdr",
     {64, 64, 93},
     VoxelType::Int16,
     {3.2, 3.2, 1.5},
     1e-9},
    {"voreen_nucleon_41cubed_uint8/nucleon.nrrd", {41, 41, 41}, VoxelType::UInt8, {1, 1, 1}, 1e-9},
    {"volume_library_bucky_pvm/Bucky.pvm", {32, 32, 32}, VoxelType::UInt8, {1, 1, 1}, 1e-9},
    {"volume_library_lobster_pvm/Lobster.pvm", {301, 324, 56}, VoxelType::UInt8, {1, 1, 1.4}, 1e-6},
    {"opensciviz_cropped_nifti/fuel.nii.gz", {64, 33, 32}, VoxelType::UInt8, {1, 1, 1}, 1e-6},
    {"opensciviz_cropped_nifti/engine.nii.gz", {256, 256, 128}, VoxelType::UInt8, {1, 1, 1}, 1e-6},
    {"opensciviz_cropped_nifti/bonsai.nii.gz", {256, 256, 256}, VoxelType::UInt8, {1, 1, 1}, 1e-6},
    {"ct_head_nifti_niivue/CT_pitch.nii.gz",
     {175, 248, 58},
     VoxelType::UInt8,
     {0.8125, 0.8125, 2.397},
     1e-3},
    {"ct_head_nifti_niivue/CT_AVM.nii.gz",
     {256, 242, 154},
     VoxelType::UInt8,
     {0.72, 0.72, 1.0},
     2e-3},
    {"ct_example_nifti_dicom2stl/ct_example.nii.gz",
     {256, 256, 26},
     VoxelType::Int16,
     {1.25, 1.25, 4.0},
     1e-6},
};

TEST(VolumeData, EveryListedFileLoadsAsDocumented) {
    for (const Expected& e : kExpected)
        checkVolume(e, readVolumeFile(volumesDir() / e.file));
}

// Every NRRD/NIfTI/PVM under volumes/ is in the table above: a new file must be added there.
TEST(VolumeData, NoReadableFileIsLeftUnchecked) {
    std::set<std::string> listed;
    for (const Expected& e : kExpected)
        listed.insert(e.file);
    int found = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(volumesDir())) {
        if (!entry.is_regular_file())
            continue;
        const VolumeFormat format = detectVolumeFormat(entry.path());
        if (format == VolumeFormat::Unknown)
            continue;
        const std::string relative =
            std::filesystem::relative(entry.path(), volumesDir()).generic_string();
        EXPECT_TRUE(listed.count(relative)) << relative << " is readable but not checked";
        ++found;
    }
    EXPECT_EQ(found, int(std::size(kExpected)));
}

TEST(VolumeData, ValueRangesAndGeometry) {
    const Volume quarter =
        readVolumeFile(volumesDir() / "vtk_headsq_quarter_64x64x93_int16le/quarter.nhdr");
    EXPECT_EQ(quarter.storedRange().min, 0);
    EXPECT_EQ(quarter.storedRange().max, 3926);

    const Volume bucky = readVolumeFile(volumesDir() / "volume_library_bucky_pvm/Bucky.pvm");
    EXPECT_EQ(bucky.storedRange().min, 0);
    EXPECT_EQ(bucky.storedRange().max, 255);
    EXPECT_EQ(bucky.description(), "Bucky Ball");
    // C60 is centred: the density is symmetric under x -> 31 - x.
    EXPECT_EQ(bucky.storedValue(0, 0, 0), bucky.storedValue(31, 0, 0));

    const Volume nucleon =
        readVolumeFile(volumesDir() / "voreen_nucleon_41cubed_uint8/nucleon.nrrd");
    EXPECT_EQ(nucleon.storedRange().max, 249);
    // The .raw next to it is the same data.
    RawOptions raw;
    raw.dims = {41, 41, 41};
    const Volume nucleonRaw =
        readRawVolume(volumesDir() / "voreen_nucleon_41cubed_uint8/nucleon.raw", raw);
    EXPECT_EQ(std::memcmp(nucleonRaw.data(), nucleon.data(), nucleon.byteSize()), 0);

    const Volume ct = readVolumeFile(volumesDir() / "ct_example_nifti_dicom2stl/ct_example.nii.gz");
    EXPECT_EQ(ct.realRange().min, -1024);
    EXPECT_EQ(ct.realRange().max, 1945);

    const Volume avm = readVolumeFile(volumesDir() / "ct_head_nifti_niivue/CT_AVM.nii.gz");
    EXPECT_NEAR(avm.valueMapping().slope, 2.2086, 1e-4);

    // CT_pitch: rotated against the bore, but not sheared.
    const Volume pitch = readVolumeFile(volumesDir() / "ct_head_nifti_niivue/CT_pitch.nii.gz");
    EXPECT_LT(pitch.geometry().tiltDegrees(), 0.01);
    EXPECT_GT(std::abs(pitch.geometry().axisJ().z), 0.1);
}

TEST(VolumeData, StanfordCtHeadSliceIsBigEndianInt16) {
    RawOptions o;
    o.dims = {256, 256, 1};
    o.type = VoxelType::Int16;
    o.bigEndian = true;
    const auto folder = volumesDir() / "stanford_cthead_113x256x256_int16be";
    const Volume slice = readRawVolume(folder / "CThead.60", o);
    const ValueRange r = slice.storedRange();
    EXPECT_GE(r.min, 0);
    EXPECT_LE(r.max, 3272);
    EXPECT_GT(r.max, 1200); // skull in a mid slice
    // Read with the wrong byte order the values leave the documented range.
    o.bigEndian = false;
    const ValueRange swapped = readRawVolume(folder / "CThead.60", o).storedRange();
    EXPECT_TRUE(swapped.min < 0 || swapped.max > 3272);
    o.dims = {256, 256, 2};
    EXPECT_THROW(readRawVolume(folder / "CThead.60", o), core::Error);
}

} // namespace
} // namespace lw::volume
