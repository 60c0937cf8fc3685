#pragma once
// One episode: the protocol of the paper (greetings, tutorial, free play until the children stop or the cap,
// debriefing) on the simulated sandtray, with synthetic children and, in child-robot scenarios, the robot's play
// policy, planner, move executor and body. Deterministic from one root seed.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "freeplay/agents/annotations.hpp"
#include "freeplay/agents/params.hpp"
#include "freeplay/agents/session.hpp"
#include "freeplay/core/event_log.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/runner/child_action_source.hpp"
#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/runner/move_driver.hpp"
#include "freeplay/runner/robot_action_source.hpp"
#include "freeplay/runner/robot_body.hpp"
#include "freeplay/scenario/scenario.hpp"
#include "freeplay/runner/signal_source.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "freeplay/sim/item_catalogue.hpp"

namespace freeplay::runner {

/// Immutable models shared by every episode of a process (loaded once, read-only, safe across threads).
struct SharedModels {
  std::shared_ptr<const sim::ItemCatalogue> catalogue;        ///< the game's items
  std::shared_ptr<const agents::ChildModelParams> child_params;  ///< the calibrated child model
  RobotBodyFactory robot_body;                               ///< builds the robot's body per episode

  /// The shipped catalogue, child model and the default robot body.
  static SharedModels load_default();
  /// The shipped models, loaded once per process on first use (thread-safe): for tests, benchmarks and tools.
  static const SharedModels& shipped();
};

/// Everything one episode produced.
struct EpisodeResult {
  nlohmann::json record;                   ///< its line of episodes.jsonl (without run identity fields)
  EventLog events;                         ///< the full event log
  agents::SessionAnnotations annotations;  ///< ground truth as the coder labels it (PInSoRo format)
  std::vector<agents::ChildOutcome> children;  ///< each synthetic child: profile, coded and internal timelines
  bool hit_cap = false;                    ///< free play stopped at the 40-minute cap
  double simulated_s = 0.0;                ///< whole protocol, simulated seconds
  double duration_s = 0.0;                 ///< free-play duration
  bool aborted = false;                    ///< stopped early by the stop flag: discard
};

/// Never set: the stop flag of an episode that runs to its end.
inline const std::atomic<bool> kNeverStop{false};

/// What one episode runs: the scenario, its root seed and the models, and the parts a front replaces (children's
/// actions, what decides for the robot, the robot's finger, signals from outside). Deterministic from these alone.
struct EpisodeInputs {
  const scenario::Scenario& scenario;                              ///< what it runs (validated)
  std::uint64_t seed = 0;                                ///< root seed
  const SharedModels& models = SharedModels::shipped();  ///< the catalogue, child model and robot body
  const std::atomic<bool>& stop = kNeverStop;            ///< the episode returns `aborted` once this becomes true
  std::string id = "episode";                            ///< file id (`<variant>-<index>`) the observers see
  int episode_index = 0;                                 ///< index within its variant (the policy's context)
  /// The children's free-play actions instead of the synthetic agents' (which then leave no annotations), or null.
  ChildActionSource* children = nullptr;
  /// Child-robot scenarios: what decides for the robot instead of the scenario's policy, in front of the one robot
  /// side (the web page's wizard and SPARC modes, `freeplay serve --robot external`'s goals); reset by the episode,
  /// not owned; or null.
  policies::PlayPolicy* decisions = nullptr;
  /// Child-robot scenarios: the robot's finger poses from outside (a live graph's `/poses`), or null. Without
  /// `decisions` they replace the robot side; with them, both act (the poses first, at every free-play tick).
  RobotActionSource* robot = nullptr;
  /// Child-robot scenarios: hears every move of the robot side's driver besides the world (a live graph's
  /// move_sandbox_items server: its feedback, result and `/poses`); not owned; or null.
  MoveObserver* moves = nullptr;
  /// Signals received from outside, applied at every tick: `start_tutorial`, `start_freeplay` and (in free play)
  /// `blank_interface` end the stages before the one they start (free play then ends "by signal"); every other
  /// signal goes to the game as it is. Null: none.
  SignalSource* signals = nullptr;

  /// The identity its observers see.
  EpisodeInfo info() const { return {&scenario, id, seed, episode_index}; }
  /// The same inputs, stopped by `other` instead (a live front's own stop); every field but `stop` is copied here,
  /// next to the fields, so a new field is not dropped.
  EpisodeInputs stopped_by(const std::atomic<bool>& other) const {
    return {.scenario = scenario,
            .seed = seed,
            .models = models,
            .stop = other,
            .id = id,
            .episode_index = episode_index,
            .children = children,
            .decisions = decisions,
            .robot = robot,
            .moves = moves,
            .signals = signals};
  }
};

/// Where an episode's ticks go while it runs: observers that see every 10 Hz tick of every stage (cameras,
/// recorders, live fronts). The result is identical to the run without observers except for the fields the
/// observers add to the record.
struct EpisodeOutputs {
  std::vector<EpisodeObserver*> observers;  ///< called in order at every tick (not owned)
};

/// The outputs that hand every tick to `observers`, in order (they stay owned by the caller).
EpisodeOutputs observed_by(const EpisodeObservers& observers);

/// Runs one episode of `inputs` with `outputs` watching; returns with `aborted` when `inputs.stop` becomes true.
EpisodeResult run_episode(const EpisodeInputs& inputs, const EpisodeOutputs& outputs = {});

/// Makes the observers an episode of a scenario needs (cameras, recorder) for the run folder `run_dir`.
using ObserverFactory = std::function<EpisodeObservers(const scenario::Scenario& scenario, const std::filesystem::path& run_dir)>;

/// The suite runner's episode function: writes `events/<id>.jsonl` and `annotations/<id>.yaml`; with an
/// observer factory, attaches its observers to each episode (they write under `run_dir`).
EpisodeFunction episode_function(const SharedModels& models, ObserverFactory observers = {},
                                 std::filesystem::path run_dir = {});

}  // namespace freeplay::runner
