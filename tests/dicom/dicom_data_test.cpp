// Reading, decoding and assembling the public sample data in ../shared/data (label: data).
// Expected values come from /work/shared/data/SOURCES.md (verified there with DCMTK/pydicom).
#include "dicom_file.h"
#include "lw/core/error.h"
#include "lw/dicom/volume_assembler.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <map>

using namespace lw;
using namespace lw::dicom;
namespace fs = std::filesystem;

namespace {

fs::path dataDir() {
    const auto dir = lw::test::sharedDataDir();
    if (!dir)
        throw std::runtime_error("shared data missing"); // the data main already skips then
    return *dir;
}

std::vector<fs::path> filesIn(const fs::path& folder) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.is_regular_file())
            files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

SeriesInfo seriesOf(const std::vector<fs::path>& files) {
    SeriesInfo series;
    for (const auto& file : files)
        series.instances.push_back(readInstanceHeader(file));
    series.seriesInstanceUid = series.instances.front().seriesInstanceUid;
    series.description = series.instances.front().seriesDescription;
    return series;
}

// Decodes every frame of one file into int32 values (whatever the stored type).
std::vector<std::int32_t> decodeFile(const fs::path& path) {
    const InstanceInfo info = readInstanceHeader(path);
    const volume::VoxelType type = storedVoxelType(info);
    const std::size_t pixels = std::size_t(info.rows) * std::size_t(info.columns);
    std::vector<std::int32_t> all;
    FrameDecoder decoder(info);
    for (int f = 0; f < info.numberOfFrames; ++f) {
        std::vector<std::byte> buffer(pixels * volume::voxelSize(type));
        decoder.decodeFrame(f, type, buffer.data());
        volume::dispatchVoxelType(type, [&](auto tag) {
            using T = decltype(tag);
            const T* values = reinterpret_cast<const T*>(buffer.data());
            all.insert(all.end(), values, values + pixels);
        });
    }
    return all;
}

int maxAbsDifference(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b) {
    EXPECT_EQ(a.size(), b.size());
    int worst = 0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
        worst = std::max(worst, std::abs(a[i] - b[i]));
    return worst;
}

std::vector<std::byte> bytesOf(const volume::Volume& v) {
    return {v.data(), v.data() + v.byteSize()};
}

bool anyContains(const std::vector<std::string>& texts, const std::string& part) {
    return std::any_of(texts.begin(), texts.end(),
                       [&](const std::string& t) { return t.find(part) != std::string::npos; });
}

} // namespace

TEST(DicomData, GeHeadTiltAndVariableSpacing) {
    const SeriesInfo series =
        seriesOf(filesIn(dataDir() / "dicom/ct_head_ge_hispeed_tilt_varspacing"));
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 1u);
    const VolumePlan& plan = assembly.volumes[0];
    EXPECT_EQ(plan.dims, glm::ivec3(512, 512, 28));
    EXPECT_EQ(plan.voxelType, volume::VoxelType::Int16);
    EXPECT_NEAR(plan.tiltDegrees, 18.5, 0.5);
    EXPECT_TRUE(plan.unevenGaps);
    EXPECT_LT(plan.minGap, plan.maxGap * 0.5);
    // Sorted along the normal: offsets increase monotonically.
    for (int k = 1; k < 28; ++k)
        EXPECT_GT(plan.geometry.sliceOffset(k), plan.geometry.sliceOffset(k - 1));
    const volume::Volume v = loadVolume(series, plan);
    const volume::ValueRange range = v.realRange();
    EXPECT_GE(range.min, -1500.0);
    EXPECT_LE(range.min, -1000.0);
    EXPECT_GT(range.max, 1000.0);
}

