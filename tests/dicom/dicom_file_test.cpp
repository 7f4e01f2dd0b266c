// Reading headers and decoding frames of files the test writes itself (known ground truth).
#include "dicom_file.h"
#include "dicom_test_writer.h"
#include "test_support.h"

#include "lw/core/error.h"
#include "lw/core/file_util.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <fstream>
#include <sys/resource.h>
#include <zlib.h>

namespace dt = lw::dicom::test;
using namespace lw;
using namespace lw::dicom;
using lw::dicom::test::TestSlice;
using lw::dicom::test::TestTransferSyntax;

namespace {

TestSlice ctSlice() {
    TestSlice s;
    // Not smaller: DCMTK 3.6.7's JPEG-LS encoder overruns its buffer on tiny images.
    s.rows = 24;
    s.columns = 20;
    s.pixels = dt::rampPixels(24, 20, -1000, 37);
    s.position = glm::dvec3(-10.5, 20.25, 33.0);
    s.orientation = std::array<double, 6>{1, 0, 0, 0, 0.8, -0.6};
    s.pixelSpacing = glm::dvec2(0.7, 0.9);
    s.rescaleSlope = 1.5;
    s.rescaleIntercept = -1024;
    s.instanceNumber = 7;
    s.seriesDescription = "head  ";
    return s;
}

std::vector<std::int16_t> decodeInt16(const InstanceInfo& info, int frame = 0) {
    FrameDecoder decoder(info);
    std::vector<std::int16_t> out(std::size_t(info.rows) * std::size_t(info.columns));
    decoder.decodeFrame(frame, volume::VoxelType::Int16, out.data());
    return out;
}

} // namespace

TEST(DicomFile, ReadsClassicHeader) {
    lw::test::TempDir dir;
    TestSlice s = ctSlice();
    dt::writeTestSlice(dir / "a.dcm", s);
    const InstanceInfo info = readInstanceHeader(dir / "a.dcm");
    EXPECT_EQ(info.rows, 24);
    EXPECT_EQ(info.columns, 20);
    EXPECT_EQ(info.bitsAllocated, 16);
    EXPECT_EQ(info.pixelRepresentation, 1);
    EXPECT_EQ(info.modality, "CT");
    EXPECT_EQ(info.seriesDescription, "head"); // trimmed
    EXPECT_EQ(info.instanceNumber, 7);
    EXPECT_TRUE(info.hasPixelData);
    EXPECT_FALSE(info.isEnhanced);
    EXPECT_FALSE(info.isGzipWrapped);
    EXPECT_EQ(info.transferSyntaxUid, "1.2.840.10008.1.2.1");
    ASSERT_EQ(info.frames.size(), 1u);
    const FrameInfo& f = info.frames[0];
    ASSERT_TRUE(f.position);
    EXPECT_DOUBLE_EQ(f.position->x, -10.5);
    EXPECT_DOUBLE_EQ(f.position->y, 20.25);
    ASSERT_TRUE(f.orientation);
    EXPECT_DOUBLE_EQ((*f.orientation)[4], 0.8);
    EXPECT_DOUBLE_EQ((*f.orientation)[5], -0.6);
    ASSERT_TRUE(f.pixelSpacing);
    EXPECT_DOUBLE_EQ(f.pixelSpacing->x, 0.7);
    EXPECT_DOUBLE_EQ(f.rescaleSlope, 1.5);
    EXPECT_DOUBLE_EQ(f.rescaleIntercept, -1024);
    EXPECT_EQ(f.frameType, "ORIGINAL\\PRIMARY\\AXIAL");
    EXPECT_EQ(storedVoxelType(info), volume::VoxelType::Int16);
}

