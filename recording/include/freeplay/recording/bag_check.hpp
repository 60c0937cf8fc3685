#pragma once
// A structural check of a ROS bag 2.0 file before rosbag_storage reads it: Debian's rosbag trusts every length and
// offset in the file (it allocates what a length says and reads a chunk at whatever offset the index gives), so a
// corrupt or hostile bag could make it allocate gigabytes or read outside its buffers.

#include <filesystem>

namespace freeplay::recording {

/// Walks every record of `file` (`#ROSBAG V2.0`; per record: header length, header, data length, data; the records
/// inside every chunk too, lz4 and bz2 chunks decompressed as rosbag does) and throws an InputError naming the file
/// and the byte offset (and the chunk, for a record inside a decompressed one) when:
/// - a length runs past its record or the file, or a chunk claims more than 512 MiB;
/// - a chunk's compression is not none, lz4 or bz2, or its data do not decompress to exactly its `size`;
/// - a record's or connection's header is not made of `length name=value` fields that fill it exactly;
/// - an index entry points at no message record of its chunk, a chunk-info record at no chunk, or the bag header's index
///   position at no record;
/// - an index or chunk-info record's data is not exactly its `count` entries (rosbag reads the next record right
///   after them);
/// - fewer records are there than rosbag reads by count: the bag header's `conn_count` connection and `chunk_count`
///   chunk-info records from its index position, and one index record per connection after each chunk.
/// A file without the 2.0 version line or without an index (a killed recording) is left to rosbag, whose messages
/// say what is wrong.
void check_bag_structure(const std::filesystem::path& file);

}  // namespace freeplay::recording
