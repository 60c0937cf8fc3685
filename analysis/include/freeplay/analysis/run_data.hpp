#pragma once
// The comparable numbers of a run folder: per finished episode, its identity (variant, index, seed) and every
// numeric metric as a dotted name (`duration_s` plus each numeric leaf of `metrics`, e.g. `metrics.label_share.…`).

#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace freeplay::analysis {

/// One finished episode: identity and comparable metrics.
struct EpisodeValues {
  std::string variant;                    ///< suite variant id
  int episode = 0;                        ///< index within the variant
  std::uint64_t seed = 0;                 ///< the episode's root seed (same seed = same synthetic children)
  std::map<std::string, double> metrics;  ///< dotted metric name → value
  std::map<std::string, std::string> texts = {};  ///< dotted name → string leaf of `metrics` (e.g. metrics.trace_hash)
};

/// The finished episodes of one run folder.
struct RunData {
  std::string dir;                       ///< the folder, as given
  std::string program_version;           ///< program version of the first episode ("" when not recorded)
  std::vector<std::string> variants;     ///< variant ids in order of first appearance
  std::vector<EpisodeValues> episodes;   ///< in the order of episodes.jsonl

  /// The episodes of one variant, in file order.
  std::vector<EpisodeValues> of_variant(const std::string& variant) const;
  /// True when the run holds episodes of `variant`.
  bool has_variant(const std::string& variant) const;
};

/// `duration_s` and the numeric leaves of `metrics` of one episodes.jsonl record, as dotted names.
std::map<std::string, double> comparable_metrics(const nlohmann::json& record);

/// The string leaves of `metrics` of one episodes.jsonl record, as dotted names (e.g. `metrics.trace_hash`).
std::map<std::string, std::string> comparable_texts(const nlohmann::json& record);
/// Builds run data from episodes.jsonl records (`dir` only names the run in messages).
RunData run_from_records(const std::vector<nlohmann::json>& records, const std::string& dir);

/// Reads a run folder's episodes.jsonl (a torn last line is dropped); InputError when it is not a run folder or
/// holds no finished episode.
RunData load_run(const std::filesystem::path& dir);

/// True when `metric` matches any of the shell-style glob `patterns` (`*`, `?`, `[…]`); an empty list matches all.
bool metric_matches(const std::string& metric, const std::vector<std::string>& patterns);

}  // namespace freeplay::analysis
