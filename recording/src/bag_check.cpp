#include "freeplay/recording/bag_check.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <bzlib.h>
#include <roslz4/lz4s.h>

#include "freeplay/core/error.hpp"

namespace freeplay::recording {

namespace {

constexpr std::uint64_t kMaxChunkBytes = 512ULL << 20;
constexpr char kOpMessage = 0x02, kOpBagHeader = 0x03, kOpIndexData = 0x04, kOpChunk = 0x05, kOpChunkInfo = 0x06,
               kOpConnection = 0x07;

/// The fields of a record header (`length name=value` pairs that fill it exactly); nullopt when malformed. ROS's
/// Header::parse checks neither that a field fits nor that a length fits, and reads past its buffer.
std::optional<std::map<std::string, std::string>> header_fields(const std::string& header) {
  std::map<std::string, std::string> fields;
  std::size_t at = 0;
  while (at < header.size()) {
    if (header.size() - at < 4) return std::nullopt;
    std::uint32_t length = 0;
    std::memcpy(&length, header.data() + at, 4);
    at += 4;
    if (length > header.size() - at) return std::nullopt;
    const auto field = header.substr(at, length);
    at += length;
    const auto eq = field.find('=');
    if (eq == std::string::npos) return std::nullopt;
    fields[field.substr(0, eq)] = field.substr(eq + 1);
  }
  return fields;
}

/// A little-endian uint32 or uint64 header field; nullopt-like 0 with `ok` false when absent or of another size.
std::uint64_t uint_field(const std::map<std::string, std::string>& fields, const std::string& name, bool* ok = nullptr) {
  const auto it = fields.find(name);
  const bool good = it != fields.end() && (it->second.size() == 4 || it->second.size() == 8);
  if (ok != nullptr) *ok = good;
  if (!good) return 0;
  std::uint64_t value = 0;
  std::memcpy(&value, it->second.data(), it->second.size());
  return value;
}

char op_of(const std::map<std::string, std::string>& fields) {
  const auto it = fields.find("op");
  return it != fields.end() && it->second.size() == 1 ? it->second[0] : '\0';
}

/// Where records are read from: the bag file, or a compressed chunk's data once decompressed.
class Source {
 public:
  virtual ~Source() = default;
  /// Reads `n` bytes starting at `at` into `out`; false when they are not all there.
  virtual bool read(std::uint64_t at, char* out, std::uint64_t n) = 0;
};

/// The bag file, read where asked.
class FileSource final : public Source {
 public:
  explicit FileSource(const std::filesystem::path& file) : in_(file, std::ios::binary) {}
  bool read(std::uint64_t at, char* out, std::uint64_t n) override {
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(at));
    return static_cast<bool>(in_.read(out, static_cast<std::streamsize>(n)));
  }
  /// The stream itself, for the version line.
  std::istream& stream() { return in_; }

 private:
  std::ifstream in_;
};

/// Bytes in memory: a decompressed chunk.
class MemorySource final : public Source {
 public:
  MemorySource(const char* bytes, std::uint64_t size) : bytes_(bytes), size_(size) {}
  bool read(std::uint64_t at, char* out, std::uint64_t n) override {
    if (at > size_ || n > size_ - at) return false;
    std::memcpy(out, bytes_ + at, n);
    return true;
  }

 private:
  const char* bytes_;
  std::uint64_t size_;
};

class Checker {
 public:
  explicit Checker(const std::filesystem::path& file) : path_(file), file_(file), size_(std::filesystem::file_size(file)) {}

  void run() {
    if (!version_2_0()) return;
    std::uint64_t index_pos = 0;
    std::map<std::string, std::string> bag_header;
    for (std::uint64_t at = header_at_; at < size_;) {
      const auto r = record(file_, at, size_);
      ordinal_of_[at] = ops_.size();
      const char op = op_of(r.fields);
      ops_.push_back(op);
      if (at == header_at_ && op == kOpBagHeader) {
        bool indexed = true;
        index_pos = uint_field(r.fields, "index_pos", &indexed);
        if (!indexed || index_pos == 0) return;  // unindexed: rosbag says so and how to reindex
        bag_header = r.fields;
      } else if (op == kOpChunk) {
        chunk(at, r);
      } else if (op == kOpIndexData) {
        index_data(at, r);
      } else if (op == kOpChunkInfo) {
        chunk_info(at, r);
      }
      at = r.end;
    }
    if (index_pos == 0) return;
    if (!ordinal_of_.contains(index_pos)) {
      fail(header_at_, fmt::format("the index position {} is not the start of a record", index_pos));
    }
    index_section(index_pos, bag_header);
  }

