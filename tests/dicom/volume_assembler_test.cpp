// planVolumes/loadVolume on series the test writes itself: every expectation is ground truth
// from the writer, not from the reader under test.
#include "dicom_file.h"
#include "dicom_test_writer.h"
#include "lw/core/error.h"
#include "lw/core/progress.h"
#include "lw/dicom/dicom_scanner.h"
#include "lw/dicom/volume_assembler.h"
#include "test_support.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <gtest/gtest.h>
#include <numeric>
#include <random>

namespace dt = lw::dicom::test;
using namespace lw;
using namespace lw::dicom;

namespace {

constexpr int kSize = 16;

// Slice k of a synthetic series: values unique per slice, so misordering shows.
std::vector<int> slicePixels(int k) {
    return dt::rampPixels(kSize, kSize, -500 + 1000 * k, 3);
}

dt::TestSlice baseSlice(const std::string& seriesUid) {
    dt::TestSlice s;
    s.rows = kSize;
    s.columns = kSize;
    s.seriesUid = seriesUid;
    s.studyUid = "1.2.826.0.1.3680043.2.1143.1";
    s.pixelSpacing = glm::dvec2(0.5, 0.75);
    return s;
}

SeriesInfo readSeries(const std::vector<std::filesystem::path>& files) {
    SeriesInfo series;
    for (const auto& file : files)
        series.instances.push_back(readInstanceHeader(file));
    series.seriesInstanceUid = series.instances.front().seriesInstanceUid;
    series.description = series.instances.front().seriesDescription;
    return series;
}

// Writes slices at the given z positions (slice k gets slicePixels(k)) under shuffled names
// and shuffled InstanceNumbers; returns the files in writing order.
std::vector<std::filesystem::path> writeStack(const lw::test::TempDir& dir,
                                              const std::vector<double>& zs, dt::TestSlice base,
                                              const std::string& prefix = "s") {
    std::vector<int> order(zs.size());
    std::iota(order.begin(), order.end(), 0);
    std::mt19937 rng(42);
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<std::filesystem::path> files;
    for (std::size_t k = 0; k < zs.size(); ++k) {
        dt::TestSlice s = base;
        s.position = glm::dvec3(-20.0, 10.0, zs[k]);
        s.pixels = slicePixels(int(k));
        s.instanceNumber =
            int(zs.size() - std::size_t(order[k])); // deliberately not the slice order
        const auto path = dir / (prefix + std::to_string(order[k]) + ".dcm");
        dt::writeTestSlice(path, s);
        files.push_back(path);
    }
    std::shuffle(files.begin(), files.end(), rng);
    return files;
}

void expectSliceValues(const volume::Volume& v, int z, const std::vector<int>& expected) {
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            ASSERT_EQ(v.storedValue(x, y, z), expected[std::size_t(y * kSize + x)])
                << "z " << z << " x " << x << " y " << y;
}

// Runs `action`, which must throw a core::Error whose message contains `text`.
template <typename Action> void expectErrorMentions(Action&& action, const std::string& text) {
    try {
        action();
        ADD_FAILURE() << "expected an error mentioning " << text;
    } catch (const core::Error& e) {
        EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
}

} // namespace

TEST(VolumeAssembler, SortsByPositionNotByNameOrInstanceNumber) {
    lw::test::TempDir dir;
    const std::vector<double> zs = {10, 12, 14, 16, 18, 20};
    const auto files = writeStack(dir, zs, baseSlice(dt::makeTestUid()));
    const SeriesInfo series = readSeries(files);
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 1u);
    const VolumePlan& plan = assembly.volumes[0];
    EXPECT_EQ(plan.dims, glm::ivec3(kSize, kSize, 6));
    EXPECT_EQ(plan.voxelType, volume::VoxelType::Int16);
    EXPECT_NEAR(plan.tiltDegrees, 0.0, 1e-9);
    EXPECT_FALSE(plan.unevenGaps);
    EXPECT_NEAR(plan.minGap, 2.0, 1e-9);
    EXPECT_NEAR(plan.maxGap, 2.0, 1e-9);
    EXPECT_EQ(plan.missingSlices, 0);
    EXPECT_NEAR(plan.geometry.origin().z, 10.0, 1e-9);
    EXPECT_NEAR(plan.geometry.spacingI(), 0.75, 1e-12); // column spacing runs along the row axis
    EXPECT_NEAR(plan.geometry.spacingJ(), 0.5, 1e-12);
    EXPECT_NEAR(plan.geometry.sliceStep(), 2.0, 1e-9);
    ASSERT_EQ(plan.transferSyntaxes.size(), 1u);
    EXPECT_EQ(plan.transferSyntaxes[0], "1.2.840.10008.1.2.1");