TEST(DicomData, DemoStudyIsALosslessCopyOfTheGeSeries) {
    // resources/demo ships the GE series recompressed with JPEG-LS lossless (its README says
    // so): the assembled volumes must match voxel for voxel, and the geometry exactly.
    const SeriesInfo original =
        seriesOf(filesIn(dataDir() / "dicom/ct_head_ge_hispeed_tilt_varspacing"));
    const SeriesInfo demo =
        seriesOf(filesIn(lw::test::sourceDir() / "resources/demo/ct_head_ge_tilt"));
    for (const auto& instance : demo.instances)
        EXPECT_EQ(instance.transferSyntaxUid, "1.2.840.10008.1.2.4.80") << instance.path;
    const SeriesAssembly a = planVolumes(original), b = planVolumes(demo);
    ASSERT_EQ(a.volumes.size(), 1u);
    ASSERT_EQ(b.volumes.size(), 1u);
    const volume::Volume va = loadVolume(original, a.volumes[0]);
    const volume::Volume vb = loadVolume(demo, b.volumes[0]);
    EXPECT_EQ(va.dims(), vb.dims());
    EXPECT_TRUE(bytesOf(va) == bytesOf(vb)) << "demo voxels differ from the original series";
    for (int k = 0; k < va.dims().z; ++k)
        EXPECT_EQ(va.geometry().indexToPatient({0, 0, double(k)}),
                  vb.geometry().indexToPatient({0, 0, double(k)}));
}

TEST(DicomData, Wg04LosslessEncodingsMatchUncompressed) {
    const fs::path dir = dataDir() / "dicom/ct_single_slices_nema_wg04_compression";
    for (const std::string ct : {"CT1", "CT2"}) {
        const auto reference = decodeFile(dir / (ct + "_UNC.dcm"));
        ASSERT_EQ(reference.size(), 512u * 512u);
        for (const std::string encoding : {"RLE", "JPLL", "JLSL", "J2KR"})
            EXPECT_EQ(maxAbsDifference(decodeFile(dir / (ct + "_" + encoding + ".dcm")), reference),
                      0)
                << ct << " " << encoding;
        // Near-lossless JPEG-LS (NEAR = 4 or less) and lossy JPEG 2000 stay close.
        EXPECT_LE(maxAbsDifference(decodeFile(dir / (ct + "_JLSN.dcm")), reference), 4) << ct;
        const int j2ki = maxAbsDifference(decodeFile(dir / (ct + "_J2KI.dcm")), reference);
        EXPECT_GT(j2ki, 0) << ct;
        EXPECT_LE(j2ki, 500) << ct;
    }
    const InstanceInfo ct1 = readInstanceHeader(dir / "CT1_UNC.dcm");
    EXPECT_DOUBLE_EQ(ct1.frames.at(0).rescaleIntercept, -1024.0);
    // CT1 and CT2 share a SeriesInstanceUID but are not one volume (different pixel spacing).
    const SeriesAssembly mixed = planVolumes(seriesOf({dir / "CT1_UNC.dcm", dir / "CT2_UNC.dcm"}));
    EXPECT_EQ(mixed.volumes.size(), 2u);
}

TEST(DicomData, MrSmallEncodingsIdentical) {
    const fs::path dir = dataDir() / "dicom/mr_single_slice_pydicom_small_ts_matrix";
    const auto reference = decodeFile(dir / "MR_small.dcm");
    ASSERT_EQ(reference.size(), 64u * 64u);
    for (const std::string name :
         {"MR_small_implicit", "MR_small_bigendian", "MR_small_expb", "MR_small_RLE",
          "MR_small_jp2klossless", "MR_small_jpeg_ls_lossless"})
        EXPECT_EQ(maxAbsDifference(decodeFile(dir / (name + ".dcm")), reference), 0) << name;
    // The same image padded, gzip-wrapped and truncated.
    const fs::path odd = dataDir() / "dicom-odd/pydicom_broken_and_unusual";
    EXPECT_EQ(maxAbsDifference(decodeFile(odd / "MR_small_padded.dcm"), reference), 0);
    EXPECT_EQ(maxAbsDifference(decodeFile(odd / "zipMR.gz"), reference), 0);
    EXPECT_TRUE(readInstanceHeader(odd / "zipMR.gz").isGzipWrapped);
    EXPECT_THROW(decodeFile(odd / "MR_truncated.dcm"), core::Error);
}

TEST(DicomData, Mr4SliceSeriesCopiesIdentical) {
    const fs::path dir = dataDir() / "dicom/mr_4slice_series_dicom2nifti_ts_matrix";
    std::vector<std::vector<std::byte>> volumes;
    for (const std::string folder :
         {"compressed_j2k", "compressed_jpeg", "compressed_jpegls", "compressed_rle"}) {
        const SeriesInfo series = seriesOf(filesIn(dir / folder));
        const SeriesAssembly assembly = planVolumes(series);
        ASSERT_EQ(assembly.volumes.size(), 1u) << folder;
        EXPECT_EQ(assembly.volumes[0].dims, glm::ivec3(256, 256, 4)) << folder;
        EXPECT_NEAR(assembly.volumes[0].minGap, 1.0, 1e-3) << folder;
        volumes.push_back(bytesOf(loadVolume(series, assembly.volumes[0])));
    }
    for (std::size_t i = 1; i < volumes.size(); ++i)
        EXPECT_TRUE(volumes[i] == volumes[0]) << i;
}