 private:
  /// Reads the version line as rosbag does (`fgets` into 1 024 bytes: up to and including the first newline, at most
  /// 1 023 bytes, after which the records start; then `#ROS<name> V<major>.<minor>`); true for 2.0. A 1.2 bag fails
  /// here (rosbag's 1.2 reader trusts its lengths too, and freeplay writes 2.0); anything else is left to rosbag,
  /// which refuses it.
  bool version_2_0() {
    constexpr std::size_t kLineBytes = 1023;
    std::string line;
    char c = 0;
    while (line.size() < kLineBytes && file_.stream().get(c)) {
      line.push_back(c);
      if (c == '\n') break;
    }
    header_at_ = line.size();
    char name[100] = {};
    int major = 0, minor = 0;
    if (std::sscanf(line.c_str(), "#ROS%99s V%d.%d", name, &major, &minor) != 3) return false;
    if (major == 1 && minor == 2) fail(0, "a ROS bag 1.2 (freeplay reads bags of version 2.0)");
    return major == 2 && minor == 0;
  }

  struct Record {
    std::map<std::string, std::string> fields;
    std::uint64_t data_at = 0;      // first byte of the data
    std::uint64_t data_length = 0;
    std::uint64_t end = 0;          // first byte after the record
  };

  /// Throws the InputError for the record at byte `at` of the file (of the decompressed chunk being walked, if any).
  [[noreturn]] void fail(std::uint64_t at, const std::string& what) const {
    throw InputError(fmt::format("corrupt bag record at byte {}{}: {}", at, inside_, what), "SESSION_DIR",
                     "a ROS 1 bag written by `freeplay run --record`", {path_.string()});
  }

  std::uint64_t read_u32(Source& source, std::uint64_t at) {
    std::uint32_t value = 0;
    if (!source.read(at, reinterpret_cast<char*>(&value), 4)) fail(at, "the data end inside a length");
    return value;
  }

  /// The fields of the header stored at `at`; fails when they do not fill it exactly.
  std::map<std::string, std::string> parsed_header(std::uint64_t at, const std::string& header) const {
    auto fields = header_fields(header);
    if (!fields) fail(at, fmt::format("a malformed header: its fields do not fill its {} bytes", header.size()));
    return std::move(*fields);
  }

  /// The record of `source` at `at`, which must end by `end`.
  Record record(Source& source, std::uint64_t at, std::uint64_t end) {
    if (end - at < 4) fail(at, "the record ends inside a length");
    const auto header_length = read_u32(source, at);
    if (header_length > end - at - 4) fail(at, fmt::format("a header of {} bytes runs past its end", header_length));
    std::string header(header_length, '\0');
    if (!source.read(at + 4, header.data(), header_length)) fail(at, "unreadable header");
    Record r;
    r.fields = parsed_header(at, header);
    const auto length_at = at + 4 + header_length;
    if (end - length_at < 4) fail(length_at, "the record ends inside a length");
    r.data_length = read_u32(source, length_at);
    r.data_at = length_at + 4;
    if (r.data_length > end - r.data_at) fail(length_at, fmt::format("data of {} bytes run past its end", r.data_length));
    r.end = r.data_at + r.data_length;
    if (op_of(r.fields) == kOpConnection) {  // a connection's data is the connection header, parsed the same way
      std::string data(r.data_length, '\0');
      if (!source.read(r.data_at, data.data(), r.data_length)) fail(r.data_at, "unreadable connection header");
      parsed_header(r.data_at, data);
    }
    return r;
  }

  /// A chunk record: its records, decompressed first for lz4 and bz2 (rosbag reads a message by decompressing its
  /// whole chunk and parsing the record at the index entry's offset, trusting its header as in an uncompressed chunk).
  void chunk(std::uint64_t at, const Record& r) {
    chunk_starts_.insert(at);
    const auto size = uint_field(r.fields, "size");
    if (size > kMaxChunkBytes) fail(at, "a chunk claims more than 512 MiB");
    chunk_messages_.clear();
    const auto it = r.fields.find("compression");
    const std::string compression = it == r.fields.end() ? "" : it->second;
    if (compression == "none") {
      if (size != r.data_length) fail(at, "an uncompressed chunk's size differs from its data length");
      walk_chunk(file_, r.data_at, r.end);
      return;
    }
    const auto plain = decompressed(at, r, compression, size);
    MemorySource memory(plain.get(), size);
    inside_ = fmt::format(" of the {} chunk at byte {}, decompressed", compression, at);
    walk_chunk(memory, 0, size);
    inside_.clear();
  }

  /// Records the message records among the records of a chunk's data, `begin` to `end` of `source`.
  void walk_chunk(Source& source, std::uint64_t begin, std::uint64_t end) {
    for (std::uint64_t inner = begin; inner < end;) {
      const auto m = record(source, inner, end);
      if (op_of(m.fields) == kOpMessage) chunk_messages_.insert(inner - begin);
      inner = m.end;
    }
  }

