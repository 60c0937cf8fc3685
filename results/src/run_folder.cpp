#include "freeplay/results/run_folder.hpp"

#include <fcntl.h>
#include <fmt/chrono.h>
#include <fmt/format.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"

namespace freeplay::results {

namespace {
constexpr const char* kEpisodesFile = "episodes.jsonl";

/// Calls `visit(line, offset)` for every complete line of `path`; returns the bytes up to the last good line and
/// whether a torn or unparsable last line stopped the scan.
template <typename Visit>
std::pair<std::uint64_t, bool> scan_lines(const std::filesystem::path& path, Visit&& visit) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::uint64_t offset = 0;
  while (std::getline(in, line)) {
    if (in.eof()) return {offset, true};  // no newline: a torn final write (the episode simply runs again)
    const std::uint64_t next = offset + line.size() + 1;
    if (!line.empty() && !visit(line, offset)) return {offset, true};
    offset = next;
  }
  return {offset, false};
}
}  // namespace

RunFolder::RunFolder(std::filesystem::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw InputError(fmt::format("cannot create the run folder: {}", ec.message()), "--out", {},
                           {dir_.string(), 0, 0});
  const auto path = dir_ / kEpisodesFile;
  if (!std::filesystem::exists(path)) return;
  const auto [good_bytes, dropped] = scan_lines(path, [&](const std::string& line, std::uint64_t) {
    try {
      const auto record = nlohmann::json::parse(line);
      mark_finished(record.value("variant", ""), record.value("episode", -1), record.value("config_hash", std::uint64_t{0}));
      ++records_;
      return true;
    } catch (const nlohmann::json::exception&) {
      return false;
    }
  });
  dropped_partial_ = dropped;
  if (dropped_partial_) std::filesystem::resize_file(path, good_bytes);
}

bool RunFolder::finished(const std::string& variant, int index, std::uint64_t config_hash) const {
  std::lock_guard lock(mutex_);
  const auto it = finished_.find(variant);
  if (it == finished_.end() || index < 0 || static_cast<std::size_t>(index) >= it->second.done.size() ||
      !it->second.done[static_cast<std::size_t>(index)]) {
    return false;
  }
  const auto other = it->second.other_hashes.find(index);
  const auto hash = other != it->second.other_hashes.end() ? other->second : it->second.config_hash;
  if (hash != config_hash) {
    throw InputError(fmt::format("this run folder already holds episode {} of '{}' from a different "
                                 "configuration; resume only with the same scenario and overrides",
                                 index, variant),
                     "--out", "a new folder, or the original configuration", {dir_.string(), 0, 0});
  }
  return true;
}

void RunFolder::append(const nlohmann::json& record) {
  const auto line = record.dump() + "\n";
  std::lock_guard lock(mutex_);
  const auto path = dir_ / kEpisodesFile;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd < 0) throw std::runtime_error(fmt::format("cannot open {}: {}", path.string(), std::strerror(errno)));
  const auto n = ::write(fd, line.data(), line.size());  // one write: a crash tears at most this line
  const bool ok = n == static_cast<ssize_t>(line.size()) && ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) throw std::runtime_error(fmt::format("cannot append to {}: {}", path.string(), std::strerror(errno)));
  mark_finished(record.value("variant", ""), record.value("episode", -1), record.value("config_hash", std::uint64_t{0}));
  ++records_;
}

void RunFolder::mark_finished(const std::string& variant, int index, std::uint64_t config_hash) {
  if (index < 0) return;
  const auto [it, first] = finished_.try_emplace(variant);
  auto& f = it->second;
  if (first) f.config_hash = config_hash;
  const auto i = static_cast<std::size_t>(index);
  if (i >= f.done.size()) f.done.resize(i + 1);
  f.done[i] = true;
  if (config_hash != f.config_hash) f.other_hashes[index] = config_hash; else f.other_hashes.erase(index);
}

void RunFolder::for_each_record(const std::function<void(const nlohmann::json&)>& visit) const {
  std::lock_guard lock(mutex_);
  scan_lines(dir_ / kEpisodesFile, [&](const std::string& line, std::uint64_t) {
    visit(nlohmann::json::parse(line));
    return true;
  });
}

std::vector<nlohmann::json> RunFolder::records() const {
  std::vector<nlohmann::json> out;
  for_each_record([&](const nlohmann::json& record) { out.push_back(record); });
  return out;
}

std::size_t RunFolder::record_count() const {
  std::lock_guard lock(mutex_);
  return records_;
}

void RunFolder::finalize(const std::vector<std::string>& variant_order) {
  std::lock_guard lock(mutex_);
  std::unordered_map<std::string, std::size_t> rank;
  for (std::size_t i = 0; i < variant_order.size(); ++i) rank.emplace(variant_order[i], i);
  // The sort keeps only positions (a few bytes per record); the lines are copied from the old file in order.
  struct Line {
    std::size_t rank;
    int episode;
    std::uint64_t offset;
    std::uint64_t length;
  };
  std::vector<Line> lines;
  const auto path = dir_ / kEpisodesFile;
  scan_lines(path, [&](const std::string& line, std::uint64_t offset) {
    const auto record = nlohmann::json::parse(line);
    const auto it = rank.find(record.value("variant", ""));
    lines.push_back({it != rank.end() ? it->second : rank.size(), record.value("episode", 0), offset, line.size()});
    return true;
  });
  std::stable_sort(lines.begin(), lines.end(), [](const Line& a, const Line& b) {
    return a.rank != b.rank ? a.rank < b.rank : a.episode < b.episode;
  });
  std::ifstream in(path, std::ios::binary);
  std::string buffer;
  write_file_atomically(path, [&](const std::function<void(std::string_view)>& write) {
    for (const auto& line : lines) {
      buffer.resize(line.length + 1);
      in.seekg(static_cast<std::streamoff>(line.offset));
      in.read(buffer.data(), static_cast<std::streamsize>(line.length + 1));
      write(buffer);
    }
  });
}

void RunFolder::write(const std::string& relative, std::string_view contents) const {
  write_file_atomically(dir_ / relative, contents);
}

std::string RunFolder::episode_file_id(const std::string& variant, int index) {
  std::string safe;
  for (const char c : variant) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' || c == '=';
    safe += ok ? c : '_';
  }
  return fmt::format("{}-{:04d}", safe, index);
}

std::filesystem::path RunFolder::default_dir(const std::string& name) {
  const auto now = std::chrono::system_clock::now();
  return std::filesystem::path("runs") /
         fmt::format("{:%Y%m%d-%H%M%S}-{}", fmt::gmtime(std::chrono::system_clock::to_time_t(now)), name);
}

std::string gzip_compress(std::string_view contents) {
  z_stream stream{};
  constexpr int kGzipWindowBits = 15 + 16;  // deflate window 2^15, gzip header and trailer
  if (deflateInit2(&stream, Z_DEFAULT_COMPRESSION, Z_DEFLATED, kGzipWindowBits, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    throw std::runtime_error("zlib: cannot start a gzip stream");
  }
  std::string out(deflateBound(&stream, static_cast<uLong>(contents.size())) + 32, '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(contents.data()));
  stream.avail_in = static_cast<uInt>(contents.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = static_cast<uInt>(out.size());
  const int status = deflate(&stream, Z_FINISH);
  deflateEnd(&stream);
  if (status != Z_STREAM_END) throw std::runtime_error("zlib: gzip compression did not finish");
  out.resize(stream.total_out);
  return out;
}

}  // namespace freeplay::results
