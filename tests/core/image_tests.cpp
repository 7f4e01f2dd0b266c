#include "lw/core/error.h"
#include "lw/core/file_util.h"
#include "lw/core/image.h"
#include "lw/core/image_compare.h"
#include "lw/core/png_io.h"
#include "test_support.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <random>
#include <zlib.h>

using namespace lw::core;

namespace {

// Noise plus gradients, so the encoder picks different filter types on different rows.
ImageRgba8 testImage(int width, int height, unsigned seed, bool grey = false, bool opaque = false) {
    std::mt19937 random(seed);
    ImageRgba8 image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const bool noisy = (y % 3) == 0;
            auto v = [&](int base) {
                return static_cast<std::uint8_t>(noisy ? random() & 0xff
                                                       : (base + 7 * x + 3 * y) & 0xff);
            };
            Rgba8 p{v(0), v(80), v(160), opaque ? std::uint8_t(255) : v(40)};
            if (grey)
                p = {p.r, p.r, p.r, 255};
            image.at(x, y) = p;
        }
    return image;
}

std::vector<std::byte> withFixedCrc(std::vector<std::byte> png, std::size_t chunkStart) {
    const std::uint32_t length =
        (std::uint32_t(png[chunkStart]) << 24) | (std::uint32_t(png[chunkStart + 1]) << 16) |
        (std::uint32_t(png[chunkStart + 2]) << 8) | std::uint32_t(png[chunkStart + 3]);
    const auto crc =
        crc32(0L, reinterpret_cast<const Bytef*>(png.data() + chunkStart + 4), length + 4);
    for (int i = 0; i < 4; ++i)
        png[chunkStart + 8 + length + std::size_t(i)] = std::byte((crc >> (24 - 8 * i)) & 0xff);
    return png;
}

// Where the chunk of `type` starts (its length field) in an encoded PNG.
std::size_t chunkAt(const std::vector<std::byte>& png, const char* type) {
    for (std::size_t pos = 8; pos + 12 <= png.size();) {
        const std::uint32_t length =
            (std::uint32_t(png[pos]) << 24) | (std::uint32_t(png[pos + 1]) << 16) |
            (std::uint32_t(png[pos + 2]) << 8) | std::uint32_t(png[pos + 3]);
        if (std::memcmp(png.data() + pos + 4, type, 4) == 0)
            return pos;
        pos += std::size_t(length) + 12;
    }
    ADD_FAILURE() << "no " << type << " chunk";
    return 0;
}

void expectDecodeError(const std::vector<std::byte>& bytes, const std::string& reasonPart) {
    try {
        decodePng(bytes.data(), bytes.size(), "test.png");
        FAIL() << "decoding succeeded, expected an error containing '" << reasonPart << "'";
    } catch (const Error& error) {
        EXPECT_EQ(error.subject(), "test.png");
        EXPECT_NE(error.reason().find(reasonPart), std::string::npos) << error.reason();
    }
}

} // namespace

TEST(Image, LayoutFillAndFlip) {
    ImageRgba8 image(3, 2, {1, 2, 3, 4});
    EXPECT_EQ(image.pixelCount(), 6u);
    EXPECT_EQ(image.at(2, 1), (Rgba8{1, 2, 3, 4}));
    image.at(0, 0) = {9, 9, 9, 9};
    EXPECT_EQ(image.bytes()[0], 9);
    EXPECT_EQ(image.bytes()[4], 1); // row-major, 4 bytes per pixel
    image.flipRows();
    EXPECT_EQ(image.at(0, 1), (Rgba8{9, 9, 9, 9}));
    EXPECT_EQ(image.at(0, 0), (Rgba8{1, 2, 3, 4}));
    EXPECT_THROW(ImageRgba8(-1, 2), Error);
}

TEST(Image, FloatToGrey) {
    ImageFloat depth(3, 1);
    depth.at(0, 0) = 0.0f;
    depth.at(1, 0) = 0.5f;
    depth.at(2, 0) = std::numeric_limits<float>::infinity();
    const ImageRgba8 grey = depth.toGrey(0.0f, 1.0f, {255, 0, 0, 255});
    EXPECT_EQ(grey.at(0, 0), (Rgba8{0, 0, 0, 255}));
    EXPECT_EQ(grey.at(1, 0), (Rgba8{128, 128, 128, 255}));
    EXPECT_EQ(grey.at(2, 0), (Rgba8{255, 0, 0, 255}));
}