TEST(DicomData, EmriSmallEncodingsIdentical) {
    const fs::path dir = dataDir() / "dicom/mr_enhanced_multiframe_pydicom_emri_small";
    std::vector<std::vector<std::byte>> volumes;
    for (const std::string name : {"emri_small", "emri_small_big_endian", "emri_small_RLE",
                                   "emri_small_jpeg_2k_lossless", "emri_small_jpeg_ls_lossless"}) {
        const SeriesInfo series = seriesOf({dir / (name + ".dcm")});
        const SeriesAssembly assembly = planVolumes(series);
        ASSERT_EQ(assembly.volumes.size(), 1u) << name;
        EXPECT_EQ(assembly.volumes[0].dims, glm::ivec3(64, 64, 10)) << name;
        EXPECT_FALSE(assembly.volumes[0].warnings.empty()) << name; // no positions, no spacing
        volumes.push_back(bytesOf(loadVolume(series, assembly.volumes[0])));
    }
    for (std::size_t i = 1; i < volumes.size(); ++i)
        EXPECT_TRUE(volumes[i] == volumes[0]) << i;
}

TEST(DicomData, PhilipsFieldmapSplitsByFrameTypeAndRescale) {
    const SeriesInfo series =
        seriesOf({dataDir() / "dicom/mr_enhanced_multiframe_dcm_qa_enh/Philips/IM_0027_fMAP.dcm"});
    ASSERT_EQ(series.instances[0].frames.size(), 64u);
    const SeriesAssembly assembly = planVolumes(series);
    ASSERT_EQ(assembly.volumes.size(), 2u);
    bool sawMagnitude = false;
    bool sawFieldMap = false;
    for (const VolumePlan& plan : assembly.volumes) {
        EXPECT_EQ(plan.dims, glm::ivec3(64, 64, 32));
        if (std::abs(plan.valueMapping.slope - 1.2799) < 1e-3) {
            sawMagnitude = true;
            EXPECT_NEAR(plan.valueMapping.intercept, 0.0, 1e-9);
        } else if (std::abs(plan.valueMapping.slope - 0.2442) < 1e-3) {
            sawFieldMap = true;
            EXPECT_NEAR(plan.valueMapping.intercept, -500.0, 1e-6);
            EXPECT_NE(plan.label.find("FIELD_MAP"), std::string::npos) << plan.label;
        }
        EXPECT_NEAR(plan.geometry.spacingI(), 4.0, 1e-6);
    }
    EXPECT_TRUE(sawMagnitude);
    EXPECT_TRUE(sawFieldMap);
    const volume::Volume v = loadVolume(series, assembly.volumes[1]);
    EXPECT_GT(v.storedRange().max, 0.0);
}

TEST(DicomData, SiemensXa10MultiFrameFilesAreRepeats) {
    const SeriesInfo series =
        seriesOf(filesIn(dataDir() / "dicom/mr_enhanced_multiframe_dcm_qa_enh/Siemens_XA10"));
    const SeriesAssembly assembly = planVolumes(series);
    // 4 files of 6 frames at the same 6 positions: 4 volumes of 6 slices, never one of 24.
    ASSERT_EQ(assembly.volumes.size(), 4u);
    for (const VolumePlan& plan : assembly.volumes) {
        EXPECT_EQ(plan.dims, glm::ivec3(64, 64, 6));
        EXPECT_NEAR(plan.geometry.spacingI(), 3.375, 1e-6);
    }
}

