// Reading headers and decoding frames of files the test writes itself (known ground truth).
#include "dicom_file.h"
#include "dicom_test_writer.h"
#include "jpegls_decoder.h"
#include "test_support.h"

#include "lw/core/error.h"
#include "lw/core/file_util.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
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
}

// JPEG-LS goes through the system CharLS (C API), not DCMTK's bundled copy: pixel-identical to
// what was written, for single- and multi-frame objects, 16-bit signed/unsigned and 8-bit.
TEST(DicomFile, JpegLsDecodedByCharlsPixelIdentical) {
    if (!jpegls::available())
        GTEST_SKIP() << "built without CharLS";
    lw::test::TempDir dir;
    struct Case {
        const char* name;
        int bitsAllocated, bitsStored, pixelRepresentation, frames, start, step;
    };
    for (const Case c : {Case{"int16", 16, 16, 1, 1, -1000, 37}, Case{"uint12", 16, 12, 0, 1, 0, 7},
                         Case{"int16_multiframe", 16, 16, 1, 3, -3000, 11}, Case{"uint8", 8, 8, 0, 2, 0, 1}}) {
        TestSlice s = ctSlice();
        s.bitsAllocated = c.bitsAllocated;
        s.bitsStored = c.bitsStored;
        s.highBit = c.bitsStored - 1;
        s.pixelRepresentation = c.pixelRepresentation;
        s.numberOfFrames = c.frames;
        const int mod = 1 << c.bitsStored;
        const int low = c.pixelRepresentation ? -(mod / 2) : 0;
        s.pixels = dt::rampPixels(s.rows, s.columns * c.frames, c.start, c.step);
        for (int& v : s.pixels)
            v = ((v - low) % mod + mod) % mod + low; // within the stored range
        s.transferSyntax = TestTransferSyntax::JpegLsLossless;
        const auto path = dir / (std::string(c.name) + ".dcm");
        dt::writeTestSlice(path, s);
        const InstanceInfo info = readInstanceHeader(path);
        ASSERT_EQ(info.transferSyntaxUid, "1.2.840.10008.1.2.4.80") << c.name;
        ASSERT_EQ(info.numberOfFrames, c.frames) << c.name;

        const std::uint64_t before = jpegls::framesDecoded();
        FrameDecoder decoder(info);
        const std::size_t pixels = std::size_t(s.rows) * std::size_t(s.columns);
        for (int f = 0; f < c.frames; ++f) {
            std::vector<std::int32_t> got(pixels);
            if (c.bitsAllocated == 8) {
                std::vector<std::uint8_t> out(pixels);
                decoder.decodeFrame(f, volume::VoxelType::UInt8, out.data());
                std::copy(out.begin(), out.end(), got.begin());
            } else if (c.pixelRepresentation == 0) {
                std::vector<std::uint16_t> out(pixels);
                decoder.decodeFrame(f, volume::VoxelType::UInt16, out.data());
                std::copy(out.begin(), out.end(), got.begin());
            } else {
                std::vector<std::int16_t> out(pixels);
                decoder.decodeFrame(f, volume::VoxelType::Int16, out.data());
                std::copy(out.begin(), out.end(), got.begin());
            }
            for (std::size_t i = 0; i < pixels; ++i)
                ASSERT_EQ(got[i], s.pixels[std::size_t(f) * pixels + i]) << c.name << " frame " << f << " pixel " << i;
        }
        // The new path handled every frame (DCMTK's codec would leave the counter alone).
        EXPECT_EQ(jpegls::framesDecoded() - before, std::uint64_t(c.frames)) << c.name;
    }
}

// A corrupt JPEG-LS codestream: CharLS refuses it, the DCMTK / GDCM fallback is tried, and the
// caller gets a clear error (not a crash, not garbage).
TEST(DicomFile, CorruptJpegLsFallsBackAndFailsCleanly) {
    lw::test::TempDir dir;
    TestSlice s = ctSlice();
    s.transferSyntax = TestTransferSyntax::JpegLsLossless;
    dt::writeTestSlice(dir / "a.dcm", s);
    auto bytes = core::readFileBytes(dir / "a.dcm");
    // The JPEG-LS start-of-frame marker (FFF7): break its width.
    std::size_t sof = 0;
    for (std::size_t i = 0; i + 1 < bytes.size(); ++i)
        if (bytes[i] == std::byte{0xFF} && bytes[i + 1] == std::byte{0xF7}) {
            sof = i;
            break;
        }
    ASSERT_GT(sof, 0u);
    bytes[sof + 7] = std::byte{0x7F}; // width high byte: far more columns than the header says
    {
        std::ofstream out(dir / "b.dcm", std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }
    const InstanceInfo info = readInstanceHeader(dir / "b.dcm");
    const std::uint64_t before = jpegls::framesDecoded();
    EXPECT_THROW(decodeInt16(info), core::Error);
    EXPECT_EQ(jpegls::framesDecoded(), before);
}
