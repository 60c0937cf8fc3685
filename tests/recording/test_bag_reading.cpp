// Reading bags in replay: every malformed or hostile bag is refused with an InputError naming it before rosbag (which
// trusts every length and offset in the file) or ROS's deserialisers read it.

#include <bzlib.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <roslz4/lz4s.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "freeplay/core/error.hpp"
#include "freeplay/recording/bag_check.hpp"
#include "freeplay/recording/bag_recorder.hpp"
#include "freeplay/recording/publishers.hpp"
#include "freeplay/recording/replay.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "test_dirs.hpp"

using namespace freeplay;
using namespace freeplay::recording;
using freeplay::recording::test_dirs::file_bytes;
using freeplay::recording::test_dirs::fresh_dir;

namespace {

/// A bag holding one message `m` on `topic` at t = 1 s, its chunks compressed with `compression`.
template <class M>
std::filesystem::path bag_with_message(const std::string& name, const std::string& topic, const M& m,
                                       rosbag::compression::CompressionType compression = rosbag::compression::Uncompressed) {
  const auto file = fresh_dir(name) / "freeplay.bag";
  Bag bag;
  bag.open(file.string(), rosbag::bagmode::Write);
  bag.get().setCompression(compression);
  bag.get().write(topic, ros_time(1.0), m);
  bag.close();
  return file;
}

/// A bag holding one /freeplay/events message with `text` as its data.
std::filesystem::path bag_with_event_text(const std::string& name, const std::string& text) {
  msg::String m;
  m.data = ros_string(text);
  return bag_with_message(name, std::string(topics::kEvents), m);
}

/// The InputError that reading and replaying `file` raises (fails the test when none is raised).
InputError replay_error(const std::filesystem::path& file) {
  try {
    recompute_metrics(read_session(file));
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for " << file;
  return InputError("none");
}

/// Overwrites the 4 bytes at byte `at` of `file` with `value`.
void write_u32_at(const std::filesystem::path& file, std::streamoff at, std::uint32_t value) {
  std::fstream f(file, std::ios::binary | std::ios::in | std::ios::out);
  f.seekp(at);
  f.write(reinterpret_cast<const char*>(&value), 4);
}

/// Overwrites the 4 bytes at `offset` from the first occurrence of `marker` in `file` with `value`.
void patch_u32(const std::filesystem::path& file, const std::string& marker, std::ptrdiff_t offset, std::uint32_t value) {
  const auto bytes = file_bytes(file);
  const auto at = bytes.find(marker);
  ASSERT_NE(at, std::string::npos);
  write_u32_at(file, static_cast<std::streamoff>(at) + offset, value);
}


/// `bytes` with the u32 at `at`.
std::uint32_t u32_at(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);
  return value;
}

/// `plain` compressed as rosbag compresses a chunk (roslz4 with its block size 6, or libbz2).
std::string compressed(const std::string& plain, const std::string& compression) {
  std::string out(plain.size() * 2 + 1024, '\0');
  auto size = static_cast<unsigned int>(out.size());
  auto input = plain;
  const int status = compression == "lz4"
                         ? roslz4_buffToBuffCompress(input.data(), static_cast<unsigned int>(input.size()), out.data(),
                                                     &size, 6)
                         : BZ2_bzBuffToBuffCompress(out.data(), &size, input.data(),
                                                    static_cast<unsigned int>(input.size()), 9, 0, 30);
  EXPECT_EQ(status, 0) << compression;
  out.resize(size);
  return out;
}

/// `packed` decompressed into its `size` bytes.
std::string decompressed(std::string packed, const std::string& compression, std::size_t size) {
  std::string out(size, '\0');
  auto produced = static_cast<unsigned int>(size);
  const int status = compression == "lz4"
                         ? roslz4_buffToBuffDecompress(packed.data(), static_cast<unsigned int>(packed.size()),
                                                       out.data(), &produced)
                         : BZ2_bzBuffToBuffDecompress(out.data(), &produced, packed.data(),
                                                      static_cast<unsigned int>(packed.size()), 0, 0);
  EXPECT_EQ(status, 0) << compression;
  EXPECT_EQ(produced, size) << compression;
  return out;
}

/// Rewrites the first chunk of the compressed bag `file`: its data decompressed, changed by `change`, compressed
/// again, and the bag header's index position moved by the change in length. Returns the chunk's byte position.
std::size_t rewrite_first_chunk(const std::filesystem::path& file, const std::function<void(std::string&)>& change) {
  auto bytes = file_bytes(file);
  const std::size_t bag_header = 13;  // after "#ROSBAG V2.0\n"
  const auto bag_data_length_at = bag_header + 4 + u32_at(bytes, bag_header);
  const auto chunk = bag_data_length_at + 4 + u32_at(bytes, bag_data_length_at);
  const auto chunk_header = bytes.substr(chunk + 4, u32_at(bytes, chunk));
  const auto data_length_at = chunk + 4 + chunk_header.size();
  const auto data_length = u32_at(bytes, data_length_at);
  const auto compression = chunk_header.substr(chunk_header.find("compression=") + 12, 3);
  const auto size = u32_at(chunk_header, chunk_header.find("size=") + 5);
  auto plain = decompressed(bytes.substr(data_length_at + 4, data_length), compression, size);
  change(plain);
  const auto packed = compressed(plain, compression);
  const auto new_length = static_cast<std::uint32_t>(packed.size());
  bytes.replace(data_length_at, 4 + data_length, std::string(reinterpret_cast<const char*>(&new_length), 4) + packed);
  const auto index_pos_at = bytes.find("index_pos=") + 10;
  std::uint64_t index_pos = 0;
  std::memcpy(&index_pos, bytes.data() + index_pos_at, 8);
  index_pos = index_pos + packed.size() - data_length;
  std::memcpy(bytes.data() + index_pos_at, &index_pos, 8);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  return chunk;
}

/// A bag of one valid event in a chunk compressed with `compression` (rosbag's LZ4 or BZ2).
std::filesystem::path compressed_event_bag(const std::string& name, rosbag::compression::CompressionType compression) {
  msg::String m;
  m.data = ros_string(R"({"tick": 1.0, "t": 1.0, "source": "x", "type": "y"})");
  return bag_with_message(name, std::string(topics::kEvents), m, compression);
}

/// The compressions rosbag writes besides none, by their names in a chunk header.
const std::vector<std::pair<std::string, rosbag::compression::CompressionType>> kCompressions = {
    {"lz4", rosbag::compression::LZ4}, {"bz2", rosbag::compression::BZ2}};

}  // namespace