    const volume::Volume volume = loadVolume(series, plan);
    EXPECT_EQ(volume.dims(), plan.dims);
    for (int z = 0; z < 6; ++z)
        expectSliceValues(volume, z, slicePixels(z));
}

TEST(VolumeAssembler, TiltedStackGivesTiltAngle) {
    lw::test::TempDir dir;
    const double angle = 15.0;
    const double rad = angle * M_PI / 180.0;
    dt::TestSlice base = baseSlice(dt::makeTestUid());
    // Slices rotated about x, positions still advancing along z: a gantry tilt.
    base.orientation = std::array<double, 6>{1, 0, 0, 0, std::cos(rad), -std::sin(rad)};
    const auto files = writeStack(dir, {0, 3, 6, 9, 12}, base);
    const SeriesInfo series = readSeries(files);
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 1u);
    EXPECT_NEAR(assembly.volumes[0].tiltDegrees, angle, 1e-3);
    EXPECT_NEAR(assembly.volumes[0].minGap, 3.0, 1e-6); // along the stacking direction
    const volume::Volume volume = loadVolume(series, assembly.volumes[0]);
    for (int z = 0; z < 5; ++z)
        expectSliceValues(volume, z, slicePixels(z));
}

TEST(VolumeAssembler, UnevenGapsAndMissingSlice) {
    lw::test::TempDir dir;
    const auto files = writeStack(dir, {0, 1.5, 3, 6, 7.5, 9}, baseSlice(dt::makeTestUid()));
    const SeriesAssembly assembly = planVolumes(readSeries(files));
    ASSERT_EQ(assembly.volumes.size(), 1u);
    const VolumePlan& plan = assembly.volumes[0];
    EXPECT_TRUE(plan.unevenGaps);
    EXPECT_NEAR(plan.minGap, 1.5, 1e-9);
    EXPECT_NEAR(plan.maxGap, 3.0, 1e-9);
    EXPECT_EQ(plan.missingSlices, 1);
    EXPECT_FALSE(plan.geometry.hasUniformSlices());
    EXPECT_NEAR(plan.geometry.sliceOffset(3), 6.0, 1e-9);

    lw::test::TempDir dir2;
    const auto uneven = writeStack(dir2, {0, 1, 2.5, 3.5}, baseSlice(dt::makeTestUid()));
    const SeriesAssembly b = planVolumes(readSeries(uneven));
    ASSERT_EQ(b.volumes.size(), 1u);
    EXPECT_TRUE(b.volumes[0].unevenGaps);
    EXPECT_EQ(b.volumes[0].missingSlices, 0); // 1.5 is not a whole multiple of 1
}

TEST(VolumeAssembler, TwoOrientationsGiveTwoVolumes) {
    lw::test::TempDir dir;
    const std::string uid = dt::makeTestUid();
    auto files = writeStack(dir, {0, 2, 4}, baseSlice(uid), "axial");
    dt::TestSlice sagittal = baseSlice(uid);
    sagittal.orientation = std::array<double, 6>{0, 1, 0, 0, 0, -1};
    for (int k = 0; k < 4; ++k) {
        dt::TestSlice s = sagittal;
        s.position = glm::dvec3(5.0 * k, 0, 0);
        s.pixels = slicePixels(k);
        const auto path = dir / ("sag" + std::to_string(k) + ".dcm");
        dt::writeTestSlice(path, s);
        files.push_back(path);
    }
    const SeriesAssembly assembly = planVolumes(readSeries(files));
    ASSERT_EQ(assembly.volumes.size(), 2u);
    std::vector<int> depths = {assembly.volumes[0].dims.z, assembly.volumes[1].dims.z};
    std::sort(depths.begin(), depths.end());
    EXPECT_EQ(depths, (std::vector<int>{3, 4}));
    EXPECT_NE(assembly.volumes[0].label, assembly.volumes[1].label);
    EXPECT_FALSE(assembly.volumes[0].label.empty());
}

