#pragma once
// Observers of a running episode: what renders cameras and records bags sees of the simulation at each
// 10 Hz tick of every protocol stage (ground truth, unlike the policy's Observation). Observers only read.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "freeplay/core/event_log.hpp"
#include "freeplay/core/geometry.hpp"

namespace freeplay::sim {
class Sandtray;
}

namespace freeplay::scenario {
struct Scenario;
}

namespace freeplay::runner {

struct EpisodeResult;

/// Simulation only: a synthetic child's internal state, which no camera, coder or policy sees (freeplay.Env hands
/// it to Python only as explicitly requested privileged information).
struct ChildHiddenState {
  /// The child's own labels (task engagement, social engagement, social attitude; PInSoRo names) before the
  /// coder's delay and noise: what it intends to do.
  std::array<std::string_view, 3> labels{};
  double motivation = 0.0;          ///< motivation drive in [0, 1]
  double boredom = 0.0;             ///< boredom drive (≥ 0)
  double answer_expectation = 0.0;  ///< how much it expects its partner to answer a bid, in [0, 1]
  bool wants_to_stop = false;       ///< it has decided to stop playing
};

/// One seated child as the cameras see it.
struct ChildSnapshot {
  std::string seat;                              ///< "purple" | "yellow"
  int age_years = 6;                             ///< for the avatar's size
  std::string gender;                            ///< "female" | "male"
  std::string gaze;                              ///< gaze target as in the events ("tray", "item", "partner", …)
  Eigen::Vector3d gaze_point = Eigen::Vector3d::Zero();  ///< the 3-D point looked at (sandtray frame, m)
  Eigen::Vector3d head = Eigen::Vector3d::Zero();        ///< where the child's face is (sandtray frame, m)
  std::vector<std::pair<int, Vec2>> touches;     ///< this child's fingers on the screen: (finger id, point)
  bool speaking = false;                         ///< an utterance is under way
  /// Simulation only: the coder's current labels (task engagement, social engagement, social attitude; the
  /// PInSoRo names), empty before free play.
  std::array<std::string_view, 3> coded{};
  /// Simulation only: the child model's internal state (observers that stand for sensors must not use it).
  ChildHiddenState hidden;
};

/// The robot as the cameras and `joint_states` see it (child-robot episodes only).
struct RobotSnapshot {
  std::vector<std::string> joint_names;          ///< the Nao's joints (sensor_msgs/JointState order)
  std::vector<double> positions;                 ///< rad
  std::vector<double> velocities;                ///< rad/s (zeros in kinematic mode)
  std::vector<double> efforts;                   ///< N·m (zeros in kinematic mode)
  std::optional<Vec2> finger;                    ///< the virtual finger while a move streams poses
  Eigen::Vector3d gaze_point = Eigen::Vector3d::Zero();  ///< where the head looks (sandtray frame, m)
  bool speaking = false;                         ///< the robot is talking
};

/// One tick of an episode, valid only during the `observe` call.
struct EpisodeSnapshot {
  double t = 0.0;                          ///< sandtray clock: simulated seconds since the episode started
  double freeplay_t = 0.0;                 ///< seconds since free play started (negative before it)
  std::string_view stage;                  ///< "greeting" | "tutorial" | "freeplay" | "debriefing"
  const sim::Sandtray* tray = nullptr;     ///< the game (items, touches, zones, drawing, background)
  std::span<const ChildSnapshot> children; ///< purple first
  const RobotSnapshot* robot = nullptr;    ///< null in child-child episodes
  std::span<const Event> new_events;       ///< events emitted since the previous snapshot
};

/// Identity of the episode an observer is attached to.
struct EpisodeInfo {
  const scenario::Scenario* scenario = nullptr;  ///< the scenario it runs
  std::string id;                      ///< file id (`<variant>-<index>`)
  std::uint64_t seed = 0;              ///< the episode's root seed
  int episode_index = 0;               ///< index within its variant (the robot policy's PolicyContext gets it)
};

/// Reads an episode as it runs (cameras, recorders); never changes it.
class EpisodeObserver {
 public:
  virtual ~EpisodeObserver() = default;
  /// Called once before the first snapshot; may throw to refuse the episode (e.g. an unwritable path).
  virtual void begin(const EpisodeInfo& info) { (void)info; }
  /// Called at every 10 Hz tick of every protocol stage, in order.
  virtual void observe(const EpisodeSnapshot& snapshot) = 0;
  /// Called once after the last snapshot with the finished result (not called when the episode aborts); may add
  /// fields to `result.record` (e.g. `gl_renderer`, where a recording went), nothing else.
  virtual void end(EpisodeResult& result) { (void)result; }
  /// Called instead of `end` when the episode stops early (Ctrl-C): leave outputs readable.
  virtual void abort() {}
};

/// The observers of one episode.
using EpisodeObservers = std::vector<std::unique_ptr<EpisodeObserver>>;

}  // namespace freeplay::runner