TEST(DicomData, EnhancedCtAndPhilipsAnatomical) {
    const SeriesInfo ect = seriesOf(
        {dataDir() / "dicom/ct_enhanced_multiframe_nema_ect_supplemental/eCT_Supplemental.dcm"});
    EXPECT_TRUE(ect.instances[0].isEnhanced);
    const SeriesAssembly a = planVolumes(ect);
    ASSERT_EQ(a.volumes.size(), 1u);
    EXPECT_EQ(a.volumes[0].dims, glm::ivec3(512, 512, 2));
    EXPECT_DOUBLE_EQ(a.volumes[0].valueMapping.intercept, -1024.0);
    EXPECT_NEAR(a.volumes[0].geometry.spacingI(), 0.388672, 1e-5);
    EXPECT_NEAR(a.volumes[0].minGap, 10.0, 1e-3);
    const volume::Volume v = loadVolume(ect, a.volumes[0]);
    EXPECT_GT(v.storedRange().max, 500.0);

    // SOURCES.md calls these copies, but the implicit file is another acquisition: its
    // headers (checked with dcmdump) say slope 14.5966, 1 mm spacing, 0.9375 mm pixels.
    struct Expected {
        std::string name;
        double slope;
        double gap;
        double pixel;
    };
    for (const Expected& e : {Expected{"explicit_IM-0001-0170-0001.dcm", 4.25885, 1.2, 1.0},
                              Expected{"implicit_IM1.dcm", 14.59658, 1.0, 0.9375}}) {
        const SeriesInfo philips =
            seriesOf({dataDir() / "dicom/mr_enhanced_multiframe_philips_dicom2nifti" / e.name});
        const SeriesAssembly p = planVolumes(philips);
        ASSERT_EQ(p.volumes.size(), 1u) << e.name;
        EXPECT_EQ(p.volumes[0].dims, glm::ivec3(256, 256, 8)) << e.name;
        EXPECT_NEAR(p.volumes[0].valueMapping.slope, e.slope, 1e-4) << e.name;
        EXPECT_NEAR(p.volumes[0].minGap, e.gap, 1e-3) << e.name;
        EXPECT_NEAR(p.volumes[0].maxGap, e.gap, 1e-3) << e.name;
        EXPECT_NEAR(p.volumes[0].geometry.spacingI(), e.pixel, 1e-6) << e.name;
    }
}

TEST(DicomData, JpegExtendedAndDeflate) {
    const fs::path dir = dataDir() / "dicom/misc_single_slice_pydicom_jpeg_extended_and_deflate";
    for (const std::string name :
         {"JPGExtended.dcm", "image_dfl.dcm", "JPGLosslessP14SV1_1s_1f_8b.dcm"}) {
        const auto values = decodeFile(dir / name);
        ASSERT_FALSE(values.empty()) << name;
        const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
        EXPECT_LT(*lo, *hi) << name; // a real image, not a constant
    }
    EXPECT_EQ(readInstanceHeader(dir / "image_dfl.dcm").transferSyntaxUid,
              "1.2.840.10008.1.2.1.99");
    const auto extended = decodeFile(dir / "JPGExtended.dcm");
    EXPECT_LT(*std::max_element(extended.begin(), extended.end()), 4096); // 12-bit
}

TEST(DicomData, TwelveBitWithGarbageHighBits) {
    const fs::path dir = dataDir() / "dicom-odd/bits_stored_12_signed_unsigned_dcm_qa_12bit";
    for (const std::string name : {"12bitUnsigned.dcm", "12bitUnsigned_0x0F0F.dcm"}) {
        const auto values = decodeFile(dir / name);
        EXPECT_GE(*std::min_element(values.begin(), values.end()), 0) << name;
        EXPECT_LT(*std::max_element(values.begin(), values.end()), 4096) << name;
    }
    const auto signedValues = decodeFile(dir / "12bitSigned_0x0F0F.dcm");
    EXPECT_GE(*std::min_element(signedValues.begin(), signedValues.end()), -2048);
    EXPECT_LE(*std::max_element(signedValues.begin(), signedValues.end()), 2047);
    EXPECT_LT(*std::min_element(signedValues.begin(), signedValues.end()),
              0); // sign-extended, not masked only
}

TEST(DicomData, FragmentedJpegLosslessEqualsGzipWrapped) {
    const SeriesInfo fragmented = seriesOf(
        filesIn(dataDir() / "dicom-odd/fragmented_jpeg_lossless_series_mr_t1_96_dcm_qa_frag"));
    const SeriesInfo gzipped =
        seriesOf(filesIn(dataDir() / "dicom-odd/gzip_wrapped_series_mr_t1_96_dcm_qa_xa30i"));
    const SeriesAssembly a = planVolumes(fragmented);
    const SeriesAssembly b = planVolumes(gzipped);
    ASSERT_EQ(a.volumes.size(), 1u);
    ASSERT_EQ(b.volumes.size(), 1u);
    EXPECT_EQ(a.volumes[0].dims, glm::ivec3(128, 128, 96));
    EXPECT_EQ(b.volumes[0].dims, glm::ivec3(128, 128, 96));
    EXPECT_TRUE(gzipped.instances[0].isGzipWrapped);
    const volume::Volume va = loadVolume(fragmented, a.volumes[0]);
    const volume::Volume vb = loadVolume(gzipped, b.volumes[0]);
    EXPECT_TRUE(bytesOf(va) == bytesOf(vb));
    EXPECT_GT(va.storedRange().max, 100.0);
}