TEST(VolumeAssembler, RescalePerSliceSplitsWithWarning) {
    lw::test::TempDir dir;
    const std::string uid = dt::makeTestUid();
    dt::TestSlice a = baseSlice(uid);
    a.rescaleIntercept = -1024;
    auto files = writeStack(dir, {0, 1, 2}, a, "a");
    dt::TestSlice b = baseSlice(uid);
    b.rescaleIntercept = 0;
    b.rescaleSlope = 2;
    const auto more = writeStack(dir, {3, 4, 5}, b, "b");
    files.insert(files.end(), more.begin(), more.end());
    const SeriesAssembly assembly = planVolumes(readSeries(files));
    ASSERT_EQ(assembly.volumes.size(), 2u);
    bool foundWarning = false;
    for (const auto& w : assembly.warnings)
        foundWarning = foundWarning || w.find("rescale") != std::string::npos;
    EXPECT_TRUE(foundWarning);
    for (const VolumePlan& plan : assembly.volumes) {
        EXPECT_EQ(plan.dims.z, 3);
        if (plan.valueMapping.slope == 2.0)
            EXPECT_EQ(plan.valueMapping.intercept, 0.0);
        else
            EXPECT_EQ(plan.valueMapping.intercept, -1024.0);
    }
}

TEST(VolumeAssembler, CompressedCopiesArePixelIdentical) {
    const std::vector<double> zs = {0, 2, 4};
    std::vector<std::vector<std::byte>> loaded;
    for (dt::TestTransferSyntax syntax :
         {dt::TestTransferSyntax::ExplicitLittle, dt::TestTransferSyntax::ExplicitBig,
          dt::TestTransferSyntax::Deflated, dt::TestTransferSyntax::JpegLossless,
          dt::TestTransferSyntax::JpegLsLossless, dt::TestTransferSyntax::Rle}) {
        lw::test::TempDir dir;
        dt::TestSlice base = baseSlice(dt::makeTestUid());
        base.transferSyntax = syntax;
        const SeriesInfo series = readSeries(writeStack(dir, zs, base));
        const SeriesAssembly assembly = planVolumes(series);
        ASSERT_EQ(assembly.volumes.size(), 1u);
        EXPECT_EQ(assembly.volumes[0].transferSyntaxes.at(0), dt::transferSyntaxUid(syntax));
        const volume::Volume v = loadVolume(series, assembly.volumes[0]);
        loaded.emplace_back(v.data(), v.data() + v.byteSize());
    }
    for (std::size_t i = 1; i < loaded.size(); ++i)
        EXPECT_TRUE(loaded[i] == loaded[0])
            << "encoding " << i << " differs from explicit little endian";
}