TEST(PngIo, RoundTripRgbaOddSizes) {
    for (auto [w, h] : {std::pair{1, 1}, std::pair{7, 3}, std::pair{13, 5}, std::pair{64, 33},
                        std::pair{101, 2}}) {
        const ImageRgba8 image = testImage(w, h, unsigned(w * 31 + h));
        const auto bytes = encodePng(image, PngFormat::Rgba);
        PngFormat stored = PngFormat::Gray;
        const ImageRgba8 back = decodePng(bytes.data(), bytes.size(), "memory", &stored);
        EXPECT_EQ(stored, PngFormat::Rgba);
        EXPECT_EQ(back, image) << w << "x" << h;
    }
}

TEST(PngIo, RoundTripRgbDropsAlpha) {
    const ImageRgba8 image = testImage(17, 9, 5);
    const auto bytes = encodePng(image, PngFormat::Rgb);
    PngFormat stored = PngFormat::Rgba;
    const ImageRgba8 back = decodePng(bytes.data(), bytes.size(), "memory", &stored);
    EXPECT_EQ(stored, PngFormat::Rgb);
    ASSERT_EQ(back.width(), 17);
    ASSERT_EQ(back.height(), 9);
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 17; ++x) {
            Rgba8 expected = image.at(x, y);
            expected.a = 255;
            ASSERT_EQ(back.at(x, y), expected) << x << "," << y;
        }
}

// Whether every chunk of `png` (after the signature) carries the CRC-32 of its type and data, as
// a strict reader (Qt's, which reads through IEND) checks; the simplified libpng reader stops
// after the image data.
bool chunkCrcsHold(const std::vector<std::byte>& png) {
    const auto byteAt = [&](std::size_t i) { return std::uint32_t(std::uint8_t(png[i])); };
    const auto bigEndian = [&](std::size_t i) {
        return byteAt(i) << 24 | byteAt(i + 1) << 16 | byteAt(i + 2) << 8 | byteAt(i + 3);
    };
    std::size_t at = 8;
    while (at + 12 <= png.size()) {
        const std::uint32_t length = bigEndian(at);
        std::uint32_t crc = 0xffffffffu;
        for (std::size_t i = at + 4; i < at + 8 + length; ++i) {
            crc ^= byteAt(i);
            for (int bit = 0; bit < 8; ++bit)
                crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
        }
        if ((crc ^ 0xffffffffu) != bigEndian(at + 8 + length))
            return false;
        at += 12 + length;
    }
    return at == png.size();
}

// The exports' fast path: B, G, R, X rows with padding between them (a QImage's RGB32 rows)
// come back as the RGB they hold -- in one band of rows, and across the bands' boundaries (64
// rows a band: one row more, one less, several bands).
TEST(PngIo, FastBgrxRowsRoundTripAsRgb) {
    for (auto [w, h] : {std::pair{1, 1}, std::pair{13, 5}, std::pair{64, 33}, std::pair{3, 64},
                        std::pair{5, 65}, std::pair{1, 127}, std::pair{301, 200}}) {
        const ImageRgba8 image = testImage(w, h, unsigned(w + 7 * h));
        const std::size_t bytesPerLine = std::size_t(w) * 4 + 12;
        std::vector<std::uint8_t> rows(bytesPerLine * std::size_t(h), 0xee);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                std::uint8_t* p = rows.data() + std::size_t(y) * bytesPerLine + 4 * std::size_t(x);
                const Rgba8 c = image.at(x, y);
                p[0] = c.b, p[1] = c.g, p[2] = c.r, p[3] = 0x5a; // the X byte is ignored
            }
        const auto bytes = encodePngFastFromBgrx(rows.data(), w, h, bytesPerLine);
        EXPECT_TRUE(chunkCrcsHold(bytes)) << w << "x" << h;
        PngFormat stored = PngFormat::Rgba;
        const ImageRgba8 back = decodePng(bytes.data(), bytes.size(), "memory", &stored);
        EXPECT_EQ(stored, PngFormat::Rgb);
        ASSERT_EQ(back.width(), w);
        ASSERT_EQ(back.height(), h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                Rgba8 expected = image.at(x, y);
                expected.a = 255;
                ASSERT_EQ(back.at(x, y), expected) << w << "x" << h << " at " << x << "," << y;
            }
    }
    EXPECT_THROW(encodePngFastFromBgrx(nullptr, 4, 4, 16), Error);
}

