#pragma once
// Output files appear whole or not at all: write to a temporary sibling, flush, then rename.

#include <filesystem>
#include <functional>
#include <string_view>

namespace freeplay {

/// Writes `contents` to `path` atomically (temporary file in the same folder + fsync + rename); throws on error.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);
/// Writes `path` atomically from the pieces `produce` hands to its writer (for files too large to hold in memory).
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::function<void(std::string_view)>&)>& produce);

/// Reads a whole file into a string; throws std::runtime_error naming the path when it cannot.
std::string read_file(const std::filesystem::path& path);

}  // namespace freeplay
