#include "freeplay/runner/run_folder.hpp"

#include <fcntl.h>
#include <fmt/chrono.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"

namespace freeplay::runner {

namespace {
constexpr const char* kEpisodesFile = "episodes.jsonl";
}

RunFolder::RunFolder(std::filesystem::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw InputError(fmt::format("cannot create the run folder: {}", ec.message()), "--out", {},
                           {dir_.string(), 0, 0});
  const auto path = dir_ / kEpisodesFile;
  if (!std::filesystem::exists(path)) return;
  std::ifstream in(path, std::ios::binary);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t start = 0;
  std::size_t good_bytes = 0;
  while (start < content.size()) {
    const auto end = content.find('\n', start);
    if (end == std::string::npos) {
      dropped_partial_ = true;  // torn final write: the episode will simply run again
      break;
    }
    const auto line = content.substr(start, end - start);
    if (!line.empty()) {
      try {
        records_.push_back(nlohmann::json::parse(line));
      } catch (const nlohmann::json::exception&) {
        dropped_partial_ = true;
        break;
      }
    }
    start = end + 1;
    good_bytes = start;
  }
  if (dropped_partial_) {
    std::filesystem::resize_file(path, good_bytes);
  }
}

bool RunFolder::finished(const std::string& variant, int index, std::uint64_t config_hash) const {
  std::lock_guard lock(mutex_);
  for (const auto& r : records_) {
    if (r.value("variant", "") == variant && r.value("episode", -1) == index) {
      if (r.value("config_hash", std::uint64_t{0}) != config_hash) {
        throw InputError(fmt::format("this run folder already holds episode {} of '{}' from a different "
                                     "configuration; resume only with the same scenario and overrides",
                                     index, variant),
                         "--out", "a new folder, or the original configuration", {dir_.string(), 0, 0});
      }
      return true;
    }
  }
  return false;
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
  records_.push_back(record);
}

std::vector<nlohmann::json> RunFolder::records() const {
  std::lock_guard lock(mutex_);
  return records_;
}

void RunFolder::finalize(const std::vector<std::string>& variant_order) {
  std::lock_guard lock(mutex_);
  std::map<std::string, std::size_t> rank;
  for (std::size_t i = 0; i < variant_order.size(); ++i) rank[variant_order[i]] = i;
  std::stable_sort(records_.begin(), records_.end(), [&](const auto& a, const auto& b) {
    const auto ra = rank.count(a.value("variant", "")) ? rank[a.value("variant", "")] : rank.size();
    const auto rb = rank.count(b.value("variant", "")) ? rank[b.value("variant", "")] : rank.size();
    if (ra != rb) return ra < rb;
    return a.value("episode", 0) < b.value("episode", 0);
  });
  std::string out;
  for (const auto& r : records_) out += r.dump() + "\n";
  write_file_atomically(dir_ / kEpisodesFile, out);
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

}  // namespace freeplay::runner