TEST(DicomData, J2kPrecisionMismatchDecodesSensibly) {
    const fs::path dir = dataDir() / "dicom-odd/pydicom_broken_and_unusual";
    // BitsStored disagrees with the codestream; the uncompressed copies show the true values.
    EXPECT_EQ(maxAbsDifference(decodeFile(dir / "693_J2KR.dcm"), decodeFile(dir / "693_UNCR.dcm")),
              0);
    EXPECT_EQ(maxAbsDifference(decodeFile(dir / "693_J2KI.dcm"), decodeFile(dir / "693_UNCI.dcm")),
              0);
    const auto mismatch = decodeFile(dir / "J2K_pixelrep_mismatch.dcm");
    const auto [lo, hi] = std::minmax_element(mismatch.begin(), mismatch.end());
    EXPECT_GE(*lo, -4096); // CT range, not 16-bit garbage
    EXPECT_LE(*hi, 4095);
    EXPECT_LT(*lo, 0);
}

TEST(DicomData, BrokenFilesGiveClearErrors) {
    const fs::path dir = dataDir() / "dicom-odd/pydicom_broken_and_unusual";
    for (const std::string name : {"rtplan_truncated.dcm", "no_meta.dcm"})
        EXPECT_THROW(readInstanceHeader(dir / name), core::Error) << name;
    // Non-image objects read fine but have no pixels.
    for (const std::string name :
         {"rtstruct.dcm", "test-SR.dcm", "ExplVR_BigEndNoMeta.dcm", "ExplVR_LitEndNoMeta.dcm"}) {
        const InstanceInfo info = readInstanceHeader(dir / name);
        EXPECT_FALSE(info.hasPixelData) << name;
    }
    EXPECT_EQ(readInstanceHeader(dir / "explicit_VR-UN.dcm").modality, "CT"); // UN converted
    const SeriesAssembly rowsMissing =
        planVolumes(seriesOf(filesIn(dataDir() / "dicom-odd/missing_rows_dwv")));
    EXPECT_TRUE(rowsMissing.volumes.empty());
    EXPECT_EQ(rowsMissing.errors.size(), 1u);
    // ACR-NEMA: no preamble, no meta, implicit VR; decodes to a 1-slice volume.
    const SeriesInfo acr =
        seriesOf(filesIn(dataDir() / "dicom-odd/acrnema_no_preamble_ct_lumbar_barre"));
    const SeriesAssembly plan = planVolumes(acr);
    ASSERT_EQ(plan.volumes.size(), 1u);
    EXPECT_EQ(plan.volumes[0].dims, glm::ivec3(512, 512, 1));
    EXPECT_GT(loadVolume(acr, plan.volumes[0]).storedRange().max, 1000.0);
    EXPECT_TRUE(
        isDicomdirFile(dataDir() / "dicom/ct_headphantom_philips_dicomdir_export/DICOMDIR"));
    EXPECT_FALSE(isDicomdirFile(dir / "MR_small_padded.dcm"));
}

TEST(DicomData, Dicom2niftiSeriesDefects) {
    const fs::path dir = dataDir() / "dicom-odd/series_defects_dicom2nifti";
    const SeriesAssembly notVolume = planVolumes(seriesOf(filesIn(dir / "notavolume")));
    EXPECT_TRUE(notVolume.volumes.empty());
    EXPECT_TRUE(anyContains(notVolume.warnings, "share one position"));

    const SeriesAssembly tilt = planVolumes(seriesOf(filesIn(dir / "gantrytilting")));
    ASSERT_EQ(tilt.volumes.size(), 1u);
    EXPECT_GT(tilt.volumes[0].tiltDegrees, 1.0);

    for (const std::string folder : {"sliceincrement", "sliceincrement_002"}) {
        const SeriesAssembly gaps = planVolumes(seriesOf(filesIn(dir / folder)));
        ASSERT_EQ(gaps.volumes.size(), 1u) << folder;
        EXPECT_TRUE(gaps.volumes[0].unevenGaps) << folder;
        EXPECT_EQ(gaps.volumes[0].missingSlices, 1) << folder;
    }
    const SeriesAssembly orientations = planVolumes(seriesOf(filesIn(dir / "sliceorientation")));
    EXPECT_EQ(orientations.volumes.size(), 2u);
    const SeriesAssembly two = planVolumes(seriesOf(filesIn(dir / "slicecount")));
    ASSERT_EQ(two.volumes.size(), 1u);
    EXPECT_EQ(two.volumes[0].dims.z, 2);
}

