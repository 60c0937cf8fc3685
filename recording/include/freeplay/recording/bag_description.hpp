#pragma once
// The files PInSoRo ships beside a bag: `freeplay.bag.yaml` (rosbag's own `rosbag info --yaml` description) and the
// md5 checksum files (free-play-sandbox.md §4.3).

#include <filesystem>
#include <string>

namespace freeplay::recording {

/// `rosbag info --yaml` text of the indexed bag `bag`, field for field as python3-rosbag writes it (path, version,
/// duration, start, end, size, messages, indexed, compression, types with md5, topics with type, messages,
/// connections when more than one, and frequency = 1 / median period of the bag times when positive); `path_field`
/// is what the `path:` line says and `compression` the chunks' (`none`, `lz4`, `bz2`; rosbag's compressed and
/// uncompressed byte counts of compressed bags are not written). InputError when the bag does not open.
std::string describe_bag_yaml(const std::filesystem::path& bag, const std::string& path_field,
                              const std::string& compression = "none");
/// Lowercase hex MD5 of a file's bytes; InputError when it cannot be read.
std::string md5_hex(const std::filesystem::path& file);
/// Writes `<file>.md5` as md5sum does (`<hash>  <file name>\n`) and returns its path.
std::filesystem::path write_md5_file(const std::filesystem::path& file);

}  // namespace freeplay::recording
