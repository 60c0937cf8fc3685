#include "freeplay/recording/bag_check.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "freeplay/core/error.hpp"

namespace freeplay::recording {

namespace {

constexpr std::uint64_t kMaxChunkBytes = 512ULL << 20;
constexpr std::size_t kMagicBytes = 13;  // "#ROSBAG V2.0\n"
constexpr char kOpMessage = 0x02, kOpBagHeader = 0x03, kOpIndexData = 0x04, kOpChunk = 0x05, kOpChunkInfo = 0x06;

/// The fields of a record header (`length name=value` pairs); empty on a malformed header.
std::map<std::string, std::string> header_fields(const std::string& header) {
  std::map<std::string, std::string> fields;
  std::size_t at = 0;
  while (at + 4 <= header.size()) {
    std::uint32_t length = 0;
    std::memcpy(&length, header.data() + at, 4);
    at += 4;
    if (length > header.size() - at) return {};
    const auto field = header.substr(at, length);
    at += length;
    const auto eq = field.find('=');
    if (eq == std::string::npos) return {};
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

class Checker {
 public:
  explicit Checker(const std::filesystem::path& file)
      : file_(file), in_(file, std::ios::binary), size_(std::filesystem::file_size(file)) {}

  void run() {
    std::string magic(kMagicBytes, '\0');
    if (!in_.read(magic.data(), kMagicBytes) || magic != "#ROSBAG V2.0\n") return;
    std::uint64_t index_pos = 0;
    bool indexed = true;
    for (std::uint64_t at = kMagicBytes; at < size_;) {
      const auto r = record(at, size_);
      record_starts_.insert(at);
      const char op = op_of(r.fields);
      if (at == kMagicBytes && op == kOpBagHeader) {
        index_pos = uint_field(r.fields, "index_pos", &indexed);
        if (!indexed || index_pos == 0) return;  // unindexed: rosbag says so and how to reindex
      } else if (op == kOpChunk) {
        chunk(at, r);
      } else if (op == kOpIndexData) {
        index_data(at, r);
      } else if (op == kOpChunkInfo) {
        const auto chunk_pos = uint_field(r.fields, "chunk_pos");
        if (!chunk_starts_.contains(chunk_pos)) fail(at, fmt::format("a chunk info points at byte {}, no chunk", chunk_pos));
      }
      at = r.end;
    }
    if (index_pos != 0 && !record_starts_.contains(index_pos)) {
      fail(kMagicBytes, fmt::format("the index position {} is not the start of a record", index_pos));
    }
  }

 private:
  struct Record {
    std::map<std::string, std::string> fields;
    std::uint64_t data_at = 0;      // first byte of the data
    std::uint64_t data_length = 0;
    std::uint64_t end = 0;          // first byte after the record
  };

  [[noreturn]] void fail(std::uint64_t at, const std::string& what) const {
    throw InputError(fmt::format("corrupt bag record at byte {}: {}", at, what), "SESSION_DIR",
                     "a ROS 1 bag written by `freeplay run --record`", {file_.string()});
  }

  std::uint64_t read_u32(std::uint64_t at) {
    std::uint32_t value = 0;
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(at));
    if (!in_.read(reinterpret_cast<char*>(&value), 4)) fail(at, "the file ends inside a length");
    return value;
  }

  /// The record at `at`, which must end by `end`.
  Record record(std::uint64_t at, std::uint64_t end) {
    if (end - at < 4) fail(at, "the record ends inside a length");
    const auto header_length = read_u32(at);
    if (header_length > end - at - 4) fail(at, fmt::format("a header of {} bytes runs past its end", header_length));
    std::string header(header_length, '\0');
    if (!in_.read(header.data(), static_cast<std::streamsize>(header_length))) fail(at, "unreadable header");
    Record r;
    r.fields = header_fields(header);
    const auto length_at = at + 4 + header_length;
    if (end - length_at < 4) fail(length_at, "the record ends inside a length");
    r.data_length = read_u32(length_at);
    r.data_at = length_at + 4;
    if (r.data_length > end - r.data_at) fail(length_at, fmt::format("data of {} bytes run past its end", r.data_length));
    r.end = r.data_at + r.data_length;
    return r;
  }

  void chunk(std::uint64_t at, const Record& r) {
    chunk_starts_.insert(at);
    chunk_size_ = uint_field(r.fields, "size");
    if (chunk_size_ > kMaxChunkBytes) fail(at, "a chunk claims more than 512 MiB");
    chunk_messages_.clear();
    chunk_compressed_ = !(r.fields.contains("compression") && r.fields.at("compression") == "none");
    if (chunk_compressed_) return;  // the records inside are checked by the decompressor's bounds only
    if (chunk_size_ != r.data_length) fail(at, "an uncompressed chunk's size differs from its data length");
    for (std::uint64_t inner = r.data_at; inner < r.end;) {
      const auto m = record(inner, r.end);
      if (op_of(m.fields) == kOpMessage) chunk_messages_.insert(inner - r.data_at);
      inner = m.end;
    }
  }

  void index_data(std::uint64_t at, const Record& r) {
    const auto count = uint_field(r.fields, "count");
    if (count * 12 > r.data_length) fail(at, fmt::format("an index of {} entries holds {} bytes", count, r.data_length));
    for (std::uint64_t i = 0; i < count; ++i) {
      const auto offset = read_u32(r.data_at + i * 12 + 8);
      const bool known = chunk_compressed_ ? offset < chunk_size_ : chunk_messages_.contains(offset);
      if (!known) fail(at, fmt::format("an index entry points at byte {} of its chunk, no message record", offset));
    }
  }

  std::filesystem::path file_;
  std::ifstream in_;
  std::uint64_t size_;
  std::set<std::uint64_t> record_starts_;    // top-level records (a few thousand in a long session)
  std::set<std::uint64_t> chunk_starts_;
  std::set<std::uint64_t> chunk_messages_;   // message records of the last chunk (offsets inside its data)
  std::uint64_t chunk_size_ = 0;
  bool chunk_compressed_ = false;
};

}  // namespace

void check_bag_structure(const std::filesystem::path& file) { Checker(file).run(); }

}  // namespace freeplay::recording