TEST(FrameDecoder, MasksToBitsStoredAndSignExtends) {
    lw::test::TempDir dir;
    const std::vector<int> values = {0, 1, 2047, -2048, -1, -5, 100, -100};
    // Signed 12-bit values in 16-bit words with garbage in the four unused high bits.
    dt::TestSlice s = baseSlice(dt::makeTestUid());
    s.rows = 2;
    s.columns = 4;
    s.bitsStored = 12;
    s.highBit = 11;
    s.pixelRepresentation = 1;
    s.pixels.clear();
    for (std::size_t i = 0; i < values.size(); ++i)
        s.pixels.push_back((values[i] & 0x0FFF) | (i % 2 ? 0xA000 : 0x5000));
    dt::writeTestSlice(dir / "signed.dcm", s);
    const InstanceInfo signedInfo = readInstanceHeader(dir / "signed.dcm");
    EXPECT_EQ(storedVoxelType(signedInfo), volume::VoxelType::Int16);
    std::vector<std::int16_t> out(values.size());
    FrameDecoder(signedInfo).decodeFrame(0, volume::VoxelType::Int16, out.data());
    for (std::size_t i = 0; i < values.size(); ++i)
        EXPECT_EQ(out[i], values[i]) << i;

    // Unsigned 12-bit with garbage bits: the garbage must go.
    s.pixelRepresentation = 0;
    s.pixels.clear();
    for (std::size_t i = 0; i < values.size(); ++i)
        s.pixels.push_back((std::abs(values[i]) & 0x0FFF) | 0xF000);
    dt::writeTestSlice(dir / "unsigned.dcm", s);
    const InstanceInfo unsignedInfo = readInstanceHeader(dir / "unsigned.dcm");
    EXPECT_EQ(storedVoxelType(unsignedInfo), volume::VoxelType::UInt16);
    std::vector<std::uint16_t> u(values.size());
    FrameDecoder(unsignedInfo).decodeFrame(0, volume::VoxelType::UInt16, u.data());
    for (std::size_t i = 0; i < values.size(); ++i)
        EXPECT_EQ(u[i], std::abs(values[i]) & 0x0FFF) << i;

    // High bit not at BitsStored-1: the value sits in bits 4..15.
    s.bitsStored = 12;
    s.highBit = 15;
    s.pixels.clear();
    for (std::size_t i = 0; i < values.size(); ++i)
        s.pixels.push_back(((std::abs(values[i]) & 0x0FFF) << 4) | 0x000F);
    dt::writeTestSlice(dir / "shifted.dcm", s);
    FrameDecoder(readInstanceHeader(dir / "shifted.dcm"))
        .decodeFrame(0, volume::VoxelType::UInt16, u.data());
    for (std::size_t i = 0; i < values.size(); ++i)
        EXPECT_EQ(u[i], std::abs(values[i]) & 0x0FFF) << i;
}

TEST(FrameDecoder, Monochrome1IsInverted) {
    lw::test::TempDir dir;
    dt::TestSlice s = baseSlice(dt::makeTestUid());
    s.rows = 1;
    s.columns = 4;
    s.bitsStored = 12;
    s.highBit = 11;
    s.pixelRepresentation = 0;
    s.photometric = "MONOCHROME1";
    s.pixels = {0, 1, 1000, 4095};
    dt::writeTestSlice(dir / "m1.dcm", s);
    std::vector<std::uint16_t> out(4);
    FrameDecoder(readInstanceHeader(dir / "m1.dcm"))
        .decodeFrame(0, volume::VoxelType::UInt16, out.data());
    EXPECT_EQ(out, (std::vector<std::uint16_t>{4095, 4094, 3095, 0}));
}

TEST(FrameDecoder, EightBitAndTruncatedAndMissingPixels) {
    lw::test::TempDir dir;
    dt::TestSlice s = baseSlice(dt::makeTestUid());
    s.rows = 3;
    s.columns = 3; // odd byte count: padded on disk
    s.bitsAllocated = 8;
    s.bitsStored = 8;
    s.highBit = 7;
    s.pixelRepresentation = 0;
    s.pixels = {0, 1, 2, 3, 250, 251, 252, 253, 255};
    dt::writeTestSlice(dir / "u8.dcm", s);
    const InstanceInfo info = readInstanceHeader(dir / "u8.dcm");
    EXPECT_EQ(storedVoxelType(info), volume::VoxelType::UInt8);
    std::vector<std::uint8_t> out(9);
    FrameDecoder(info).decodeFrame(0, volume::VoxelType::UInt8, out.data());
    for (std::size_t i = 0; i < 9; ++i)
        EXPECT_EQ(out[i], s.pixels[i]);

    // Claim more rows than the pixel data holds: a clear error, not a read past the end.
    InstanceInfo lying = info;
    lying.rows = 30;
    std::vector<std::uint8_t> big(90);
    EXPECT_THROW(FrameDecoder(lying).decodeFrame(0, volume::VoxelType::UInt8, big.data()),
                 core::Error);

    s.writePixelData = false;
    dt::writeTestSlice(dir / "nopixels.dcm", s);
    const InstanceInfo none = readInstanceHeader(dir / "nopixels.dcm");
    EXPECT_FALSE(none.hasPixelData);
    EXPECT_THROW(storedVoxelType(none), core::Error);
    EXPECT_THROW(FrameDecoder(none).decodeFrame(0, volume::VoxelType::UInt8, out.data()),
                 core::Error);
}