TEST(DicomFile, RejectsNonDicomAndMissingFiles) {
    lw::test::TempDir dir;
    {
        std::ofstream out(dir / "text.dcm");
        out << "This is certainly not a DICOM file, just some words of text.\n";
    }
    EXPECT_THROW(readInstanceHeader(dir / "text.dcm"), core::Error);
    EXPECT_THROW(readInstanceHeader(dir / "missing.dcm"), core::Error);
    {
        std::ofstream out(dir / "empty.dcm");
    }
    EXPECT_THROW(readInstanceHeader(dir / "empty.dcm"), core::Error);
    EXPECT_FALSE(isDicomdirFile(dir / "text.dcm"));
}

TEST(DicomFile, TransferSyntaxesReadAndDecodeIdentically) {
    lw::test::TempDir dir;
    TestSlice s = ctSlice();
    const std::vector<int> expected = s.pixels;
    for (TestTransferSyntax syntax :
         {TestTransferSyntax::ExplicitLittle, TestTransferSyntax::ImplicitLittle, TestTransferSyntax::ExplicitBig,
          TestTransferSyntax::Deflated, TestTransferSyntax::JpegLossless, TestTransferSyntax::JpegLsLossless,
          TestTransferSyntax::Rle}) {
        s.transferSyntax = syntax;
        const std::string uid = dt::transferSyntaxUid(syntax);
        const auto path = dir / (uid + ".dcm");
        dt::writeTestSlice(path, s);
        const InstanceInfo info = readInstanceHeader(path);
        EXPECT_EQ(info.transferSyntaxUid, uid);
        ASSERT_EQ(info.frames.size(), 1u) << uid;
        ASSERT_TRUE(info.frames[0].position) << uid;
        EXPECT_DOUBLE_EQ(info.frames[0].position->z, 33.0) << uid;
        const auto pixels = decodeInt16(info);
        for (std::size_t i = 0; i < expected.size(); ++i)
            ASSERT_EQ(pixels[i], expected[i]) << uid << " pixel " << i;
    }
}

TEST(DicomFile, GzipWrappedFile) {
    lw::test::TempDir dir;
    TestSlice s = ctSlice();
    dt::writeTestSlice(dir / "plain.dcm", s);
    const auto bytes = core::readFileBytes(dir / "plain.dcm");
    {
        gzFile gz = gzopen((dir / "wrapped.dcm.gz").c_str(), "wb");
        ASSERT_NE(gz, nullptr);
        ASSERT_EQ(gzwrite(gz, bytes.data(), unsigned(bytes.size())), int(bytes.size()));
        gzclose(gz);
    }
    const InstanceInfo info = readInstanceHeader(dir / "wrapped.dcm.gz");
    EXPECT_TRUE(info.isGzipWrapped);
    EXPECT_EQ(info.rows, 24);
    ASSERT_TRUE(info.frames.at(0).position);
    EXPECT_DOUBLE_EQ(info.frames[0].position->y, 20.25);
    const auto pixels = decodeInt16(info);
    for (std::size_t i = 0; i < s.pixels.size(); ++i)
        ASSERT_EQ(pixels[i], s.pixels[i]);

    // The decoder inflates within the caller's limits, not the default ones.
    core::ImportLimits tight;
    tight.maxBytes = bytes.size() / 2;
    FrameDecoder decoder(info, tight);
    std::vector<std::int16_t> out(std::size_t(info.rows) * std::size_t(info.columns));
    try {
        decoder.decodeFrame(0, volume::VoxelType::Int16, out.data());
        FAIL() << "the decoder inflated past the caller's limit";
    } catch (const core::Error& e) {
        EXPECT_NE(std::string(e.what()).find("inflates to more than"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("wrapped.dcm.gz"), std::string::npos) << e.what();
    }
}

namespace {

// Peak resident memory of this process so far, in MB.
long peakRssMb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1024;
}

constexpr std::uint32_t kBombPixelBytes = 65535u * 32768u * 2u; // what the bomb's header declares

} // namespace