  /// The data of the compressed chunk `r` at `at`, decompressed as rosbag does (roslz4 or libbz2, one call); it must
  /// come out exactly `size` bytes (the chunk's `size` field), the size rosbag allocates for it.
  std::unique_ptr<char[]> decompressed(std::uint64_t at, const Record& r, const std::string& compression,
                                       std::uint64_t size) {
    if (compression != "lz4" && compression != "bz2") {
      fail(at, fmt::format("a chunk compressed with '{}' (allowed: none, lz4, bz2)", compression));
    }
    std::string packed(r.data_length, '\0');
    if (!file_.read(r.data_at, packed.data(), r.data_length)) fail(r.data_at, "unreadable chunk data");
    auto plain = std::make_unique_for_overwrite<char[]>(size + 1);  // +1: a valid pointer for size 0
    auto produced = static_cast<unsigned int>(size);
    const int status = compression == "lz4"
                           ? roslz4_buffToBuffDecompress(packed.data(), static_cast<unsigned int>(packed.size()),
                                                         plain.get(), &produced)
                           : BZ2_bzBuffToBuffDecompress(plain.get(), &produced, packed.data(),
                                                        static_cast<unsigned int>(packed.size()), 0, 0);
    if (status != (compression == "lz4" ? ROSLZ4_OK : BZ_OK)) {
      fail(at, fmt::format("its {} data do not decompress into its size of {} bytes (error {})", compression,
                           size, status));
    }
    if (produced != size) {
      fail(at, fmt::format("its {} data decompress to {} bytes, its size says {}", compression, produced, size));
    }
    return plain;
  }

  void index_data(std::uint64_t at, const Record& r) {
    const auto count = uint_field(r.fields, "count");
    // rosbag reads count × 12 bytes and the next record right after them, so the data must be exactly that long.
    if (count * 12 != r.data_length) fail(at, fmt::format("an index of {} entries holds {} bytes", count, r.data_length));
    for (std::uint64_t i = 0; i < count; ++i) {
      const auto offset = read_u32(file_, r.data_at + i * 12 + 8);
      if (!chunk_messages_.contains(offset)) fail(at, fmt::format("an index entry points at byte {} of its chunk, no message record", offset));
    }
  }

  /// A chunk-info record: it must point at a chunk and list its connections within its data.
  void chunk_info(std::uint64_t at, const Record& r) {
    const auto chunk_pos = uint_field(r.fields, "chunk_pos");
    if (!chunk_starts_.contains(chunk_pos)) fail(at, fmt::format("a chunk info points at byte {}, no chunk", chunk_pos));
    const auto count = uint_field(r.fields, "count");
    // Read like an index record: count × 8 bytes, then the next record.
    if (count * 8 != r.data_length) fail(at, fmt::format("a chunk info of {} connections holds {} bytes", count, r.data_length));
    std::set<std::uint64_t> connections;
    for (std::uint64_t i = 0; i < count; ++i) connections.insert(read_u32(file_, r.data_at + i * 8));
    chunk_connections_.emplace_back(chunk_pos, connections.size());
  }

  /// What rosbag reads when it opens the bag: from the index position, `conn_count` connection records then
  /// `chunk_count` chunk-info records; after each chunk, one index-data record per connection in its chunk info.
  /// rosbag reads as many records as these counts say, past the file's end if need be.
  void index_section(std::uint64_t index_pos, const std::map<std::string, std::string>& bag_header) {
    bool has_counts = true, has_chunks = true;
    const auto connections = uint_field(bag_header, "conn_count", &has_counts);
    const auto chunks = uint_field(bag_header, "chunk_count", &has_chunks);
    if (!has_counts || !has_chunks) return;  // rosbag names the missing field
    const auto first = ordinal_of_.at(index_pos);
    const auto expect = [&](std::size_t ordinal, char op, std::uint64_t at, const std::string& what) {
      if (ordinal >= ops_.size() || ops_[ordinal] != op) fail(at, what);
    };
    for (std::uint64_t i = 0; i < connections; ++i) {
      expect(first + i, kOpConnection, header_at_,
             fmt::format("the bag header counts {} connection records at its index, fewer are there", connections));
    }
    for (std::uint64_t i = 0; i < chunks; ++i) {
      expect(first + connections + i, kOpChunkInfo, header_at_,
             fmt::format("the bag header counts {} chunk-info records at its index, fewer are there", chunks));
    }
    for (const auto& [chunk_pos, count] : chunk_connections_) {
      for (std::size_t i = 1; i <= count; ++i) {
        expect(ordinal_of_.at(chunk_pos) + i, kOpIndexData, chunk_pos,
               fmt::format("the chunk's info lists {} connections, fewer index records follow the chunk", count));
      }
    }
  }

  std::filesystem::path path_;
  FileSource file_;
  std::uint64_t size_;
  std::string inside_;  // while a decompressed chunk is walked: which one, for error messages
  std::uint64_t header_at_ = 0;  // the bag header record, after the version line
  std::map<std::uint64_t, std::size_t> ordinal_of_;  // top-level records' starts (a few thousand in a long session)
  std::vector<char> ops_;                            // top-level records' ops, in file order
  std::vector<std::pair<std::uint64_t, std::size_t>> chunk_connections_;  // chunk-info: its chunk, its connections
  std::set<std::uint64_t> chunk_starts_;
  std::set<std::uint64_t> chunk_messages_;   // message records of the last chunk (offsets inside its data)
};

}  // namespace

void check_bag_structure(const std::filesystem::path& file) { Checker(file).run(); }

}  // namespace freeplay::recording