TEST(Replay, AnEventThatIsNotJsonNamesTheBag) {
  const auto file = bag_with_event_text("bad-json", "{\"tick\": 1.0, \"t\":");
  const auto e = replay_error(file);
  EXPECT_EQ(e.where().file, file.string()) << e.what();
  EXPECT_NE(std::string(e.what()).find("not a readable freeplay recording"), std::string::npos) << e.what();
}

TEST(Replay, AnEventOfTheWrongShapeNamesTheBag) {
  // Valid JSON whose fields have the wrong types: the metrics unit's reads fail, and the error names the bag.
  const auto file = bag_with_event_text(
      "bad-shape", R"({"tick": 1.0, "t": 1.0, "source": "robot", "type": "move_result", "data": {"item": 3}})");
  const auto e = replay_error(file);
  EXPECT_EQ(e.where().file, file.string()) << e.what();
}

TEST(Replay, ARecordLengthPastTheEndOfTheFileIsRefusedBeforeRosbagReadsIt) {
  const auto file = bag_with_event_text("bad-length", R"({"tick": 1.0, "t": 1.0, "source": "x", "type": "y"})");
  write_u32_at(file, 13, 0xFFFFFFF0U);  // the first record's header length, after "#ROSBAG V2.0\n"
  const auto e = replay_error(file);
  EXPECT_EQ(e.where().file, file.string()) << e.what();
  EXPECT_NE(std::string(e.what()).find("corrupt bag record at byte 13"), std::string::npos) << e.what();
}

TEST(Replay, AHeaderFieldLongerThanItsHeaderIsRefusedBeforeRosbagReadsIt) {
  // ROS's Header::parse trusts a field's length and copies past its buffer (found by fuzz_bag under ASan).
  const auto file = bag_with_event_text("bad-field", R"({"tick": 1.0, "t": 1.0, "source": "x", "type": "y"})");
  write_u32_at(file, 17, 4000);  // the bag header's first field length (after the magic and the header's own length)
  const auto e = replay_error(file);
  EXPECT_EQ(e.where().file, file.string()) << e.what();
  EXPECT_NE(std::string(e.what()).find("corrupt bag record at byte 13: a malformed header"), std::string::npos) << e.what();
}

