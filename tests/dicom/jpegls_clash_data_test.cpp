// This test binary loads the system CharLS 2 before DCMTK's own copy (link order), as a plug-in
// or another library could in an application. Both export JpegLsDecode with different ABIs, so
// DCMTK's JPEG-LS codec would call the wrong one: the decoder must refuse JPEG-LS with a clear
// error instead of crashing. Nothing in Linework links the system CharLS since JPEG 2000 moved
// from GDCM to OpenJPEG; this keeps the guard honest.
#include "dicom_file.h"
#include "lw/core/error.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <vector>

using namespace lw;
using namespace lw::dicom;

namespace {

void decodeFirstFrame(const std::filesystem::path& path) {
    const InstanceInfo info = readInstanceHeader(path);
    const volume::VoxelType type = storedVoxelType(info);
    std::vector<std::byte> frame(std::size_t(info.rows) * std::size_t(info.columns) *
                                 volume::voxelSize(type));
    FrameDecoder(info).decodeFrame(0, type, frame.data());
}

} // namespace

TEST(JpegLsClash, JpegLsIsRefusedAndOtherSyntaxesStillDecode) {
    const std::filesystem::path dir =
        *lw::test::sharedDataDir() / "dicom/mr_single_slice_pydicom_small_ts_matrix";
    try {
        decodeFirstFrame(dir / "MR_small_jpeg_ls_lossless.dcm");
        ADD_FAILURE() << "JPEG-LS decoded although the system CharLS was loaded first";
    } catch (const core::Error& error) {
        EXPECT_NE(error.reason().find("another CharLS library"), std::string::npos)
            << error.reason();
    }
    EXPECT_NO_THROW(decodeFirstFrame(dir / "MR_small_jp2klossless.dcm"));
    EXPECT_NO_THROW(decodeFirstFrame(dir / "MR_small_RLE.dcm"));
}
