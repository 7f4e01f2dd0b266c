#pragma once

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace lw::core {

// Reads a whole file (opened read-only). Throws Error naming the file on failure, and before
// reading or allocating anything when the file is larger than `maxBytes` (a file a user hands
// over whose size has no reason to be large, such as an annotation file).
std::vector<std::byte>
readFileBytes(const std::filesystem::path& path,
              std::size_t maxBytes = std::numeric_limits<std::size_t>::max());
std::string readFileText(const std::filesystem::path& path,
                         std::size_t maxBytes = std::numeric_limits<std::size_t>::max());

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

// How old a temporary of writeFileAtomically must be before a later write removes it.
inline constexpr std::chrono::minutes kStaleTemporaryAge{10};

// Whether an atomic write may replace a file that is already there.
enum class Overwrite { Allow, Refuse };

// Writes a file atomically: to a temporary sibling first, then renamed over the target, so
// an interrupted write never leaves a half-written file behind. With Overwrite::Refuse an
// existing target is an Error and stays untouched: the temporary file is linked to the target,
// which fails when it exists, so a file appearing during the write is not replaced either.
// On every failure the temporary file is removed: nothing is left behind. A process killed
// mid-write cannot remove its temporary; the next write of the same file removes those that
// are older than kStaleTemporaryAge (a write takes seconds, so none of them is still being
// written).
void writeFileAtomically(const std::filesystem::path& path, const void* data, std::size_t size,
                         Overwrite overwrite = Overwrite::Allow);

// Throws Error naming `path` when it exists and `overwrite` is Refuse, or when its folder does
// not exist or is not writable: checked before expensive work, so an export that is bound to be
// refused fails at once (writeFileAtomically checks again when it writes).
// Also refuses what checkStaysInFolder refuses.
void checkWritableTarget(const std::filesystem::path& path, Overwrite overwrite);

// An export writes regular files into the folder the user chose, nowhere else. Refuses (Error
// naming `path` and the reason) a target whose last component is not a plain file name (empty,
// "." or "..": the folder itself or its parent) or is a symbolic link: a link may point out of
// the folder (a dangling one to where a file would be created), so none is written through or
// replaced. The folder part of `path` is the user's choice and is taken as given.
void checkStaysInFolder(const std::filesystem::path& path);

// `name` as a file of `folder`, for names an export makes itself: refused (Error naming
// folder/name) unless `name` is one plain component: no separator, not absolute, not "." or
// "..", and not a symbolic link (checkStaysInFolder).
std::filesystem::path fileInFolder(const std::filesystem::path& folder, const std::string& name);

} // namespace lw::core