TEST(VolumeAssembler, DuplicatePositionsSplitByAcquisition) {
    lw::test::TempDir dir;
    const std::string uid = dt::makeTestUid();
    dt::TestSlice a = baseSlice(uid);
    a.acquisitionNumber = 1;
    auto files = writeStack(dir, {0, 1, 2, 3}, a, "a");
    dt::TestSlice b = baseSlice(uid);
    b.acquisitionNumber = 2;
    const auto more = writeStack(dir, {0, 1, 2, 3}, b, "b");
    files.insert(files.end(), more.begin(), more.end());
    const SeriesAssembly assembly = planVolumes(readSeries(files));
    ASSERT_EQ(assembly.volumes.size(), 2u);
    EXPECT_EQ(assembly.volumes[0].dims.z, 4);
    EXPECT_EQ(assembly.volumes[1].dims.z, 4);
    EXPECT_NE(assembly.volumes[0].label, assembly.volumes[1].label);

    // Without anything to tell the repeats apart: split in order, with a warning.
    lw::test::TempDir dir2;
    const std::string uid2 = dt::makeTestUid();
    auto twice = writeStack(dir2, {0, 1, 2}, baseSlice(uid2), "a");
    const auto again = writeStack(dir2, {0, 1, 2}, baseSlice(uid2), "b");
    twice.insert(twice.end(), again.begin(), again.end());
    const SeriesAssembly c = planVolumes(readSeries(twice));
    ASSERT_EQ(c.volumes.size(), 2u);
    ASSERT_FALSE(c.volumes[0].warnings.empty());
    bool mentionsDuplicates = false;
    for (const auto& w : c.volumes[0].warnings)
        mentionsDuplicates =
            mentionsDuplicates || w.find("duplicate positions") != std::string::npos;
    EXPECT_TRUE(mentionsDuplicates);
}

TEST(VolumeAssembler, AllSlicesAtOnePositionIsNotAVolume) {
    lw::test::TempDir dir;
    const auto files = writeStack(dir, {5, 5, 5, 5}, baseSlice(dt::makeTestUid()));
    const SeriesAssembly assembly = planVolumes(readSeries(files));
    EXPECT_TRUE(assembly.volumes.empty());
    bool warned = false;
    for (const auto& w : assembly.warnings)
        warned = warned || w.find("share one position") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(VolumeAssembler, SingleSliceWithoutPosition) {
    lw::test::TempDir dir;
    dt::TestSlice s = baseSlice(dt::makeTestUid());
    s.position.reset();
    s.orientation.reset();
    s.pixels = slicePixels(0);
    dt::writeTestSlice(dir / "lonely.dcm", s);
    const SeriesInfo series = readSeries({dir / "lonely.dcm"});
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 1u);
    EXPECT_EQ(assembly.volumes[0].dims, glm::ivec3(kSize, kSize, 1));
    EXPECT_GE(assembly.volumes[0].warnings.size(), 2u); // no position, no orientation
    const volume::Volume v = loadVolume(series, assembly.volumes[0]);
    expectSliceValues(v, 0, slicePixels(0));
}

TEST(VolumeAssembler, SeparateFilesWithoutPositionAreNotStacked) {
    // Two single-frame images of one series, neither with a position: nothing says they form a
    // stack, so each becomes its own one-slice volume, labelled with its file.
    lw::test::TempDir dir;
    const std::string uid = dt::makeTestUid();
    std::vector<std::filesystem::path> files;
    for (int k = 0; k < 2; ++k) {
        dt::TestSlice s = baseSlice(uid);
        s.position.reset();
        s.pixels = slicePixels(k);
        s.instanceNumber = k + 1;
        files.push_back(dir / ("image" + std::to_string(k) + ".dcm"));
        dt::writeTestSlice(files.back(), s);
    }
    const SeriesInfo series = readSeries(files);
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 2u);
    for (int k = 0; k < 2; ++k) {
        EXPECT_EQ(assembly.volumes[k].dims, glm::ivec3(kSize, kSize, 1));
        EXPECT_NE(assembly.volumes[k].label.find("image"), std::string::npos)
            << assembly.volumes[k].label;
    }
}