namespace {

bool isJpeg2000Syntax(const std::string& uid) {
    return uid.rfind("1.2.840.10008.1.2.4.9", 0) == 0;
}

// FNV-1a over the decoded values of every frame, or the error text when decoding fails.
std::string decodedChecksum(const fs::path& path) {
    try {
        std::uint64_t hash = 14695981039346656037ull;
        for (const std::int32_t value : decodeFile(path)) {
            hash ^= std::uint32_t(value);
            hash *= 1099511628211ull;
        }
        char text[17];
        std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
        return text;
    } catch (const core::Error&) {
        return "error";
    }
}

} // namespace

// Every JPEG 2000 file of the shared data decodes to the values GDCM produced before the
// decoder moved to OpenJPEG (recorded with GDCM 3.0.21 at commit 76ec329), and the files
// GDCM could not decode still fail cleanly. A new J2K file in the data must be added here.
TEST(DicomData, Jpeg2000FilesDecodeAsRecordedWithGdcm) {
    const std::map<std::string, std::string> recorded = {
        {"dicom-odd/pydicom_broken_and_unusual/693_J2KI.dcm", "fed8b701b918806b"},
        {"dicom-odd/pydicom_broken_and_unusual/693_J2KR.dcm", "686424c8340208c2"},
        {"dicom-odd/pydicom_broken_and_unusual/J2K_pixelrep_mismatch.dcm", "c66d2a60d35ff453"},
        {"dicom-odd/pydicom_broken_and_unusual/JPEG2000-embedded-sequence-delimiter.dcm", "error"},
        {"dicom-odd/pydicom_broken_and_unusual/explicit_VR-UN.dcm", "44bf705550d0b509"},
        {"dicom-odd/transfer_syntax_matrix_dcm_qa_ts/9.dcm", "9b748617abce10d0"},
        {"dicom/ct_single_slices_nema_wg04_compression/CT1_J2KI.dcm", "0522068181739c78"},
        {"dicom/ct_single_slices_nema_wg04_compression/CT1_J2KR.dcm", "4e84869105bacf8a"},
        {"dicom/ct_single_slices_nema_wg04_compression/CT2_J2KI.dcm", "ff57c0ab6826489f"},
        {"dicom/ct_single_slices_nema_wg04_compression/CT2_J2KR.dcm", "6660440f7f9f201a"},
        {"dicom/mr_4slice_series_dicom2nifti_ts_matrix/compressed_j2k/IM-0001-0001-0001.dcm",
         "dd6847bdcb0f1993"},
        {"dicom/mr_4slice_series_dicom2nifti_ts_matrix/compressed_j2k/IM-0001-0002-0001.dcm",
         "0ca5cf1a917b5810"},
        {"dicom/mr_4slice_series_dicom2nifti_ts_matrix/compressed_j2k/IM-0001-0003-0001.dcm",
         "17d0edec9ed36a97"},
        {"dicom/mr_4slice_series_dicom2nifti_ts_matrix/compressed_j2k/IM-0001-0004-0001.dcm",
         "b3dc411f7dd92ec8"},
        {"dicom/mr_enhanced_multiframe_pydicom_emri_small/emri_small_jpeg_2k_lossless.dcm",
         "ffa2c120646329ad"},
        {"dicom/mr_single_slice_pydicom_small_ts_matrix/MR_small_jp2klossless.dcm",
         "59cb1ff87f73feb1"},
    };
    std::map<std::string, std::string> found;
    for (const auto& entry : fs::recursive_directory_iterator(dataDir())) {
        if (!entry.is_regular_file())
            continue;
        std::string syntax;
        try {
            syntax = readInstanceHeader(entry.path()).transferSyntaxUid;
        } catch (const core::Error&) {
            continue; // not DICOM, or a header that cannot be read: not this test's business
        }
        if (isJpeg2000Syntax(syntax))
            found[fs::relative(entry.path(), dataDir()).generic_string()] =
                decodedChecksum(entry.path());
    }
    EXPECT_EQ(found, recorded);
}

