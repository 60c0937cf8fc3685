#pragma once
// Runs the episodes of a suite on worker threads: resumable, interruptible (Ctrl-C keeps every finished
// episode), shardable, and independent of the number of workers (each episode's result depends only on its seed).

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/scenario/suite.hpp"
#include "freeplay/results/run_folder.hpp"

namespace freeplay::runner {

/// What one finished episode produced.
struct EpisodeOutput {
  nlohmann::json record;                      ///< its line of episodes.jsonl (the runner adds identity fields)
  std::map<std::string, std::string> files;   ///< extra files, relative to the run folder (events, annotations)
  double simulated_s = 0.0;                   ///< simulated seconds (for progress and speed)
};

/// One episode to run.
struct EpisodeTask {
  const scenario::SuiteVariant* variant = nullptr;  ///< which variant
  int index = 0;                          ///< episode index within the variant
  std::uint64_t seed = 0;                 ///< the episode's root seed
  bool events = true;                     ///< the run keeps event logs (the episode may skip writing them)
};

/// Runs one episode; must return promptly with `std::nullopt`-like empty record when `stop` becomes true.
using EpisodeFunction = std::function<EpisodeOutput(const EpisodeTask& task, const std::atomic<bool>& stop)>;

/// What a run keeps of each episode's event log (`--events`).
enum class EventsOutput {
  Auto,  ///< All up to kAutoEventsMaxEpisodes episodes in the shard, None above (sweeps at scale)
  All,   ///< events/<episode>.jsonl
  Gz,    ///< events/<episode>.jsonl.gz (gzip, zlib)
  None,  ///< no event log (episodes.jsonl and annotations only)
};
/// Shards of more episodes than this keep no event logs under EventsOutput::Auto.
inline constexpr int kAutoEventsMaxEpisodes = 1000;
/// EventsOutput from "auto", "all", "gz" or "none"; throws InputError listing them.
EventsOutput events_output_from_name(std::string_view name);

/// Options of a run.
struct RunOptions {
  int jobs = 1;                     ///< worker threads (one episode each at a time)
  std::filesystem::path out;        ///< run folder (created; resumed when it holds finished episodes)
  bool progress = true;             ///< draw the progress line on stderr
  int shard_index = 0;              ///< this shard (0-based)
  int shard_count = 1;              ///< number of shards
  std::string title;                ///< heading of summary.md
  EventsOutput events = EventsOutput::Auto;  ///< what to keep of the event logs
};

/// What a run did.
struct RunReport {
  int total = 0;            ///< episodes in this shard
  int skipped = 0;          ///< already finished before (resumed)
  int finished = 0;         ///< finished by this invocation
  bool interrupted = false; ///< stopped early by `stop`
  std::filesystem::path dir;///< run folder
};

/// The root seed of episode `index` of a scenario with root seed `scenario_seed` (same for every variant, so
/// conditions share synthetic children: common random numbers).
std::uint64_t episode_seed(std::uint64_t scenario_seed, int index);
/// True when episode (variant id, index) belongs to shard `shard_index` of `shard_count` (balanced, deterministic).
bool in_shard(const std::string& variant_id, int index, int shard_index, int shard_count);

/// Builds each child-robot variant's policy once and asks it whether it can play the variant's episodes (bad
/// policy parameters, a yoked policy's missing source episodes): InputError before any episode starts.
void check_policies(const scenario::Suite& suite);

/// Runs every unfinished episode of `suite` in this shard (after `check_policies`); writes episodes.jsonl, per-episode files,
/// summary.csv and summary.md (also when interrupted, for the finished episodes).
RunReport run_suite(const scenario::Suite& suite, const RunOptions& options, const EpisodeFunction& run_episode,
                    std::atomic<bool>& stop);

/// The episodes a run of `suite` must hold (with configuration hashes); `title` defaults to the suite name.
results::ExpectedRun expected_run(const scenario::Suite& suite, const std::string& title = {});

}  // namespace freeplay::runner
