#include "link_trap.h"
#include "lw/core/error.h"
#include "lw/core/file_util.h"
#include "lw/core/json_writer.h"
#include "lw/core/log.h"
#include "lw/core/progress.h"
#include "test_support.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <thread>
#include <vector>
#include <zlib.h>

using namespace lw::core;

TEST(Error, NamesSubjectAndReason) {
    const Error error("/data/ct/01.dcm", "truncated pixel data");
    EXPECT_EQ(error.subject(), "/data/ct/01.dcm");
    EXPECT_EQ(error.reason(), "truncated pixel data");
    EXPECT_STREQ(error.what(), "/data/ct/01.dcm: truncated pixel data");
}

TEST(JsonWriter, NestedStructuresAndEscaping) {
    JsonWriter w(0);
    w.beginObject();
    w.field("name", "a \"quoted\"\nline");
    w.key("dims").beginArray().value(512).value(512).value(28).endArray();
    w.key("empty").beginArray().endArray();
    w.key("nested").beginObject().field("ok", true).field("x", 0.5).endObject();
    w.key("nothing").null();
    w.endObject();
    EXPECT_EQ(w.str(), "{\"name\":\"a \\\"quoted\\\"\\nline\",\"dims\":[512,512,28],\"empty\":[],"
                       "\"nested\":{\"ok\":true,\"x\":0.5},\"nothing\":null}");
}

// Escaping is nlohmann-json's: short escapes where JSON has them, \u00XX for other control
// characters, UTF-8 passed through, bytes that are not UTF-8 replaced by U+FFFD.
TEST(JsonWriter, EscapesControlCharactersAndReplacesInvalidUtf8) {
    EXPECT_EQ(JsonWriter::escape("\"\\\n\r\t\b\f\x01\x1f/\x7f"),
              "\"\\\"\\\\\\n\\r\\t\\b\\f\\u0001\\u001f/\x7f\"");
    EXPECT_EQ(JsonWriter::escape("L\xc3\xa4sion \xe2\x82\xac"), "\"L\xc3\xa4sion \xe2\x82\xac\"");
    EXPECT_EQ(JsonWriter::escape("Z\xfcrich"), "\"Z\xef\xbf\xbdrich\""); // Latin-1 \xfc
}

// Ten significant digits, integral values without a point: the CLI's JSON has always looked so.
TEST(JsonWriter, NumbersKeepTheirFormat) {
    JsonWriter w(0);
    w.beginArray().value(0.0).value(1.0).value(398.4835037).value(0.48828125).value(1e-5);
    w.value(12345678901.5).value(std::int64_t(-7)).endArray();
    EXPECT_EQ(w.str(), "[0,1,398.4835037,0.48828125,1e-05,1.23456789e+10,-7]");
}

TEST(JsonWriter, NonFiniteNumbersBecomeNull) {
    JsonWriter w(0);
    w.beginArray().value(std::numeric_limits<double>::quiet_NaN()).value(1.25).endArray();
    EXPECT_EQ(w.str(), "[null,1.25]");
}

TEST(Progress, ReportsFractionsAndCancels) {
    auto token = std::make_shared<CancelToken>();
    double last = -1.0;
    int calls = 0;
    Progress progress(
        [&](double f, const std::string& message) {
            EXPECT_GE(f, last);
            EXPECT_EQ(message, "decoding");
            last = f;
            ++calls;
        },
        token);
    progress.setTotal(4, "decoding");
    for (int i = 0; i < 4; ++i)
        progress.step();
    EXPECT_DOUBLE_EQ(last, 1.0);
    EXPECT_EQ(calls, 4);
    EXPECT_NO_THROW(progress.throwIfCancelled());
    token->cancel();
    EXPECT_TRUE(progress.isCancelled());
    EXPECT_THROW(progress.throwIfCancelled(), Cancelled);
}

