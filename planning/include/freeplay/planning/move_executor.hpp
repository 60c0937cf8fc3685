#pragma once
// INTERFACE ONLY (not implemented yet): the `move_sandbox_items` action server of the real system.
//
// A move order (item + target) is planned with a `MotionPlanner`, then the timed path is streamed as robot-finger
// poses at 10 Hz into a sink (the simulated `/poses` topic), with feedback percentages and cancellation, exactly as
// the real `play_traj`: poses[0..N−2] one per period with feedback i·100/N, then the last pose, then success.
// It is stepped by the episode loop in simulated time and reaches the world only through callbacks, so it needs
// no `freeplay_sim` (the game's auto-release after 1 s is the sandtray's business, not the executor's).

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/core/geometry.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/planning/plan.hpp"

namespace freeplay::planning {

/// A move order, as the `PlaygroundNavigation` action goal: item (TF frame) and target point in `sandtray`.
struct MoveGoal {
  std::string item;             ///< item to move, e.g. "hippo"
  Vec2 target = Vec2::Zero();   ///< target of the item centre (sandtray frame, metres)
};

/// Read access to the world the executor needs, as callbacks (TF and `/footprints` in the real system).
struct MoveWorld {
  /// Current centre of `item` in `sandtray`, or nullopt when the item is unknown.
  std::function<std::optional<Vec2>(const std::string& item)> item_centre;
  /// Footprints of every item in `sandtray` (the moved one is excluded by name).
  std::function<std::vector<Obstacle>()> footprints;
};

/// The robot's reachable disc (the `arm_reach` frame): shoulder projected on the table, reach, shoulder height.
struct ArmReach {
  Vec2 shoulder_xy = Vec2::Zero();  ///< RShoulder projected on the table (sandtray frame)
  double reach = 0.5;               ///< arm reach (m); 0.5 in real sessions
  double shoulder_height = 0.0;     ///< shoulder height above the table (m)
};

/// Receives each robot-finger pose (the `/poses` topic: frame `sandtray`, 10 Hz).
using FingerSink = std::function<void(const TimedPose& pose)>;
/// Receives the action feedback (`int32 percentage`).
using FeedbackSink = std::function<void(int percentage)>;

/// State of a move.
enum class MoveStatus {
  Idle,       ///< no move started
  Running,    ///< poses are being streamed
  Succeeded,  ///< the last pose was sent
  Aborted,    ///< planning failed (see `MoveOutcome::plan.reason`)
  Preempted,  ///< cancelled before the last pose
};

/// Result of a finished (or aborted/cancelled) move.
struct MoveOutcome {
  MoveStatus status = MoveStatus::Idle;  ///< how it ended
  PlanResult plan;                       ///< the plan that was executed (or why planning failed)
  std::size_t poses_sent = 0;            ///< finger poses delivered to the sink
  bool start_in_reach = true;            ///< item centre inside the arm-reach disc (true when no reach is set)
  bool target_in_reach = true;           ///< target inside the arm-reach disc (true when no reach is set)
};

/// Settings of an executor.
struct MoveExecutorConfig {
  double time_budget_s = 1.0;            ///< planning budget per move
  std::optional<ArmReach> arm_reach;     ///< reported, not enforced (the real server moves anything)
};

/// Plans and streams one move at a time; owns only per-move state (one instance per episode).
class MoveExecutor {
 public:
  /// Uses `planner` (shared, immutable) for every move.
  MoveExecutor(std::shared_ptr<const MotionPlanner> planner, MoveExecutorConfig config);

  /// Starts a move (pre-empting a running one): looks up the item, plans, and readies the stream; throws
  /// InputError for an unknown item or a non-finite target and then leaves the executor unchanged.
  void start(const MoveGoal& goal, const MoveWorld& world, Rng& rng);
  /// Advances simulated time by `dt` s and delivers every pose whose stamp has come, plus feedback.
  void step(double dt, const FingerSink& sink, const FeedbackSink& feedback);
  /// Cancels the running move (status Preempted; no further poses).
  void cancel();
  /// Current status.
  MoveStatus status() const;
  /// The outcome once the move is no longer running.
  std::optional<MoveOutcome> outcome() const;

 private:
  std::shared_ptr<const MotionPlanner> planner_;
  MoveExecutorConfig config_;
  MoveOutcome current_;
  double elapsed_s_ = 0.0;
};

}  // namespace freeplay::planning