// A deflated file declaring 65535 x 32768 16-bit pixels over a stream of zeros: DCMTK inflated
// all of it while reading the header (19 s and 4.2 GB for the 4 GiB version). The header is
// now read in front of the pixel data: fast, small, and with the declared length.
TEST(DicomFile, DeflateBombHeaderReadIsBounded) {
    lw::test::TempDir dir;
    dt::HandMadeImage bomb;
    bomb.rows = 65535;
    bomb.columns = 32768;
    bomb.deflate = true;
    bomb.pixelDataBytes = std::size_t(256) << 20; // enough to cost seconds when inflated
    bomb.declaredPixelDataLength = kBombPixelBytes;
    dt::writeHandMadeImage(dir.path() / "bomb.dcm", bomb);

    core::ImportLimits roomy;
    roomy.maxBytes = std::size_t(8) << 30; // the declaration itself fits: only the read is tested
    const long rssBefore = peakRssMb();
    const auto start = std::chrono::steady_clock::now();
    const InstanceInfo info = readInstanceHeader(dir.path() / "bomb.dcm", roomy);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 1.0);
    EXPECT_LT(peakRssMb() - rssBefore, 64);
    EXPECT_EQ(info.transferSyntaxUid, "1.2.840.10008.1.2.1.99");
    EXPECT_TRUE(info.hasPixelData);
    ASSERT_TRUE(info.nativePixelDataBytes.has_value());
    EXPECT_EQ(*info.nativePixelDataBytes, kBombPixelBytes);

    // With a limit below the declaration it is refused, just as fast, with the reason.
    core::ImportLimits tight;
    tight.maxBytes = std::size_t(1) << 30;
    const auto refusedStart = std::chrono::steady_clock::now();
    try {
        readInstanceHeader(dir.path() / "bomb.dcm", tight);
        FAIL() << "a declaration over the limit was accepted";
    } catch (const core::Error& e) {
        EXPECT_NE(std::string(e.what()).find("import limit"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("bomb.dcm"), std::string::npos) << e.what();
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - refusedStart).count(), 1.0);
}

// A header longer than the first inflated prefix (a 300 KB private element in front of the
// pixel data) is still read whole, and the pixels decode.
TEST(DicomFile, DeflatedLongHeaderReadsAndDecodes) {
    lw::test::TempDir dir;
    dt::HandMadeImage image;
    image.deflate = true;
    image.privateBytesBeforePixels = 300 * 1024;
    dt::writeHandMadeImage(dir.path() / "long.dcm", image);
    const InstanceInfo info = readInstanceHeader(dir.path() / "long.dcm");
    EXPECT_EQ(info.rows, 4);
    EXPECT_EQ(info.modality, "CT");
    ASSERT_TRUE(info.nativePixelDataBytes.has_value());
    EXPECT_EQ(*info.nativePixelDataBytes, 32u);
    EXPECT_EQ(decodeInt16(info), std::vector<std::int16_t>(16, 0));
}

// Loading the pixels inflates no further than the header's declaration allows: 4 x 4 pixels
// followed by 64 MB of zeros is refused with the reason instead of being inflated.
TEST(DicomFile, DeflatedPixelsBeyondTheDeclarationAreRefused) {
    lw::test::TempDir dir;
    dt::HandMadeImage image;
    image.deflate = true;
    image.pixelDataBytes = std::size_t(64) << 20;
    dt::writeHandMadeImage(dir.path() / "long_pixels.dcm", image);
    const InstanceInfo info = readInstanceHeader(dir.path() / "long_pixels.dcm");
    try {
        decodeInt16(info);
        FAIL() << "64 MB of pixel data for 4 x 4 pixels was inflated";
    } catch (const core::Error& e) {
        EXPECT_NE(std::string(e.what()).find("more than its header declares"), std::string::npos) << e.what();
    }
}

namespace {

constexpr std::uint32_t kLyingLength = 3u << 30; // 3 GB declared over far fewer bytes

// Reads the header of `image` under `limits`; the reason it was refused (empty when accepted).
std::string headerRefusal(const std::filesystem::path& path, const dt::HandMadeImage& image,
                          const core::ImportLimits& limits) {
    dt::writeHandMadeImage(path, image);
    try {
        readInstanceHeader(path, limits);
    } catch (const core::Error& e) {
        return e.what();
    }
    return {};
}

core::ImportLimits roomyLimits() {
    core::ImportLimits roomy;
    roomy.maxBytes = std::size_t(8) << 30; // the lie fits: only the stream's end can refute it
    return roomy;
}

} // namespace

