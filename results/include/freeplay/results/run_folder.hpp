#pragma once
// The output folder of a run: episodes.jsonl (one record per finished episode), per-episode files, summaries.
// Every file appears whole; an interrupted run keeps its finished episodes and resumes where it stopped.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace freeplay::results {

/// The manifest each run folder carries (suite, variants and their episode counts, shard, overrides).
inline constexpr const char* kRunManifestFile = "run.json";

/// One variant a run must hold.
struct ExpectedVariant {
  std::string id;                            ///< suite variant id
  int episodes = 0;                          ///< episodes 0 … episodes − 1
  std::optional<std::uint64_t> config_hash;  ///< required configuration hash, when known
};

/// The episodes a run must hold, in suite order, and the heading of its summary.
struct ExpectedRun {
  std::string title;                     ///< heading of summary.md (the suite name by default)
  std::vector<ExpectedVariant> variants; ///< in suite order
};

/// The run folder of a suite; safe to share between worker threads. Memory does not grow with the records: it keeps
/// only an index (variant, episode, configuration hash) and reads episodes.jsonl from disk when asked.
class RunFolder {
 public:
  /// Opens or creates `dir`; reads the finished episodes of an earlier, interrupted run (a torn last line of
  /// episodes.jsonl is dropped and reported in `dropped_partial_line()`).
  explicit RunFolder(std::filesystem::path dir);

  /// The folder.
  const std::filesystem::path& dir() const { return dir_; }
  /// True when `variant` episode `index` finished in this folder with the same configuration hash; throws
  /// InputError when it finished with a different configuration (the scenario changed: use another folder).
  bool finished(const std::string& variant, int index, std::uint64_t config_hash) const;
  /// Appends one finished episode's record (needs "variant", "episode", "config_hash"), durable on return.
  void append(const nlohmann::json& record);
  /// Every finished record (earlier and this run), in file order (completion order until finalize).
  std::vector<nlohmann::json> records() const;
  /// Calls `visit` with each finished record in file order, parsing one line at a time (constant memory).
  void for_each_record(const std::function<void(const nlohmann::json&)>& visit) const;
  /// Number of finished records.
  std::size_t record_count() const;
  /// Rewrites episodes.jsonl sorted by variant (in `variant_order`) and episode index, atomically.
  void finalize(const std::vector<std::string>& variant_order);
  /// Writes `relative` inside the folder atomically (e.g. "events/cc-0003.jsonl").
  void write(const std::string& relative, std::string_view contents) const;
  /// True when the last line of an earlier episodes.jsonl was incomplete and was dropped.
  bool dropped_partial_line() const { return dropped_partial_; }

  /// File-name-safe identifier of an episode: "<variant>-<index, 4 digits>" with unsafe characters replaced.
  static std::string episode_file_id(const std::string& variant, int index);
  /// A new default folder name: runs/<UTC timestamp>-<name>.
  static std::filesystem::path default_dir(const std::string& name);

 private:
  std::filesystem::path dir_;
  mutable std::mutex mutex_;
  /// The finished episodes of one variant: one bit per episode index, the configuration hash of the variant's first
  /// record, and the episodes recorded with another hash (rare: a changed scenario).
  struct FinishedEpisodes {
    std::vector<bool> done;
    std::uint64_t config_hash = 0;
    std::map<int, std::uint64_t> other_hashes;
  };
  /// Marks `variant` episode `index` finished with `config_hash` (the caller holds mutex_ or is the constructor).
  void mark_finished(const std::string& variant, int index, std::uint64_t config_hash);
  std::unordered_map<std::string, FinishedEpisodes> finished_;  // by variant
  std::size_t records_ = 0;
  bool dropped_partial_ = false;
};

/// `contents` compressed in the gzip format (zlib, default level), readable with `zcat`.
std::string gzip_compress(std::string_view contents);

}  // namespace freeplay::results
