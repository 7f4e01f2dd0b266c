#pragma once

// Test-only DICOM writer: synthetic CT/MR slices with exactly the attributes a test needs, in
// any transfer syntax DCMTK can write (including its JPEG lossless, JPEG-LS and RLE encoders).
// Tests build series with known geometry and pixels from these, so reader, decoder and
// assembler can be checked against ground truth instead of against themselves.
//
// Usage:
//   lw::dicom::test::TestSlice s;             // 4x4 int16 CT slice at (0,0,0), axial
//   s.rows = 8; s.columns = 8;
//   s.pixels = lw::dicom::test::rampPixels(8, 8, -100);  // stored values, row-major
//   s.position = {0, 0, 2.5};
//   s.seriesUid = seriesUid;                  // share one series UID across slices
//   s.transferSyntax = lw::dicom::test::TestTransferSyntax::JpegLossless;
//   lw::dicom::test::writeTestSlice(dir / "a.dcm", s);
//
// Stored pixel values are written exactly as given (bits above BitsStored included, so tests
// can put garbage there); signed values are written as their two's complement 16-bit words.

#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

namespace lw::dicom::test {

enum class TestTransferSyntax {
    ExplicitLittle,  // 1.2.840.10008.1.2.1
    ImplicitLittle,  // 1.2.840.10008.1.2
    ExplicitBig,     // 1.2.840.10008.1.2.2
    Deflated,        // 1.2.840.10008.1.2.1.99
    JpegLossless,    // 1.2.840.10008.1.2.4.70 (process 14, selection value 1)
    JpegLsLossless,  // 1.2.840.10008.1.2.4.80 (the test must link DCMTK::dcmjpls first with
                     // LINKER:--no-as-needed, see tests/dicom/CMakeLists.txt: a system CharLS clashes)
    Rle,             // 1.2.840.10008.1.2.5
};

// The transfer syntax UID written for `syntax`.
std::string transferSyntaxUid(TestTransferSyntax syntax);

struct TestSlice {
    int rows = 4;
    int columns = 4;
    int numberOfFrames = 1;  // > 1 writes a classic multi-frame object (NumberOfFrames)
    std::vector<int> pixels; // rows*columns*numberOfFrames stored values; empty = all zero
    bool writePixelData = true;
    int bitsAllocated = 16; // 8 or 16
    int bitsStored = 16;
    int highBit = 15;
    int pixelRepresentation = 1; // 0 unsigned, 1 signed
    std::string photometric = "MONOCHROME2";

    std::optional<glm::dvec3> position = glm::dvec3(0.0);                      // IPP; nullopt: not written
    std::optional<std::array<double, 6>> orientation = std::array<double, 6>{1, 0, 0, 0, 1, 0}; // IOP
    std::optional<glm::dvec2> pixelSpacing = glm::dvec2(1.0, 1.0);             // (row, column) spacing
    double sliceThickness = 1.0;
    std::optional<double> rescaleSlope = 1.0;     // nullopt: not written
    std::optional<double> rescaleIntercept = 0.0; // nullopt: not written

    std::string modality = "CT";
    std::string sopClassUid = "1.2.840.10008.5.1.4.1.1.2"; // CT Image Storage
    std::string imageType = "ORIGINAL\\PRIMARY\\AXIAL";
    std::string patientId = "LW-TEST";
    std::string patientName = "Test^Linework";
    std::string studyUid;       // generated when empty
    std::string seriesUid;      // generated when empty
    std::string sopInstanceUid; // generated when empty
    std::string seriesDescription = "synthetic";
    std::optional<int> seriesNumber = 1;
    std::optional<int> instanceNumber;
    std::optional<int> acquisitionNumber;

    TestTransferSyntax transferSyntax = TestTransferSyntax::ExplicitLittle;
};

// Writes `slice` as a DICOM Part 10 file (preamble + meta). Throws std::runtime_error when
// DCMTK cannot encode or write it.
void writeTestSlice(const std::filesystem::path& path, const TestSlice& slice);

// A fresh DICOM UID (DCMTK's generator).
std::string makeTestUid();

// rows*columns values start, start+1, ... row-major: every pixel distinct, orientation visible.
std::vector<int> rampPixels(int rows, int columns, int start = 0, int step = 1);

// A hostile image header written byte by byte (explicit VR little endian), with whatever the
// header claims and no check that it is consistent: 2^31-1 frames, 65535x65535 pixels, pixel
// data shorter than declared. A few hundred bytes; DCMTK would refuse to write most of these.
struct HandMadeImage {
    int rows = 4;
    int columns = 4;
    std::string numberOfFrames = "1"; // written as is (IS); empty: not written
    int bitsAllocated = 16;
    bool writePixelData = true;
    std::size_t pixelDataBytes = 32; // the element's value (zeros), its length as declared
    std::optional<std::uint32_t> declaredPixelDataLength; // a length other than pixelDataBytes
    // Deflated Explicit VR Little Endian: the data set after the meta group is raw-deflated,
    // its zeros streamed through zlib, so a bomb of hundreds of MB costs the test little.
    bool deflate = false;
    // A private element of this many zeros in front of the pixel data (0: none, unless a
    // declared length is given).
    std::size_t privateBytesBeforePixels = 0;
    // Its VR, written with a 4-byte length field ("ZZ", unknown to DICOM: DCMTK reads it so).
    std::string privateVr = "OB";
    // A length for it other than privateBytesBeforePixels (a header that lies).
    std::optional<std::uint32_t> declaredPrivateLength;
};
void writeHandMadeImage(const std::filesystem::path& path, const HandMadeImage& image);

} // namespace lw::dicom::test