TEST(VolumeAssembler, CancellationThroughProgress) {
    lw::test::TempDir dir;
    std::vector<double> zs(24);
    std::iota(zs.begin(), zs.end(), 0.0);
    const SeriesInfo series = readSeries(writeStack(dir, zs, baseSlice(dt::makeTestUid())));
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 1u);

    double last = 0.0;
    core::Progress complete([&](double fraction, const std::string&) { last = fraction; });
    EXPECT_NO_THROW(loadVolume(series, assembly.volumes[0], &complete));
    EXPECT_DOUBLE_EQ(last, 1.0);

    auto token = std::make_shared<core::CancelToken>();
    double reached = 0.0;
    core::Progress cancelling(
        [&](double fraction, const std::string&) {
            reached = std::max(reached, fraction);
            if (fraction > 0.2)
                token->cancel();
        },
        token);
    EXPECT_THROW(loadVolume(series, assembly.volumes[0], &cancelling), core::Cancelled);
    EXPECT_LT(reached, 1.0);
}

TEST(VolumeAssembler, DecodeErrorNamesTheFile) {
    lw::test::TempDir dir;
    const auto files = writeStack(dir, {0, 1, 2}, baseSlice(dt::makeTestUid()));
    const SeriesInfo series = readSeries(files);
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 1u);
    const VolumePlan& plan = assembly.volumes[0];
    expectErrorMentions([&] { loadSlice(series, plan, 3); }, series.seriesInstanceUid);

    const std::filesystem::path gone = series.instances[plan.slices[1].instance].path;
    std::filesystem::remove(gone);
    expectErrorMentions([&] { loadVolume(series, plan); }, gone.filename().string());
    expectErrorMentions([&] { loadSlice(series, plan, 1); }, gone.filename().string());
    EXPECT_NO_THROW(loadSlice(series, plan, 0)); // only the slice asked for is read
}

TEST(VolumeAssembler, MixedSignednessBecomesInt16WhenValuesFit) {
    lw::test::TempDir dir;
    const std::string uid = dt::makeTestUid();
    dt::TestSlice a = baseSlice(uid); // signed 16-bit
    auto files = writeStack(dir, {0, 1}, a, "signed");
    dt::TestSlice b = baseSlice(uid); // unsigned 12-bit: fits int16
    b.pixelRepresentation = 0;
    b.bitsStored = 12;
    b.highBit = 11;
    for (int k = 0; k < 2; ++k) {
        b.position = glm::dvec3(-20.0, 10.0, 2.0 + k);
        b.pixels = dt::rampPixels(kSize, kSize, 100 * k, 7);
        const auto path = dir / ("unsigned" + std::to_string(k) + ".dcm");
        dt::writeTestSlice(path, b);
        files.push_back(path);
    }
    const SeriesInfo series = readSeries(files);
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 1u);
    EXPECT_EQ(assembly.volumes[0].voxelType, volume::VoxelType::Int16);
    EXPECT_TRUE(assembly.volumes[0].warnings.empty());
    const volume::Volume v = loadVolume(series, assembly.volumes[0]);
    expectSliceValues(v, 3, dt::rampPixels(kSize, kSize, 100, 7));
    // Signed slices sorted first (z 0 and 1): ramp from slicePixels, in position order.
    EXPECT_EQ(v.storedValue(0, 0, 0), slicePixels(0)[0]);
}