// An element in front of the pixel data declaring 3 GB over 256 KB: DCMTK allocated the
// declared length while parsing the first inflated prefix (64 KB). The prefix's element headers
// are walked first: the stream ends short of the declaration and the file is refused, naming
// the element; under a smaller import limit the declaration itself is refused, without
// inflating past the first prefix.
TEST(DicomFile, DeflatedHeaderElementLongerThanTheStreamIsRefused) {
    lw::test::TempDir dir;
    dt::HandMadeImage image;
    image.deflate = true;
    image.privateBytesBeforePixels = std::size_t(256) << 10;
    image.declaredPrivateLength = kLyingLength;
    const long rssBefore = peakRssMb();
    const auto start = std::chrono::steady_clock::now();
    const std::string refusal = headerRefusal(dir.path() / "lying.dcm", image, roomyLimits());
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    EXPECT_LT(peakRssMb() - rssBefore, 64);
    EXPECT_NE(refusal.find("element (0029,1000) declares 3221225472 bytes"), std::string::npos)
        << refusal;
    EXPECT_NE(refusal.find("lying.dcm"), std::string::npos) << refusal;

    core::ImportLimits tight;
    tight.maxBytes = std::size_t(1) << 30;
    const std::string overLimit = headerRefusal(dir.path() / "lying.dcm", image, tight);
    EXPECT_NE(overLimit.find("import limit"), std::string::npos) << overLimit;
}

// A VR DICOM does not know ("ZZ") is read by DCMTK with a 4-byte length; the walk reads the
// same width, so a lie hidden behind an unknown VR is found too (the fuzz finding
// tests/data/fuzz/dicom_file/deflated_unknown_vr_declares_4gb.dcm did this after the pixels).
TEST(DicomFile, DeflatedUnknownVrIsMeasuredAsDcmtkReadsIt) {
    lw::test::TempDir dir;
    dt::HandMadeImage image;
    image.deflate = true;
    image.privateBytesBeforePixels = 16;
    image.privateVr = "ZZ";
    image.declaredPrivateLength = kLyingLength;
    const std::string refusal = headerRefusal(dir.path() / "zz.dcm", image, roomyLimits());
    EXPECT_NE(refusal.find("element (0029,1000) declares 3221225472 bytes"), std::string::npos)
        << refusal;

    // Told the truth, the unknown VR's value is skipped and the pixels decode.
    image.declaredPrivateLength.reset();
    EXPECT_EQ(headerRefusal(dir.path() / "zz.dcm", image, roomyLimits()), "");
    EXPECT_EQ(decodeInt16(readInstanceHeader(dir.path() / "zz.dcm")),
              std::vector<std::int16_t>(16, 0));
}

// The fuzz finding itself: its header reads (the lie is behind the pixel data), and loading
// the pixels refuses the whole data set before DCMTK parses it.
TEST(DicomFile, DeflatedFuzzFindingIsRefusedBeforeDcmtkAllocates) {
    const auto path =
        lw::test::sourceDir() / "tests/data/fuzz/dicom_file/deflated_unknown_vr_declares_4gb.dcm";
    const InstanceInfo info = readInstanceHeader(path);
    FrameDecoder decoder(info);
    std::vector<std::uint8_t> pixels(std::size_t(info.rows) * std::size_t(info.columns) * 2);
    try {
        decoder.decodeFrame(0, volume::VoxelType::Int16, pixels.data());
        FAIL() << "a 4 GB element in a 16 KB file was parsed";
    } catch (const core::Error& e) {
        EXPECT_NE(std::string(e.what()).find("element (5A5A,5A5A) declares 4174763477 bytes"),
                  std::string::npos)
            << e.what();
    }
}