TEST(PngIo, RoundTripGray) {
    const ImageRgba8 image = testImage(23, 11, 9, /*grey=*/true);
    const auto bytes = encodePng(image, PngFormat::Gray);
    PngFormat stored = PngFormat::Rgba;
    const ImageRgba8 back = decodePng(bytes.data(), bytes.size(), "memory", &stored);
    EXPECT_EQ(stored, PngFormat::Gray);
    EXPECT_EQ(back, image);
    // One byte per pixel plus a filter byte per row, before compression: much smaller than RGBA.
    EXPECT_LT(bytes.size(), encodePng(image, PngFormat::Rgba).size());
}

// Written by a separate encoder (a short Python script: its own filter code, rows filtered with
// Sub, Up, Average and Paeth in turn, the data split over two IDAT chunks, a tEXt chunk), so a
// mistake shared by our encoder and decoder cannot hide behind the round trip.
TEST(PngIo, ReadsAnIndependentlyEncodedFile) {
    static const unsigned char kIndependentPng[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
        0x52, 0x00, 0x00, 0x00, 0x05, 0x00, 0x00, 0x00, 0x04, 0x08, 0x02, 0x00, 0x00, 0x00, 0xc9,
        0x51, 0x62, 0x17, 0x00, 0x00, 0x00, 0x13, 0x74, 0x45, 0x58, 0x74, 0x43, 0x6f, 0x6d, 0x6d,
        0x65, 0x6e, 0x74, 0x00, 0x69, 0x6e, 0x64, 0x65, 0x70, 0x65, 0x6e, 0x64, 0x65, 0x6e, 0x74,
        0xb5, 0x98, 0xd1, 0xe2, 0x00, 0x00, 0x00, 0x0a, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63,
        0x64, 0x60, 0xf8, 0x6f, 0x2a, 0x78, 0xc3, 0xa6, 0x4f, 0x4e, 0x46, 0x00, 0x00, 0x00, 0x31,
        0x49, 0x44, 0x41, 0x54, 0xd4, 0xf8, 0x86, 0x69, 0xe8, 0x0d, 0xd3, 0xf2, 0x1b, 0x4c, 0xb2,
        0xee, 0xdf, 0x91, 0x11, 0xb3, 0x4e, 0x76, 0x91, 0xa6, 0xce, 0x0b, 0x4d, 0xdb, 0x17, 0x9a,
        0x7e, 0x2f, 0x34, 0xe3, 0x5f, 0xb0, 0x80, 0x84, 0x05, 0xbf, 0xcb, 0x1a, 0x7f, 0x97, 0x0d,
        0x05, 0xc9, 0x03, 0x00, 0x26, 0x36, 0x1a, 0x03, 0x1a, 0xd0, 0xcc, 0x85, 0x00, 0x00, 0x00,
        0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    PngFormat stored = PngFormat::Rgba;
    const ImageRgba8 image = decodePng(reinterpret_cast<const std::byte*>(kIndependentPng),
                                       sizeof(kIndependentPng), "independent.png", &stored);
    EXPECT_EQ(stored, PngFormat::Rgb);
    ASSERT_EQ(image.width(), 5);
    ASSERT_EQ(image.height(), 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x) {
            const Rgba8 expected{std::uint8_t((x * 53 + y * 29) % 256),
                                 std::uint8_t((x * x * 17 + y * 71) % 256),
                                 std::uint8_t((255 - x * 40 - y * 9) % 256), 255};
            EXPECT_EQ(image.at(x, y), expected) << x << "," << y;
        }
}

TEST(PngIo, WritesAtomicallyAndReadsBack) {
    lw::test::TempDir dir;
    const ImageRgba8 image = testImage(31, 7, 3);
    writePng(dir / "out.png", image);
    EXPECT_EQ(readPng(dir / "out.png"), image);
    int files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path()))
        ++files;
    EXPECT_EQ(files, 1) << "a temporary file was left behind";
    EXPECT_THROW(writePng(dir / "empty.png", ImageRgba8()), Error);
}