TEST(VolumeAssembler, ClassicMultiFrameWithoutPositionsIsStackedWithWarning) {
    lw::test::TempDir dir;
    dt::TestSlice s = baseSlice(dt::makeTestUid());
    s.numberOfFrames = 3;
    s.pixels.clear();
    for (int f = 0; f < 3; ++f) {
        const auto frame = slicePixels(f);
        s.pixels.insert(s.pixels.end(), frame.begin(), frame.end());
    }
    s.sliceThickness = 2.5;
    s.transferSyntax = dt::TestTransferSyntax::Rle; // encapsulated multi-frame: decoded once
    dt::writeTestSlice(dir / "multi.dcm", s);
    const SeriesInfo series = readSeries({dir / "multi.dcm"});
    ASSERT_EQ(series.instances[0].frames.size(), 3u);
    EXPECT_FALSE(series.instances[0].frames[1].position.has_value());
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 1u);
    EXPECT_EQ(assembly.volumes[0].dims, glm::ivec3(kSize, kSize, 3));
    EXPECT_NEAR(assembly.volumes[0].geometry.sliceStep(), 2.5, 1e-9);
    EXPECT_FALSE(assembly.volumes[0].warnings.empty());
    const volume::Volume v = loadVolume(series, assembly.volumes[0]);
    for (int z = 0; z < 3; ++z)
        expectSliceValues(v, z, slicePixels(z));
}

TEST(VolumeAssembler, LoadSliceDecodesOneSliceWithItsGeometry) {
    lw::test::TempDir dir;
    const std::vector<double> zs = {0, 1.5, 3, 6, 7.5};
    const SeriesInfo series = readSeries(writeStack(dir, zs, baseSlice(dt::makeTestUid())));
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 1u);
    const VolumePlan& plan = assembly.volumes[0];
    const volume::Volume whole = loadVolume(series, plan);

    for (std::size_t k : {std::size_t(0), std::size_t(3), zs.size() - 1}) {
        const volume::Volume slice = loadSlice(series, plan, k);
        EXPECT_EQ(slice.dims(), glm::ivec3(kSize, kSize, 1));
        EXPECT_EQ(slice.voxelType(), whole.voxelType());
        expectSliceValues(slice, 0, slicePixels(int(k)));
        // The slice sits where the whole volume has it: same patient position of its corners.
        for (const glm::dvec3 corner : {glm::dvec3(0, 0, 0), glm::dvec3(kSize - 1, kSize - 1, 0)}) {
            const glm::dvec3 expected =
                whole.geometry().indexToPatient(corner + glm::dvec3(0, 0, double(k)));
            const glm::dvec3 actual = slice.geometry().indexToPatient(corner);
            EXPECT_NEAR(glm::distance(expected, actual), 0.0, 1e-9) << "slice " << k;
        }
    }
}

// Issue 10: slices at z = 0, 1 and 1e12 made the missing-slice estimate convert an
// out-of-range double to int ("2147483647 missing slices"). The far slice is left out with
// the reason; the estimate stays bounded whatever the gaps.
TEST(VolumeAssembler, ImplausiblePositionIsLeftOutWithTheReason) {
    lw::test::TempDir dir;
    const auto files = writeStack(dir, {0.0, 1.0, 1e12}, baseSlice(dt::makeTestUid()));
    const SeriesAssembly assembly = planVolumes(readSeries(files));
    ASSERT_EQ(assembly.errors.size(), 1u);
    const InstanceInfo far = readInstanceHeader(assembly.errors[0].file);
    EXPECT_EQ(far.frames.at(0).position->z, 1e12);
    EXPECT_NE(assembly.errors[0].reason.find("implausible ImagePositionPatient"), std::string::npos)
        << assembly.errors[0].reason;
    ASSERT_EQ(assembly.volumes.size(), 1u);
    EXPECT_EQ(assembly.volumes[0].dims.z, 2);
    EXPECT_EQ(assembly.volumes[0].missingSlices, 0);
}

