#pragma once

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace lw::core {

// Reads a whole file (opened read-only). Throws Error naming the file on failure.
std::vector<std::byte> readFileBytes(const std::filesystem::path& path);
std::string readFileText(const std::filesystem::path& path);

// Inflates gzip or zlib data; throws Error naming `subject` when the stream is corrupt or would
// inflate to more than `maxOutput` bytes: a reader passes inflateBound(what its header declares)
// (lw/core/limits.h), so a 4 MB bomb inflating to 4 GiB stops right after the expected size.
std::vector<std::byte> gunzip(const std::byte* data, std::size_t size, const std::string& subject,
                              std::size_t maxOutput = std::numeric_limits<std::size_t>::max());
// The first `count` inflated bytes (fewer when the stream is shorter): a header is read before
// anything is known about the size of what follows it.
std::vector<std::byte> gunzipPrefix(const std::byte* data, std::size_t size,
                                    const std::string& subject, std::size_t count);
bool looksGzipped(const std::byte* data, std::size_t size);

// Writes a file atomically: to a temporary sibling first, then renamed over the target, so
// an interrupted write never leaves a half-written file behind.
void writeFileAtomically(const std::filesystem::path& path, const void* data, std::size_t size);

} // namespace lw::core
