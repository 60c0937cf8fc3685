#pragma once
// The experiment manager of a web session, after the real supervisor's records tab (free-play-sandbox.md §6):
// condition, per-child demographics, markers and notes during free play, the end-of-session Likert; every change
// rewrites `experiment.yaml` (PInSoRo format, recording::to_experiment_yaml) atomically.

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>

#include "freeplay/recording/session_files.hpp"
#include "freeplay/scenario/scenario.hpp"
#include "freeplay/web/commands.hpp"
#include "freeplay/web/session_log.hpp"

namespace freeplay::web {

/// Keeps the session's `experiment.yaml` (thread-safe).
class ExperimentManager {
 public:
  /// Writes to `path` (nothing is written until the first change); `condition` is the scenario's;
  /// `created_unix_s` names the participants as the supervisor did.
  ExperimentManager(std::filesystem::path path, scenario::Condition condition, std::int64_t created_unix_s,
                    SessionLog& log);

  /// Applies a validated experiment command at free-play time `freeplay_t` (s; negative before free play) and
  /// episode time `t`; throws CommandError (409) when it cannot apply now (e.g. a marker before free play).
  void apply(const Command& command, double freeplay_t, double t);
  /// Records the start of free play (ROS time in ns, as `timestamp`).
  void freeplay_started(std::uint64_t unix_ns);
  /// What the page shows: condition, participants, markers, Likert, file path.
  nlohmann::json state() const;

 private:
  void write() const;  // under mutex_

  std::filesystem::path path_;
  SessionLog& log_;
  std::string id_prefix_;
  mutable std::mutex mutex_;
  recording::ExperimentInfo info_;
  bool finalised_ = false;
};

}  // namespace freeplay::web