TEST(VolumeAssembler, HugeGapIsNoRunOfMissingSlices) {
    lw::test::TempDir dir;
    // 9 m between the last two slices: plausible positions, but no 8997 lost slices.
    const auto files = writeStack(dir, {0.0, 1.0, 2.0, 9000.0}, baseSlice(dt::makeTestUid()));
    const SeriesAssembly assembly = planVolumes(readSeries(files));
    EXPECT_TRUE(assembly.errors.empty());
    ASSERT_EQ(assembly.volumes.size(), 1u);
    const VolumePlan& plan = assembly.volumes[0];
    EXPECT_TRUE(plan.unevenGaps);
    EXPECT_EQ(plan.missingSlices, 0);
    EXPECT_NEAR(plan.maxGap, 8998.0, 1e-6);
}

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void expectReason(const std::function<void()>& work, const std::string& reason) {
    try {
        work();
        ADD_FAILURE() << "no error; expected: " << reason;
    } catch (const core::Error& error) {
        EXPECT_NE(error.reason().find(reason), std::string::npos) << error.reason();
    }
}

// A hand-made header declaring rows x columns x frames of int16 with 2 bytes of pixel data.
std::filesystem::path writeHostileHeader(const lw::test::TempDir& dir, const std::string& name,
                                         int rows, int columns, const std::string& frames) {
    dt::HandMadeImage image;
    image.rows = rows;
    image.columns = columns;
    image.numberOfFrames = frames;
    image.pixelDataBytes = 2;
    dt::writeHandMadeImage(dir / name, image);
    return dir / name;
}

} // namespace

// Issue 10: a ~550-byte header declaring 2^31-1 frames cost a minute and 13 GB of frame
// descriptions before failing; the frame count is checked before any frame is described.
TEST(ImportLimits, HeaderDeclaring2147483647FramesIsRejectedAtOnce) {
    lw::test::TempDir dir;
    writeHostileHeader(dir, "frames.dcm", 512, 512, "2147483647");
    const auto start = std::chrono::steady_clock::now();
    expectReason([&] { (void)readInstanceHeader(dir / "frames.dcm"); },
                 "implausible number of frames 2147483647");
    const DicomIndex index = scanDicom(dir.path());
    EXPECT_LT(secondsSince(start), 0.1);
    ASSERT_EQ(index.errors.size(), 1u);
    EXPECT_NE(index.errors[0].reason.find("implausible number of frames"), std::string::npos);
}

TEST(ImportLimits, PixelDataOverTheLimitIsRejectedFromTheHeader) {
    lw::test::TempDir dir;
    writeHostileHeader(dir, "big.dcm", 1024, 1024, "100");
    core::ImportLimits limits;
    limits.maxBytes = std::size_t(64) << 20;
    expectReason(
        [&] { (void)readInstanceHeader(dir / "big.dcm", limits); },
        "the pixel data the header declares needs 200 MB, more than the import limit of 64 MB");
}

// Issue 10: 65535 x 65535 pixels declared, 2 bytes present: loadVolume allocated the 8 GB volume
// before finding out. The pixel data length is compared with the header before allocating.
TEST(ImportLimits, HugeImageWithoutItsPixelsFailsBeforeAllocating) {
    lw::test::TempDir dir;
    writeHostileHeader(dir, "huge.dcm", 65535, 65535, "1");
    core::ImportLimits limits;
    limits.maxBytes = std::size_t(16) << 30; // so that only the missing pixels can stop it
    SeriesInfo series;
    series.instances.push_back(readInstanceHeader(dir / "huge.dcm", limits));
    series.seriesInstanceUid = series.instances[0].seriesInstanceUid;
    ASSERT_TRUE(series.instances[0].nativePixelDataBytes.has_value());
    EXPECT_EQ(*series.instances[0].nativePixelDataBytes, 2u);
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 1u);
    const auto start = std::chrono::steady_clock::now();
    expectReason([&] { (void)loadVolume(series, assembly.volumes[0], nullptr, limits); },
                 "pixel data truncated: 2 bytes where the header declares 8589672450");
    EXPECT_LT(secondsSince(start), 0.1);
    // And with the default limit of a small machine, the volume itself is refused.
    limits.maxBytes = std::size_t(1) << 30;
    expectReason([&] { (void)loadVolume(series, assembly.volumes[0], nullptr, limits); },
                 "the volume (65535×65535×1 int16) = 8.0 GiB is more than the limit of 1.0 GiB");
}