TEST(PngIo, CorruptFilesGiveErrors) {
    const auto good = encodePng(testImage(16, 16, 1), PngFormat::Rgba);
    const std::size_t ihdr = chunkAt(good, "IHDR"), idat = chunkAt(good, "IDAT");

    auto badSignature = good;
    badSignature[1] = std::byte{'X'};
    expectDecodeError(badSignature, "Not a PNG file");

    const std::vector<std::byte> truncated(good.begin(),
                                           good.begin() + std::ptrdiff_t(good.size() / 2));
    expectDecodeError(truncated, "read beyond end of data");

    // A flipped byte in the data: zlib notices first. One in the checksum: the CRC check does.
    auto flipped = good;
    flipped[idat + 8 + 5] ^= std::byte{0x55};
    expectDecodeError(flipped, "PNG image data is corrupt: IDAT: ");
    auto badCrc = good;
    badCrc[chunkAt(good, "IEND") - 1] ^= std::byte{0x55};
    expectDecodeError(badCrc, "IDAT: CRC error");

    // Damaged compressed data behind a valid CRC: the inflater must notice.
    auto damaged = flipped;
    for (std::size_t i = idat + 8 + 2; i < idat + 8 + 40; ++i)
        damaged[i] = std::byte{0xff};
    expectDecodeError(withFixedCrc(damaged, idat), "PNG image data is corrupt");

    auto sixteenBit = good;
    sixteenBit[ihdr + 8 + 8] = std::byte{16};
    expectDecodeError(withFixedCrc(sixteenBit, ihdr), "bit depth 16");

    // Palette and interlaced files are read (ReadsInterlacedPaletteFiles); these headers do not
    // match their data, which must be noticed.
    auto palette = good;
    palette[ihdr + 8 + 9] = std::byte{3};
    expectDecodeError(withFixedCrc(palette, ihdr), "PLTE");

    auto interlaced = good;
    interlaced[ihdr + 8 + 12] = std::byte{1};
    expectDecodeError(withFixedCrc(interlaced, ihdr), "PNG image data is corrupt");

    lw::test::TempDir dir;
    const auto path = dir / "broken.png";
    writeFileAtomically(path, flipped.data(), flipped.size());
    try {
        readPng(path);
        FAIL() << "corrupt file was read";
    } catch (const Error& error) {
        EXPECT_EQ(error.subject(), path.string());
    }
}

// A header declaring 60000 x 60000 pixels (14 GB of RGBA) is refused from the header alone, before
// anything of that size is allocated: the file is a few dozen bytes.
TEST(PngIo, AbsurdSizesAreRefusedBeforeAllocating) {
    const auto good = encodePng(testImage(4, 4, 2), PngFormat::Rgba);
    const std::size_t ihdr = chunkAt(good, "IHDR");
    for (const std::uint32_t side : {60000u, 1u << 30}) {
        auto huge = good;
        for (std::size_t field : {ihdr + 8, ihdr + 12})
            for (int i = 0; i < 4; ++i)
                huge[field + std::size_t(i)] = std::byte((side >> (24 - 8 * i)) & 0xff);
        try {
            const auto fixed = withFixedCrc(huge, ihdr);
            decodePng(fixed.data(), fixed.size(), "huge.png");
            FAIL() << side << " x " << side << " was decoded";
        } catch (const Error& error) {
            EXPECT_EQ(error.subject(), "huge.png");
            // 2^30 is beyond libpng's own limit (a million pixels a side), 60000 only beyond ours.
            EXPECT_NE(error.reason().find(side == 60000u ? "60000x60000 is empty or too large"
                                                         : "Invalid IHDR data"),
                      std::string::npos)
                << error.reason();
        }
    }
}

