// JPEG 2000 frames split over several fragments (issue 10): the decoder finds each frame's
// fragments through the Basic Offset Table, or without one through the end-of-codestream marker,
// and a file of very many fragments costs one pass over them, not one pass per fragment. The
// files are made here from the shared enhanced MR (10 frames, one fragment each) with DCMTK.
#include "dicom_file.h"
#include "test_support.h"

#include <cstdint>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcpixel.h>
#include <dcmtk/dcmdata/dcpixseq.h>
#include <dcmtk/dcmdata/dcpxitem.h>
#include <gtest/gtest.h>
#include <vector>

using namespace lw;
using namespace lw::dicom;
namespace fs = std::filesystem;

namespace {

fs::path emriJpeg2000() {
    return *lw::test::sharedDataDir() /
           "dicom/mr_enhanced_multiframe_pydicom_emri_small/emri_small_jpeg_2k_lossless.dcm";
}

std::vector<std::int32_t> decodeAllFrames(const fs::path& path) {
    const InstanceInfo info = readInstanceHeader(path);
    const volume::VoxelType type = storedVoxelType(info);
    const std::size_t pixels = std::size_t(info.rows) * std::size_t(info.columns);
    std::vector<std::uint16_t> frame(pixels);
    std::vector<std::int32_t> all;
    FrameDecoder decoder(info);
    for (int f = 0; f < info.numberOfFrames; ++f) {
        decoder.decodeFrame(f, type, frame.data());
        all.insert(all.end(), frame.begin(), frame.end());
    }
    return all;
}

void appendItem(DcmPixelSequence& sequence, const std::uint8_t* bytes, std::size_t length) {
    auto* item = new DcmPixelItem(DcmTag(DCM_Item, EVR_OB));
    item->putUint8Array(bytes, Uint32(length));
    sequence.insert(item);
}

struct Layout {
    bool offsetTable = false;  // the Basic Offset Table filled in
    std::size_t emptyTail = 0; // empty fragments after the last frame's
};

// The shared file with each frame's codestream split in two fragments (at an even byte).
fs::path refragmented(const fs::path& target, const Layout& layout) {
    DcmFileFormat file;
    EXPECT_TRUE(file.loadFile(emriJpeg2000().c_str()).good());
    DcmDataset& data = *file.getDataset();
    const E_TransferSyntax xfer = data.getOriginalXfer();
    DcmElement* element = nullptr;
    EXPECT_TRUE(data.findAndGetElement(DCM_PixelData, element).good());
    auto* pixelData = static_cast<DcmPixelData*>(element);
    DcmPixelSequence* original = nullptr;
    EXPECT_TRUE(pixelData->getEncapsulatedRepresentation(xfer, nullptr, original).good());

    std::vector<std::uint8_t> table;
    auto* split = new DcmPixelSequence(DCM_PixelSequenceTag);
    appendItem(*split, nullptr, 0); // the table, filled in below
    std::uint32_t offset = 0;
    for (unsigned long i = 1; i < original->card(); ++i) {
        DcmPixelItem* fragment = nullptr;
        Uint8* bytes = nullptr;
        original->getItem(fragment, i);
        fragment->getUint8Array(bytes);
        const std::size_t length = fragment->getLength(), half = (length / 2) & ~std::size_t(1);
        for (int shift = 0; shift < 32; shift += 8)
            table.push_back(std::uint8_t(offset >> shift));
        appendItem(*split, bytes, half);
        appendItem(*split, bytes + half, length - half);
        offset += std::uint32_t(8 + half + 8 + (length - half));
    }
    for (std::size_t i = 0; i < layout.emptyTail; ++i)
        appendItem(*split, nullptr, 0);
    if (layout.offsetTable) {
        DcmPixelItem* first = nullptr;
        split->getItem(first, 0);
        first->putUint8Array(table.data(), Uint32(table.size()));
    }
    pixelData->putOriginalRepresentation(xfer, nullptr, split);
    EXPECT_TRUE(file.saveFile(target.c_str(), xfer).good());
    return target;
}

} // namespace

TEST(Jpeg2000Fragments, FramesSplitOverFragmentsDecodeAsWhole) {
    const auto whole = decodeAllFrames(emriJpeg2000());
    ASSERT_EQ(whole.size(), 64u * 64u * 10u);
    lw::test::TempDir dir;
    EXPECT_EQ(decodeAllFrames(refragmented(dir / "table.dcm", {true, 0})), whole);
    EXPECT_EQ(decodeAllFrames(refragmented(dir / "markers.dcm", {false, 0})), whole);
}

// 200 000 empty fragments after the last frame (a 1.6 MB file): DCMTK's getItem(i) walks its
// list from the start, so reading them one by one took minutes; one pass takes milliseconds.
TEST(Jpeg2000Fragments, ManyFragmentsCostOnePass) {
    const auto whole = decodeAllFrames(emriJpeg2000());
    lw::test::TempDir dir;
    EXPECT_EQ(decodeAllFrames(refragmented(dir / "tail.dcm", {false, 200000})), whole);
}