namespace {

const char* const kJpeg2000File = "dicom-odd/transfer_syntax_matrix_dcm_qa_ts/9.dcm";

std::string fileBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// A copy of `source` with `replacement` written at the first occurrence of `anchor` plus `skip`.
fs::path changedCopy(const fs::path& source, const fs::path& target, std::string_view anchor,
                     std::size_t skip, std::string_view replacement) {
    std::string bytes = fileBytes(source);
    const std::size_t at = bytes.find(anchor);
    if (at == std::string::npos)
        throw std::runtime_error("anchor not found in " + source.string());
    bytes.replace(at + skip, replacement.size(), replacement);
    writeBytes(target, bytes);
    return target;
}

const std::string kSamplesPerPixelTag("\x28\x00\x02\x00", 4);
const std::string kImagePositionTag("\x20\x00\x32\x00", 4);
const std::string kSizMarker("\xFF\x4F\xFF\x51", 4);

} // namespace

// Issue 10: two changed bytes, the VR of SamplesPerPixel or of ImagePositionPatient made UL,
// made GDCM (which re-parsed the file to decode JPEG 2000) fail an assertion and abort the
// process. OpenJPEG now decodes the fragments DCMTK parsed: the file loads, pixels unchanged.
TEST(DicomData, Jpeg2000FileWithAWrongVrLoadsWithItsPixels) {
    const fs::path source = dataDir() / kJpeg2000File;
    const auto intact = decodeFile(source);
    lw::test::TempDir dir;
    for (const std::string& tag : {kSamplesPerPixelTag, kImagePositionTag}) {
        const fs::path damaged = changedCopy(source, dir / "damaged.dcm", tag, 4, "UL");
        EXPECT_EQ(decodeFile(damaged), intact);
        SeriesInfo series = seriesOf({damaged});
        const SeriesAssembly plan = planVolumes(series);
        ASSERT_EQ(plan.volumes.size(), 1u);
        EXPECT_EQ(loadVolume(series, plan.volumes[0]).dims(), glm::ivec3(384, 384, 1));
    }
}

// Two bytes of the codestream's SIZ marker changed (its width): a clear core::Error naming the
// file, raised before OpenJPEG allocates for the wrong size.
TEST(DicomData, Jpeg2000CodestreamOfTheWrongSizeIsAnError) {
    lw::test::TempDir dir;
    // Xsiz is 6 bytes after the marker: its low half-word 0x0180 (384) becomes 0x4000.
    const fs::path damaged = changedCopy(dataDir() / kJpeg2000File, dir / "wide.dcm", kSizMarker,
                                         2 + 6 + 2, std::string("\x40\x00", 2));
    try {
        (void)decodeFile(damaged);
        ADD_FAILURE() << "a codestream wider than the header was decoded";
    } catch (const core::Error& error) {
        EXPECT_NE(error.subject().find("wide.dcm"), std::string::npos) << error.subject();
        EXPECT_NE(error.reason().find("the header says 384x384"), std::string::npos)
            << error.reason();
    }
}

// Two bytes set to FF FF at every third position of the codestream's first 300 bytes (the
// main header and the first tile-part): each decodes or fails with core::Error, none aborts.
TEST(DicomData, DamagedJpeg2000CodestreamsNeverAbort) {
    const fs::path source = dataDir() / kJpeg2000File;
    const std::string bytes = fileBytes(source);
    const std::size_t codestream = bytes.find(kSizMarker);
    ASSERT_NE(codestream, std::string::npos);
    lw::test::TempDir dir;
    int errors = 0, decoded = 0;
    for (std::size_t offset = 4; offset < 300; offset += 3) {
        std::string damaged = bytes;
        damaged.replace(codestream + offset, 2, "\xFF\xFF");
        writeBytes(dir / "damaged.dcm", damaged);
        try {
            (void)decodeFile(dir / "damaged.dcm");
            ++decoded;
        } catch (const core::Error& error) {
            EXPECT_FALSE(error.reason().empty());
            ++errors;
        }
    }
    EXPECT_GT(errors, 0);
    EXPECT_EQ(errors + decoded, 99);
}
