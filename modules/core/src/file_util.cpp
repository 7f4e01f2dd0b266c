#include "lw/core/file_util.h"

#include "lw/core/error.h"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <limits>
#include <random>
#include <unistd.h>
#include <zlib.h>

namespace lw::core {

std::vector<std::byte> readFileBytes(const std::filesystem::path& path, std::size_t maxBytes) {
    // A folder opens as a stream whose "size" is the largest offset: refuse it before sizing.
    std::error_code ec;
    if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
        throw Error(path.string(), "not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(path.string(), std::string("cannot open for reading: ") + std::strerror(errno));
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0)
        throw Error(path.string(), "cannot determine the file size");
    if (static_cast<std::uintmax_t>(size) > maxBytes)
        throw Error(path.string(), "the file is " + std::to_string(size) +
                                       " bytes, more than the limit of " +
                                       std::to_string(maxBytes) + " bytes for this kind of file");
    in.seekg(0);
    std::vector<std::byte> bytes(static_cast<std::size_t>(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size))
        throw Error(path.string(), "read failed");
    return bytes;
}

std::string readFileText(const std::filesystem::path& path, std::size_t maxBytes) {
    const auto bytes = readFileBytes(path, maxBytes);
    return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

bool looksGzipped(const std::byte* data, std::size_t size) {
    return size >= 2 && data[0] == std::byte{0x1f} && data[1] == std::byte{0x8b};
}

namespace {

// Inflates gzip or zlib data into at most `limit` bytes. Stops there: `*exceeded` tells whether
// the stream had more. zlib's counters are 32-bit (uInt), so input and output are fed in
// pieces; the output grows by doubling up to the limit, never beyond it.
std::vector<std::byte> inflateAtMost(const std::byte* data, std::size_t size,
                                     const std::string& subject, std::size_t limit,
                                     bool* exceeded) {
    constexpr std::size_t kPiece = std::numeric_limits<uInt>::max();
    z_stream stream{};
    // 15 + 32: accept both zlib and gzip headers.
    if (inflateInit2(&stream, 15 + 32) != Z_OK)
        throw Error(subject, "zlib initialisation failed");
    std::vector<std::byte> out(
        std::min(limit, std::max<std::size_t>(size < limit / 4 ? size * 4 : limit, 1 << 16)));
    std::size_t consumed = 0; // input handed to zlib so far
    std::size_t produced = 0; // output across concatenated members
    *exceeded = false;
    const auto fail = [&](const std::string& reason) {
        inflateEnd(&stream);
        throw Error(subject, reason);
    };
    while (true) {
        if (stream.avail_in == 0 && consumed < size) {
            stream.next_in = reinterpret_cast<Bytef*>(const_cast<std::byte*>(data + consumed));
            stream.avail_in = uInt(std::min(kPiece, size - consumed));
            consumed += stream.avail_in;
        }
        if (produced == out.size()) {
            if (out.size() >= limit) {
                // Full: one more byte of output means the stream is larger than allowed.
                std::byte probe{};
                stream.next_out = reinterpret_cast<Bytef*>(&probe);
                stream.avail_out = 1;
                const int status = inflate(&stream, Z_NO_FLUSH);
                *exceeded = stream.avail_out == 0 && (status == Z_OK || status == Z_STREAM_END);
                break;
            }
            out.resize(std::min(limit, std::max<std::size_t>(out.size(), 1) * 2));
        }
        stream.next_out = reinterpret_cast<Bytef*>(out.data() + produced);
        stream.avail_out = uInt(std::min(kPiece, out.size() - produced));
        const uInt before = stream.avail_out;
        const int status = inflate(&stream, Z_NO_FLUSH);
        produced += before - stream.avail_out;
        if (status == Z_STREAM_END) {
            // Concatenated gzip members (pigz, some NIfTI writers): keep inflating.
            if (stream.avail_in > 0 &&
                looksGzipped(reinterpret_cast<const std::byte*>(stream.next_in), stream.avail_in)) {
                inflateReset(&stream);
                continue;
            }
            break;
        }
        if (status == Z_BUF_ERROR && stream.avail_in == 0 && consumed == size)
            fail("compressed data is truncated");
        if (status != Z_OK && status != Z_BUF_ERROR)
            fail(std::string("decompression failed: ") +
                 (stream.msg ? stream.msg : "corrupt compressed data"));
    }
    inflateEnd(&stream);
    out.resize(produced);
    return out;
}

} // namespace

std::vector<std::byte> gunzip(const std::byte* data, std::size_t size, const std::string& subject,
                              std::size_t maxOutput) {
    bool exceeded = false;
    std::vector<std::byte> out = inflateAtMost(data, size, subject, maxOutput, &exceeded);
    if (exceeded)
        throw Error(subject, "compressed data inflates to more than " + std::to_string(maxOutput) +
                                 " bytes, more than its header declares (or the import limit)");
    return out;
}

std::vector<std::byte> gunzipPrefix(const std::byte* data, std::size_t size,
                                    const std::string& subject, std::size_t count) {
    bool exceeded = false;
    return inflateAtMost(data, size, subject, count, &exceeded);
}

namespace {

std::filesystem::path folderOf(const std::filesystem::path& path) {
    return path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
}

void removeQuietly(const std::filesystem::path& path) {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
}

// Puts the finished temporary file in place without replacing an existing target, atomically:
// a test for existence followed by rename() would race with another writer. link() does it
// where hard links exist; file systems without them (FAT on a USB stick, some network shares)
// get renameat2(RENAME_NOREPLACE). Returns 0 or the errno of the failure.
int placeWithoutReplacing(const std::filesystem::path& temporary,
                          const std::filesystem::path& path) {
    if (::link(temporary.c_str(), path.c_str()) == 0) {
        removeQuietly(temporary);
        return 0;
    }
    const int linkError = errno;
    if (linkError != EPERM && linkError != EOPNOTSUPP && linkError != ENOSYS)
        return linkError;
    if (::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, path.c_str(), RENAME_NOREPLACE) == 0)
        return 0;
    return errno;
}

// Moves the finished temporary file onto the target.
void commitTemporary(const std::filesystem::path& temporary, const std::filesystem::path& path,
                     Overwrite overwrite) {
    if (overwrite == Overwrite::Refuse) {
        if (const int error = placeWithoutReplacing(temporary, path); error != 0) {
            removeQuietly(temporary);
            throw Error(path.string(), error == EEXIST ? "the file exists already (not overwritten)"
                                                       : std::string("cannot create the file: ") +
                                                             std::strerror(error));
        }
        return;
    }
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        removeQuietly(temporary);
        throw Error(path.string(), "cannot replace the file: " + ec.message());
    }
}

// The hidden temporaries of `path` (".<name>.tmp<digits>", as writeFileAtomically names them)
// that were last written more than kStaleTemporaryAge ago: left by a killed write. Removed
// quietly: a failure here must not stop the write that follows.
void removeStaleTemporaries(const std::filesystem::path& path) {
    // Appended, not `"." + name + ".tmp"`: GCC 12 at -O3 warns (-Wrestrict) on a false overlap
    // inside that operator+ once this is inlined into writeFileAtomically.
    std::string prefix = ".";
    prefix += path.filename().string();
    prefix += ".tmp";
    std::error_code ec;
    const auto now = std::filesystem::file_time_type::clock::now();
    for (std::filesystem::directory_iterator it(folderOf(path), ec), end; !ec && it != end;
         it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
            name.find_first_not_of("0123456789", prefix.size()) != std::string::npos)
            continue;
        std::error_code statError;
        if (!it->is_regular_file(statError) || it->is_symlink(statError))
            continue;
        const auto written = it->last_write_time(statError);
        if (!statError && now - written > kStaleTemporaryAge)
            removeQuietly(it->path());
    }
}

} // namespace