TEST(Progress, StepIsThreadSafe) {
    // The callback is as a caller writes it, without a lock: a plain vector. Overlapping calls
    // are counted (and would corrupt the vector: the sanitizer suite caught that in a DICOM
    // scan's progress), and the fractions must arrive in order.
    std::vector<double> fractions;
    std::atomic<int> inside{0}, overlaps{0};
    Progress progress([&](double fraction, const std::string&) {
        if (inside.fetch_add(1) != 0)
            ++overlaps;
        fractions.push_back(fraction);
        std::this_thread::yield(); // widen the window another worker could enter through
        inside.fetch_sub(1);
    });
    progress.setTotal(20000);
    std::vector<std::thread> workers;
    for (int w = 0; w < 4; ++w)
        workers.emplace_back([&] {
            for (int i = 0; i < 5000; ++i)
                progress.step();
        });
    for (std::thread& worker : workers)
        worker.join();
    EXPECT_EQ(overlaps.load(), 0);
    // Throttled to per-mille changes: at most 1001 callbacks, in order, the last one at 100%.
    EXPECT_LE(fractions.size(), 1001u);
    EXPECT_GE(fractions.size(), 10u);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    ASSERT_FALSE(fractions.empty());
    EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
}

TEST(FileUtil, GunzipRoundTripAndCorruption) {
    std::string text(100000, 'x');
    for (std::size_t i = 0; i < text.size(); ++i)
        text[i] = char('a' + (i * 7919) % 26);
    // gzip stream via zlib's deflateInit2 with gzip wrapper.
    z_stream s{};
    ASSERT_EQ(deflateInit2(&s, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
    std::vector<unsigned char> out(compressBound(uLong(text.size())) + 64);
    s.next_in = reinterpret_cast<Bytef*>(text.data());
    s.avail_in = uInt(text.size());
    s.next_out = out.data();
    s.avail_out = uInt(out.size());
    ASSERT_EQ(deflate(&s, Z_FINISH), Z_STREAM_END);
    out.resize(s.total_out);
    deflateEnd(&s);
    const auto* bytes = reinterpret_cast<const std::byte*>(out.data());
    EXPECT_TRUE(looksGzipped(bytes, out.size()));
    const auto inflated = gunzip(bytes, out.size(), "test.gz");
    ASSERT_EQ(inflated.size(), text.size());
    EXPECT_EQ(std::memcmp(inflated.data(), text.data(), text.size()), 0);
    EXPECT_THROW(gunzip(bytes, out.size() / 2, "half.gz"), Error);
    std::vector<std::byte> garbage(64, std::byte{0x1f});
    EXPECT_THROW(gunzip(garbage.data(), garbage.size(), "garbage.gz"), Error);
}

TEST(FileUtil, AtomicWriteReplacesAndLeavesNoTemporary) {
    lw::test::TempDir dir;
    const auto path = dir / "out.bin";
    writeFileAtomically(path, "first", 5);
    writeFileAtomically(path, "second", 6);
    EXPECT_EQ(readFileText(path), "second");
    int entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path()))
        ++entries;
    EXPECT_EQ(entries, 1);
    EXPECT_THROW(writeFileAtomically(dir / "no-such-dir" / "x.bin", "x", 1), Error);
    EXPECT_THROW(readFileBytes(dir / "missing.bin"), Error);
}

// A write killed after creating its temporary leaves it behind; the next write of the same file
// removes it once it is older than kStaleTemporaryAge, and nothing else: not a fresh one (it may
// still be written), not another file's, not a name that only looks similar.
TEST(FileUtil, AtomicWriteRemovesStaleTemporariesOfItsFileOnly) {
    lw::test::TempDir dir;
    const auto path = dir / "review.png";
    const auto make = [&](const std::string& name, bool stale) {
        const auto file = dir / name;
        std::ofstream(file) << "partial";
        if (stale)
            std::filesystem::last_write_time(file, std::filesystem::file_time_type::clock::now() -
                                                       kStaleTemporaryAge -
                                                       std::chrono::minutes(1));
        return file;
    };
    const auto killed = make(".review.png.tmp123456", true);
    const auto fresh = make(".review.png.tmp777", false);
    const auto otherFile = make(".report.pdf.tmp42", true);
    const auto lookalike = make(".review.png.tmp12x", true);
    const auto userFile = make("review.png.tmp99", true);
    writeFileAtomically(path, "image", 5);
    EXPECT_EQ(readFileText(path), "image");
    EXPECT_FALSE(std::filesystem::exists(killed));
    for (const auto& kept : {fresh, otherFile, lookalike, userFile})
        EXPECT_TRUE(std::filesystem::exists(kept)) << kept;
}