// Written by a separate encoder (a short Python script): 7 x 5 pixels, palette with a tRNS
// chunk, Adam7 interlaced. The hand-written decoder refused both; libpng reads them.
TEST(PngIo, ReadsInterlacedPaletteFiles) {
    static const unsigned char kInterlacedPalette[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
        0x44, 0x52, 0x00, 0x00, 0x00, 0x07, 0x00, 0x00, 0x00, 0x05, 0x08, 0x03, 0x00, 0x00,
        0x01, 0xc9, 0x43, 0x36, 0x7c, 0x00, 0x00, 0x00, 0x0c, 0x50, 0x4c, 0x54, 0x45, 0xff,
        0x00, 0x00, 0x00, 0xff, 0x00, 0x00, 0x00, 0xff, 0x0a, 0x14, 0x1e, 0x22, 0x88, 0x29,
        0x04, 0x00, 0x00, 0x00, 0x01, 0x74, 0x52, 0x4e, 0x53, 0x80, 0xad, 0x5e, 0x5b, 0x46,
        0x00, 0x00, 0x00, 0x1e, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0x60, 0x80, 0x00,
        0x26, 0x26, 0x10, 0x62, 0x00, 0x92, 0x0c, 0x8c, 0xcc, 0x8c, 0x70, 0xcc, 0xc4, 0xcc,
        0xc0, 0x08, 0xc4, 0x30, 0x1a, 0x00, 0x03, 0xc8, 0x00, 0x32, 0xf1, 0x0f, 0x1a, 0x13,
        0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    const Rgba8 palette[] = {
        {255, 0, 0, 128}, {0, 255, 0, 255}, {0, 0, 255, 255}, {10, 20, 30, 255}};
    PngFormat stored = PngFormat::Gray;
    const ImageRgba8 image = decodePng(reinterpret_cast<const std::byte*>(kInterlacedPalette),
                                       sizeof(kInterlacedPalette), "palette.png", &stored);
    EXPECT_EQ(stored, PngFormat::Rgba);
    ASSERT_EQ(image.width(), 7);
    ASSERT_EQ(image.height(), 5);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
            EXPECT_EQ(image.at(x, y), palette[(x + 2 * y) % 4]) << x << "," << y;
}

TEST(ImageCompare, ToleranceAndBadPixelCount) {
    const ImageRgba8 expected = testImage(20, 10, 4);
    ImageRgba8 actual = expected;
    EXPECT_TRUE(compareImages(actual, expected, {}).matches);

    actual.at(3, 4).g =
        static_cast<std::uint8_t>(actual.at(3, 4).g ^ 0x0a); // differs by 10 at most
    const int d = std::abs(int(actual.at(3, 4).g) - int(expected.at(3, 4).g));
    auto strict = compareImages(actual, expected, {d - 1, 0});
    EXPECT_FALSE(strict.matches);
    EXPECT_EQ(strict.badPixels, 1u);
    EXPECT_EQ(strict.maxChannelDifference, d);
    EXPECT_TRUE(compareImages(actual, expected, {d, 0}).matches);
    EXPECT_TRUE(compareImages(actual, expected, {0, 1}).matches);

    const auto resized = compareImages(ImageRgba8(21, 10), expected, {255, 1000});
    EXPECT_FALSE(resized.sizesMatch);
    EXPECT_FALSE(resized.matches);
}

TEST(ImageCompare, DiffImageWrittenOnlyOnMismatch) {
    lw::test::TempDir dir;
    const ImageRgba8 expected = testImage(12, 8, 6, false, true);
    EXPECT_FALSE(compareImages(expected, expected, {}, dir / "same.png").diffWritten);
    EXPECT_FALSE(std::filesystem::exists(dir / "same.png"));

    ImageRgba8 actual = expected;
    actual.at(5, 2) = {0, 0, 0, 0};
    actual.at(6, 2).r = static_cast<std::uint8_t>(actual.at(6, 2).r ^ 1);
    const auto result = compareImages(actual, expected, {2, 0}, dir / "diff.png");
    EXPECT_TRUE(result.diffWritten);
    EXPECT_EQ(result.badPixels, 1u);
    EXPECT_NE(result.describe().find("diff.png"), std::string::npos);
    const ImageRgba8 diff = readPng(dir / "diff.png");
    EXPECT_EQ(diff.at(5, 2), (Rgba8{255, 0, 0, 255}));   // over tolerance
    EXPECT_EQ(diff.at(6, 2), (Rgba8{255, 255, 0, 255})); // within tolerance
    EXPECT_EQ(diff.at(0, 0).r, diff.at(0, 0).g);         // unchanged: grey
}

TEST(ImageCompare, BaselineHelperWritesDiffAndActual) {
    lw::test::TempDir dir;
    const ImageRgba8 baseline = testImage(9, 9, 8);
    writePng(dir / "baseline.png", baseline);
    EXPECT_TRUE(
        compareWithBaseline(baseline, dir / "baseline.png", ImageTolerance{}, dir / "case.diff.png")
            .matches);
    ImageRgba8 changed = baseline;
    changed.at(0, 0) = {1, 2, 3, 4};
    changed.at(8, 8) = {200, 2, 3, 4};
    const auto result =
        compareWithBaseline(changed, dir / "baseline.png", ImageTolerance{}, dir / "case.diff.png");
    EXPECT_FALSE(result.matches);
    EXPECT_TRUE(std::filesystem::exists(dir / "case.diff.png"));
    EXPECT_EQ(readPng(dir / "case.diff.actual.png"), changed);
}

// The one baseline policy: a missing baseline fails, naming the path and how to make it (the
// actual image left beside the diff path); LINEWORK_UPDATE_BASELINES=1 writes instead of
// comparing; an unreadable baseline throws.
TEST(ImageCompare, BaselinePolicyMissingUpdateUnreadable) {
    lw::test::TempDir dir;
    const ImageRgba8 image = testImage(9, 9, 8);
    const std::filesystem::path baseline = dir / "new" / "case.png";
    const auto missing =
        compareWithBaseline(image, baseline, ContentTolerance{}, dir / "case.diff.png");
    EXPECT_FALSE(missing.matches);
    EXPECT_TRUE(missing.baselineMissing);
    EXPECT_NE(missing.describe().find(baseline.string()), std::string::npos);
    EXPECT_NE(missing.describe().find("LINEWORK_UPDATE_BASELINES=1"), std::string::npos);
    EXPECT_EQ(readPng(dir / "case.diff.actual.png"), image);
    EXPECT_FALSE(std::filesystem::exists(baseline)); // never written unasked

    ASSERT_EQ(setenv("LINEWORK_UPDATE_BASELINES", "1", 1), 0);
    EXPECT_TRUE(updatingBaselines());
    const auto written = compareWithBaseline(image, baseline, ImageTolerance{});
    unsetenv("LINEWORK_UPDATE_BASELINES");
    EXPECT_TRUE(written.baselineWritten);
    EXPECT_TRUE(written.matches);
    EXPECT_EQ(readPng(baseline), image);
    EXPECT_FALSE(updatingBaselines());
    EXPECT_TRUE(compareWithBaseline(image, baseline, ContentTolerance{}).matches);

    std::ofstream(dir / "broken.png") << "not a png";
    EXPECT_THROW(compareWithBaseline(image, dir / "broken.png", ImageTolerance{}), Error);
}

// The baseline helper the image tests share: tolerance relative to the content, and an empty
// image fails however loose the share (a thin line drawing of 212 pixels must not pass blank).
TEST(ImageCompare, ContentToleranceIsRelativeAndRejectsEmptyImages) {
    const lw::test::TempDir dir;
    ImageRgba8 lines(64, 64, {255, 255, 255, 255});
    for (int x = 8; x < 56; ++x)
        lines.at(x, 32) = {0, 0, 0, 255}; // 48 content pixels
    writePng(dir / "lines.png", lines);
    EXPECT_EQ(contentPixels(lines, {255, 255, 255, 255}), 48u);

    ImageRgba8 shifted(64, 64, {255, 255, 255, 255});
    for (int x = 8; x < 56; ++x)
        shifted.at(x, 33) = {0, 0, 0, 255}; // the line one pixel lower: 96 pixels differ
    EXPECT_TRUE(
        compareWithBaseline(shifted, dir / "lines.png", ContentTolerance{0, 2.0, 0.5}).matches);
    EXPECT_FALSE(
        compareWithBaseline(shifted, dir / "lines.png", ContentTolerance{0, 1.0, 0.5}).matches);

    const ImageRgba8 blank(64, 64, {255, 255, 255, 255});
    const ImageComparison empty =
        compareWithBaseline(blank, dir / "lines.png", ContentTolerance{0, 10.0, 0.5});
    EXPECT_FALSE(empty.matches) << empty.describe();
    EXPECT_EQ(empty.actualContent, 0u);
    EXPECT_EQ(empty.expectedContent, 48u);
}
