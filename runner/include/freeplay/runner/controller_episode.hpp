#pragma once
// Controller regression episodes: the Nao alone (no children) driven through a scenario's sequence of pointing,
// gaze, item-move, posture and wait targets, with per-target and aggregated metrics and a golden trace of the
// MuJoCo state.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/core/event_log.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/scenario/scenario.hpp"
#include "freeplay/runner/suite_runner.hpp"

namespace freeplay::runner {

/// The raw state at one golden-trace checkpoint.
struct TraceCheckpoint {
  long step = 0;                ///< physics steps since the sequence started
  double time = 0.0;            ///< simulated seconds since the sequence started
  std::uint64_t hash = 0;       ///< FNV-1a of the raw bytes of qpos then qvel
  std::vector<double> qpos;     ///< every MuJoCo qpos value
  std::vector<double> qvel;     ///< every MuJoCo qvel value
};

/// A golden trace: the state every `interval_steps` physics steps, folded into one hash.
struct ControllerTrace {
  int interval_steps = 50;                    ///< checkpoint spacing (2 ms steps)
  std::string machine;                        ///< machine kind the trace was made on (arch, compiler, MuJoCo)
  std::vector<std::string> qpos_names;        ///< joint name per qpos index ("" for free/ball components)
  std::vector<TraceCheckpoint> checkpoints;   ///< in time order

  /// FNV-1a fold of every checkpoint hash: equal traces, equal hash (bit-exact).
  std::uint64_t hash() const;
};

/// Everything one controller episode produced.
struct ControllerEpisodeResult {
  nlohmann::json record;        ///< its line of episodes.jsonl (metrics, per-target results, trace hash)
  EventLog events;              ///< one event per target start and end
  ControllerTrace trace;        ///< the golden trace
  double simulated_s = 0.0;     ///< simulated seconds
  bool aborted = false;         ///< stopped before the end
};

/// The machine kind a golden trace is bit-exact on (CPU architecture, compiler, MuJoCo version).
std::string trace_machine_kind();

/// Runs a scenario of kind `controller` with root seed `seed` (random target sets draw from it); throws
/// InputError for a scenario of another kind.
ControllerEpisodeResult run_controller_episode(const scenario::Scenario& scenario, std::uint64_t seed,
                                               const SharedModels& models, const std::atomic<bool>& stop);

/// The suite runner's episode for a controller task: record, `events/<id>.jsonl` and `traces/<id>.jsonl`.
EpisodeOutput run_controller_task(const EpisodeTask& task, const SharedModels& models,
                                  const std::atomic<bool>& stop);

/// A trace as JSON lines: a header line, then one line per checkpoint (numbers with round-trip precision).
std::string trace_jsonl(const ControllerTrace& trace);
/// Parses `trace_jsonl` text; InputError naming `file` and the line when malformed.
ControllerTrace parse_trace(const std::string& text, const std::string& file);
/// Loads a trace file.
ControllerTrace load_trace(const std::filesystem::path& path);

/// How two traces differ.
struct TraceDiff {
  bool bit_identical = false;                 ///< same hash, same checkpoints
  bool within_tolerance = false;              ///< same checkpoints and every value within the tolerance
  std::size_t compared = 0;                   ///< checkpoints compared
  std::optional<std::size_t> first_hash_mismatch;  ///< first checkpoint whose hash differs
  std::optional<std::size_t> first_beyond;    ///< first checkpoint with a value beyond the tolerance
  double max_abs_diff = 0.0;                  ///< largest |a − b| over every compared value
  std::string max_at;                         ///< where it is, e.g. "checkpoint 12 (t 0.600 s) qpos[31] RElbowRoll"
  std::string first_beyond_at;                ///< same for the first value beyond the tolerance
  std::string problem;                        ///< structural mismatch (interval, sizes, counts); "" when none
};

/// Compares two traces checkpoint by checkpoint with an absolute tolerance on every qpos and qvel value.
TraceDiff diff_traces(const ControllerTrace& a, const ControllerTrace& b, double tolerance);
/// The diff in a few readable lines.
std::string trace_diff_text(const TraceDiff& diff, double tolerance);

}  // namespace freeplay::runner
