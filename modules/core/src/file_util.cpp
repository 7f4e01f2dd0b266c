#include "lw/core/file_util.h"

#include "lw/core/error.h"

#include <zlib.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>

namespace lw::core {

std::vector<std::byte> readFileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(path.string(), std::string("cannot open for reading: ") + std::strerror(errno));
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0)
        throw Error(path.string(), "cannot determine the file size");
    in.seekg(0);
    std::vector<std::byte> bytes(static_cast<std::size_t>(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size))
        throw Error(path.string(), "read failed");
    return bytes;
}

std::string readFileText(const std::filesystem::path& path) {
    const auto bytes = readFileBytes(path);
    return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

bool looksGzipped(const std::byte* data, std::size_t size) {
    return size >= 2 && data[0] == std::byte{0x1f} && data[1] == std::byte{0x8b};
}

std::vector<std::byte> gunzip(const std::byte* data, std::size_t size, const std::string& subject) {
    z_stream stream{};
    // 15 + 32: accept both zlib and gzip headers.
    if (inflateInit2(&stream, 15 + 32) != Z_OK)
        throw Error(subject, "zlib initialisation failed");
    std::vector<std::byte> out(std::max<std::size_t>(size * 4, 1 << 16));
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<std::byte*>(data));
    stream.avail_in = static_cast<uInt>(size);
    int status = Z_OK;
    while (true) {
        if (stream.total_out == out.size())
            out.resize(out.size() * 2);
        stream.next_out = reinterpret_cast<Bytef*>(out.data() + stream.total_out);
        stream.avail_out = static_cast<uInt>(out.size() - stream.total_out);
        status = inflate(&stream, Z_NO_FLUSH);
        if (status == Z_STREAM_END) {
            // Concatenated gzip members (pigz, some NIfTI writers): keep inflating.
            if (stream.avail_in > 0 && looksGzipped(reinterpret_cast<const std::byte*>(stream.next_in), stream.avail_in)) {
                const auto produced = stream.total_out;
                inflateReset(&stream);
                stream.total_out = produced;
                continue;
            }
            break;
        }
        if (status == Z_BUF_ERROR && stream.avail_in == 0) {
            inflateEnd(&stream);
            throw Error(subject, "compressed data is truncated");
        }
        if (status != Z_OK && status != Z_BUF_ERROR) {
            const std::string message = stream.msg ? stream.msg : "corrupt compressed data";
            inflateEnd(&stream);
            throw Error(subject, "decompression failed: " + message);
        }
    }
    out.resize(stream.total_out);
    inflateEnd(&stream);
    return out;
}

void writeFileAtomically(const std::filesystem::path& path, const void* data, std::size_t size) {
    std::random_device random;
    std::string temporaryName = ".";
    temporaryName += path.filename().string();
    temporaryName += ".tmp";
    temporaryName += std::to_string(random());
    const auto temporary = path.parent_path() / temporaryName;
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out)
            throw Error(path.string(), std::string("cannot create a temporary file: ") +
                                           std::strerror(errno));
        out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
        out.flush();
        if (!out) {
            out.close();
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            throw Error(path.string(), "write failed (disk full?)");
        }
    }
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw Error(path.string(), "cannot replace the file: " + ec.message());
    }
}

} // namespace lw::core