void checkStaysInFolder(const std::filesystem::path& path) {
    const std::filesystem::path name = path.filename();
    if (name.empty() || name == "." || name == "..")
        throw Error(path.string(), "not a file name in a folder (an export writes only files "
                                   "of the chosen folder)");
    std::error_code ec;
    if (!std::filesystem::is_symlink(std::filesystem::symlink_status(path, ec)))
        return;
    const std::filesystem::path target = std::filesystem::read_symlink(path, ec);
    throw Error(path.string(), "is a symbolic link (to " + target.string() +
                                   "): an export does not write through a link, which may lead "
                                   "out of the chosen folder");
}

std::filesystem::path fileInFolder(const std::filesystem::path& folder, const std::string& name) {
    const std::filesystem::path asGiven(name);
    if (name.find('/') != std::string::npos || asGiven.has_root_path())
        throw Error((folder / "").string() + name,
                    "the file name \"" + name +
                        "\" is a path, not a name: an export writes only files "
                        "of the chosen folder");
    const std::filesystem::path path = folder / asGiven;
    checkStaysInFolder(path);
    return path;
}

void checkWritableTarget(const std::filesystem::path& path, Overwrite overwrite) {
    checkStaysInFolder(path);
    std::error_code ec;
    if (overwrite == Overwrite::Refuse && std::filesystem::exists(path, ec))
        throw Error(path.string(), "the file exists already (not overwritten)");
    const std::filesystem::path folder = folderOf(path);
    if (!std::filesystem::is_directory(folder, ec))
        throw Error(path.string(), "the folder " + folder.string() + " does not exist");
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        throw Error(path.string(), "cannot write into the folder " + folder.string() + ": " +
                                       std::strerror(errno));
}

void writeFileAtomically(const std::filesystem::path& path, const void* data, std::size_t size,
                         Overwrite overwrite) {
    if (overwrite == Overwrite::Refuse && std::filesystem::exists(path))
        throw Error(path.string(), "the file exists already (not overwritten)");
    removeStaleTemporaries(path);
    std::random_device random;
    std::string temporaryName = ".";
    temporaryName += path.filename().string();
    temporaryName += ".tmp";
    temporaryName += std::to_string(random());
    const auto temporary = folderOf(path) / temporaryName;
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out)
            throw Error(path.string(),
                        std::string("cannot create a temporary file: ") + std::strerror(errno));
        out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
        out.flush();
        if (!out) {
            out.close();
            removeQuietly(temporary);
            throw Error(path.string(), "write failed (disk full?)");
        }
    }
    commitTemporary(temporary, path, overwrite);
}

} // namespace lw::core