TEST(Replay, MoreConnectionsThanTheIndexHoldsAreRefusedBeforeRosbagReadsPastTheFile) {
  // rosbag reads `conn_count` connection records from the index position, past the file's end if it claims more
  // (found by fuzz_bag: a realloc of a garbage length, then rosbag's assert).
  const auto file = bag_with_event_text("bad-conn-count", R"({"tick": 1.0, "t": 1.0, "source": "x", "type": "y"})");
  patch_u32(file, "conn_count=", 11, 1000);  // the value after the name
  const auto e = replay_error(file);
  EXPECT_EQ(e.where().file, file.string()) << e.what();
  EXPECT_NE(std::string(e.what()).find("counts 1000 connection records at its index, fewer are there"), std::string::npos)
      << e.what();
}

TEST(Replay, TheVersionLineIsReadAsRosbagReadsIt) {
  // rosbag reads the version up to the first newline: records after a longer line are checked where rosbag reads
  // them (fuzz_bag found "#ROSBAG V2.0#..." skipping the check, then rosbag's assert), and a 1.2 bag is refused.
  const auto file = bag_with_event_text("bad-version", R"({"tick": 1.0, "t": 1.0, "source": "x", "type": "y"})");
  {
    std::fstream f(file, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(12);
    f.put('#');
  }
  EXPECT_EQ(replay_error(file).where().file, file.string());
  {
    std::fstream f(file, std::ios::binary | std::ios::in | std::ios::out);
    f.write("#ROSBAG V1.2\n", 13);
  }
  const auto e = replay_error(file);
  EXPECT_NE(std::string(e.what()).find("a ROS bag 1.2 (freeplay reads bags of version 2.0)"), std::string::npos) << e.what();
  // rosbag reads the line with fgets into 1 024 bytes: without a newline, its first record starts at byte 1 023
  // (found by fuzz_bag: a header length of 3.6 GB there, then rosbag's assert).
  {
    std::ofstream f(file, std::ios::binary | std::ios::trunc);
    f << "#ROSBAG V2.0" << std::string(1011, 'x');
    const std::uint32_t huge = 0xD79F828DU;
    f.write(reinterpret_cast<const char*>(&huge), 4);
    f << std::string(44, 'y');
  }
  const auto long_line = replay_error(file);
  EXPECT_NE(std::string(long_line.what()).find("corrupt bag record at byte 1023: a header of 3617555085 bytes"),
            std::string::npos)
      << long_line.what();
}

TEST(Replay, AnIndexShorterThanItsDataIsRefusedBeforeRosbagReadsPastIt) {
  // rosbag reads `count` entries and the next index record right after them (found by fuzz_bag: count 0 over 12
  // bytes, then a garbage header length and rosbag's assert).
  const auto file = bag_with_event_text("bad-index-count", R"({"tick": 1.0, "t": 1.0, "source": "x", "type": "y"})");
  patch_u32(file, std::string("\x0a\0\0\0count=", 10), 10, 0);  // the index record's count (first such field)
  const auto e = replay_error(file);
  EXPECT_NE(std::string(e.what()).find("an index of 0 entries holds 12 bytes"), std::string::npos) << e.what();
}

TEST(Replay, AZoneWithMorePointsThanItsMessageIsRefusedBeforeItIsAllocated) {
  // The case fuzz_bag found: a Marker's point count of ~1.9e9, which ROS resized to (46 GB) before reading a point.
  msg::MarkerArray zones;
  msg::Marker zone;
  zone.ns = ros_string("sandbox_zone_water");
  msg::Point p;
  p.x = 1234.5;  // found in the file below
  zone.points = {p, p, p};
  zones.markers.push_back(zone);
  const auto file = bag_with_message("bad-points", std::string(topics::kZones), zones);
  const double sentinel = 1234.5;
  patch_u32(file, std::string(reinterpret_cast<const char*>(&sentinel), sizeof sentinel), -4, 0x73000000U);  // the count
  const auto e = replay_error(file);
  EXPECT_EQ(e.key(), topics::kZones) << e.what();
  EXPECT_NE(std::string(e.what()).find("corrupt message"), std::string::npos) << e.what();
}

TEST(Replay, AMessageOfAnotherTypeOnAKnownTopicNamesBothTypes) {
  msg::String text;
  text.data = ros_string("not zones");
  const auto file = bag_with_message("wrong-type", std::string(topics::kZones), text);
  const auto e = replay_error(file);
  EXPECT_EQ(e.where().file, file.string()) << e.what();
  EXPECT_EQ(e.key(), topics::kZones) << e.what();
  EXPECT_NE(std::string(e.what()).find("std_msgs/String"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("visualization_msgs/MarkerArray"), std::string::npos) << e.what();
}

TEST(Replay, MessagesOfEveryLengthAreStillRead) {
  // The allocation bound is met exactly by a string that is the whole message (its length plus 4 bytes).
  for (const std::size_t n : {0UL, 1UL, 15UL, 16UL, 29UL, 30UL, 31UL, 200UL}) {
    const auto file = bag_with_event_text("lengths", std::string(n, 'a'));  // the string is the whole message
    Bag bag;
    open_session_bag(file, bag);
    rosbag::View view(bag.get());
    for (const auto& m : view) EXPECT_EQ(read_message<msg::String>(m)->data.size(), n);
  }
}

TEST(Replay, TheRecordsInsideCompressedChunksAreCheckedLikeUncompressedOnes) {
  // rosbag decompresses a chunk and parses the record at an index entry's offset with ROS's Header::parse, which
  // trusts its field lengths (found by fuzz_bag: a heap-buffer-overflow from a malformed header in an lz4 chunk).
  for (const auto& [name, compression] : kCompressions) {
    const auto file = compressed_event_bag("compressed-" + name, compression);
    EXPECT_NO_THROW(check_bag_structure(file)) << name;
    rewrite_first_chunk(file, [](std::string&) {});  // the same records, compressed again: still a good bag
    EXPECT_NO_THROW(check_bag_structure(file)) << name;
    EXPECT_NO_THROW(read_session(file)) << name;
    const auto chunk = rewrite_first_chunk(file, [](std::string& plain) {
      const auto op = plain.find(std::string("op=\x02", 4));  // the message record's op field, after its length
      ASSERT_NE(op, std::string::npos);
      const std::uint32_t past_the_header = 0x7FFF;
      std::memcpy(plain.data() + op - 4, &past_the_header, 4);
    });
    const auto e = replay_error(file);
    EXPECT_EQ(e.where().file, file.string()) << e.what();
    EXPECT_NE(std::string(e.what()).find(fmt::format("of the {} chunk at byte {}, decompressed: a malformed header", name,
                                                     chunk)),
              std::string::npos)
        << e.what();
  }
}

TEST(Replay, ACompressedChunkMustDecompressToExactlyItsSize) {
  for (const auto& [name, compression] : kCompressions) {
    const auto file = compressed_event_bag("compressed-size-" + name, compression);
    const auto bytes = file_bytes(file);
    const auto size_at = bytes.find("size=") + 5;  // the chunk's (the bag header has no size field)
    patch_u32(file, "size=", 5, u32_at(bytes, size_at) + 16);
    const auto e = replay_error(file);
    EXPECT_NE(std::string(e.what()).find(fmt::format("its {} data decompress to {} bytes, its size says {}", name,
                                                     u32_at(bytes, size_at), u32_at(bytes, size_at) + 16)),
              std::string::npos)
        << e.what();
    patch_u32(file, "size=", 5, u32_at(bytes, size_at) - 1);  // too small a buffer: the decompressor stops
    EXPECT_NE(std::string(replay_error(file).what()).find("do not decompress into its size"), std::string::npos) << name;
  }
}

TEST(Replay, AChunkOfAnUnknownCompressionNamesTheAllowedOnes) {
  const auto file = compressed_event_bag("compressed-unknown", rosbag::compression::LZ4);
  {
    const auto at = file_bytes(file).find("compression=lz4") + 12;
    std::fstream f(file, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(static_cast<std::streamoff>(at));
    f.write("zip", 3);
  }
  const auto e = replay_error(file);
  EXPECT_NE(std::string(e.what()).find("a chunk compressed with 'zip' (allowed: none, lz4, bz2)"), std::string::npos)
      << e.what();
}