// Exports never replace a file unless asked: the existing file keeps its bytes and no temporary
// file stays behind; a missing folder is named before anything is written.
TEST(FileUtil, AtomicWriteRefusingOverwriteKeepsTheExistingFile) {
    lw::test::TempDir dir;
    const auto path = dir / "report.pdf";
    writeFileAtomically(path, "first", 5, Overwrite::Refuse);
    try {
        writeFileAtomically(path, "second", 6, Overwrite::Refuse);
        FAIL() << "an existing file was overwritten";
    } catch (const Error& error) {
        EXPECT_EQ(error.subject(), path.string());
        EXPECT_NE(error.reason().find("exists already"), std::string::npos) << error.reason();
    }
    EXPECT_EQ(readFileText(path), "first");
    EXPECT_THROW(checkWritableTarget(path, Overwrite::Refuse), Error);
    EXPECT_NO_THROW(checkWritableTarget(path, Overwrite::Allow));
    EXPECT_THROW(checkWritableTarget(dir / "missing" / "x.png", Overwrite::Allow), Error);
    int entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path()))
        ++entries;
    EXPECT_EQ(entries, 1);
}

TEST(Log, SinkReceivesCategoryAndThresholdFilters) {
    std::vector<std::string> seen;
    auto previous = setLogSink([&](LogLevel level, std::string_view category,
                                   const std::string& m) {
        seen.push_back(std::string(logLevelName(level)) + " " + std::string(category) + " " + m);
    });
    const LogCategory category("lw.test");
    category.debug("hidden");
    category.warning("shown");
    setLogThreshold(LogLevel::Debug);
    category.debug("now shown");
    setLogThreshold(LogLevel::Info);
    setLogSink(previous);
    ASSERT_EQ(seen.size(), 2u);
    EXPECT_EQ(seen[0], "warning lw.test shown");
    EXPECT_EQ(seen[1], "debug lw.test now shown");
}

// Names an export must refuse, with the reason the user reads: fileInFolder takes a name the
// export made itself and writes only into the chosen folder.
TEST(FileUtil, ExportNamesLeadingOutOfTheFolderAreRefused) {
    lw::test::TempDir dir;
    const struct {
        const char* name;
        const char* reason;
    } cases[] = {
        {"../evil.png", "is a path, not a name"},   {"sub/../../evil.png", "is a path, not a name"},
        {"/tmp/evil.png", "is a path, not a name"}, {"sub/evil.png", "is a path, not a name"},
        {"..", "not a file name in a folder"},      {".", "not a file name in a folder"},
        {"", "not a file name in a folder"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        try {
            fileInFolder(dir.path(), c.name);
            ADD_FAILURE() << "accepted";
        } catch (const Error& error) {
            EXPECT_NE(error.reason().find(c.reason), std::string::npos) << error.what();
            EXPECT_NE(error.subject().find(dir.path().string()), std::string::npos) << error.what();
        }
    }
    EXPECT_EQ(fileInFolder(dir.path(), "LWSC0001.dcm"), dir / "LWSC0001.dcm");
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

// A symbolic link at the target's name is refused before anything is written, wherever it
// points (out of the folder, nowhere yet, or to the user's own file), even where overwriting
// was agreed: the check, the name-making and the atomic write all refuse it.
TEST(FileUtil, ExportTargetsThatAreLinksAreRefused) {
    lw::test::TempDir dir;
    const lw::test::LinkTrap trap(dir.path(), "out.png");
    for (const std::string& kind : lw::test::LinkTrap::kinds()) {
        SCOPED_TRACE(kind);
        const auto path = trap.link(kind);
        try {
            checkWritableTarget(path, Overwrite::Allow);
            ADD_FAILURE() << "accepted";
        } catch (const Error& error) {
            EXPECT_EQ(error.subject(), path.string());
            EXPECT_NE(error.reason().find("is a symbolic link"), std::string::npos) << error.what();
        }
        EXPECT_THROW(fileInFolder(trap.exports(), "out.png"), Error);
        EXPECT_TRUE(trap.untouched());
    }
}
