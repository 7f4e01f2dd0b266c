#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace lw::core {

// Reads a whole file (opened read-only). Throws Error naming the file on failure.
std::vector<std::byte> readFileBytes(const std::filesystem::path& path);
std::string readFileText(const std::filesystem::path& path);

// Inflates gzip or zlib data; throws Error naming `subject` when the stream is corrupt.
std::vector<std::byte> gunzip(const std::byte* data, std::size_t size, const std::string& subject);
bool looksGzipped(const std::byte* data, std::size_t size);

// Writes a file atomically: to a temporary sibling first, then renamed over the target, so
// an interrupted write never leaves a half-written file behind.
void writeFileAtomically(const std::filesystem::path& path, const void* data, std::size_t size);

} // namespace lw::core
