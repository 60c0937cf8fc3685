#pragma once
// The `move_sandbox_items` action server of the real system (`PlaygroundNavigation`: item + target point,
// feedback `int32 percentage`, empty result).
//
// A move order is planned with a `MotionPlanner`, then the timed path is streamed as robot-finger poses into a sink
// (the simulated `/poses` topic), with feedback percentages and pre-emption, exactly as the real `play_traj`:
// poses[0..N−2] one per pose period with feedback i·100/N, then the last pose, then success. The same stream drives
// an `ArmFollower` (the Nao pointing at and looking at the finger, as `nao_behaviours`). The executor is stepped by
// the episode loop in simulated time and reaches the world only through callbacks, so it needs no `freeplay_sim`;
// the game's auto-release 1 s after the last pose is the sandtray's business, not the executor's.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
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

/// Read access to the world the executor needs, as callbacks (TF, `/footprints` and the touches in the real system).
struct MoveWorld {
  /// Current centre of `item` in `sandtray`, or nullopt when the item is unknown (required).
  std::function<std::optional<Vec2>(const std::string& item)> item_centre;
  /// Footprints of every item in `sandtray`, the moved one included (it is excluded by name) (required).
  std::function<std::vector<Obstacle>()> footprints;
  /// True when a child's finger holds `item` now (optional: without it no child is ever seen holding anything).
  std::function<bool(const std::string& item)> held_by_child;
};

/// The robot's reachable disc (the `arm_reach` frame): shoulder projected on the table, reach, shoulder height.
struct ArmReach {
  Vec2 shoulder_xy = Vec2::Zero();  ///< RShoulder projected on the table (sandtray frame)
  double reach = 0.5;               ///< arm reach (m); 0.5 in real sessions
  double shoulder_height = 0.0;     ///< shoulder height above the table (m)
};

/// What the arm reports after following one finger pose.
struct FollowReport {
  Vec2 fingertip_on_screen = Vec2::Zero();  ///< the fingertip projected on the screen plane (sandtray frame)
  bool reachable = true;                    ///< the pose lay within the arm's reach (else the arm points straight)
};

/// The robot body following the finger stream (`nao_behaviours`: point with the right arm, look at the finger).
class ArmFollower {
 public:
  virtual ~ArmFollower() = default;
  /// Points at and looks at `finger` (sandtray frame) at move time `t` (s); returns where the fingertip is then.
  virtual FollowReport follow(const Vec2& finger, double t) = 0;
};

/// Receives each robot-finger pose (the `/poses` topic: frame `sandtray`, 10 Hz); `t` is relative to the move start.
using FingerSink = std::function<void(const TimedPose& pose)>;
/// Receives the action feedback (`int32 percentage`).
using FeedbackSink = std::function<void(int percentage)>;

/// Where a running move sends its output; only `finger` is required.
struct MoveOutputs {
  FingerSink finger;              ///< the `/poses` topic (e.g. `Sandtray::robot_pose`)
  FeedbackSink feedback;          ///< action feedback (optional)
  ArmFollower* arm = nullptr;     ///< the Nao following the stream (optional, not owned)
};

/// State of a move.
enum class MoveStatus {
  Idle,       ///< no move started
  Running,    ///< poses are being streamed
  Succeeded,  ///< the last pose was sent
  Aborted,    ///< planning failed or the move was refused or stopped (see `MoveOutcome::failure`)
  Preempted,  ///< cancelled before the last pose
};

/// Why a move did not succeed.
enum class MoveFailure {
  None,             ///< it succeeded (or is still running)
  PlanningFailed,   ///< the planner found no path (see `MoveOutcome::plan.reason`)
  ItemHeldByChild,  ///< refused: a child held the item when the goal arrived (`check_child_holding`)
  StolenByChild,    ///< stopped: a child grabbed the item while the robot dragged it (`StealResponse::Stop`)
  Preempted,        ///< cancelled by the caller or by a new goal
};

/// Lower-case name of a status ("idle", "running", "succeeded", "aborted", "preempted").
std::string_view move_status_name(MoveStatus status);
/// Lower-case name of a failure ("none", "planning_failed", "item_held_by_child", "stolen_by_child", "preempted").
std::string_view move_failure_name(MoveFailure failure);

/// Synchronisation of the arm with the finger stream, over the poses of one move.
struct SyncMetrics {
  std::size_t samples = 0;          ///< poses followed
  std::size_t unreachable = 0;      ///< poses the follower reported out of reach
  double mean_error_m = 0.0;        ///< mean distance between a finger pose and the fingertip projection at that pose
  double max_error_m = 0.0;         ///< largest such distance
  double mean_lag_s = 0.0;          ///< mean time since the finger was where the fingertip points now
  double max_lag_s = 0.0;           ///< largest such time
  double best_lag_s = 0.0;          ///< delay of the finger stream that best matches the fingertip stream
  double error_at_best_lag_m = 0.0; ///< mean distance between the fingertip stream and the delayed finger stream
};

/// Result of a finished (aborted, cancelled) move, with the per-move metrics.
struct MoveOutcome {
  MoveGoal goal;                             ///< the order
  MoveStatus status = MoveStatus::Idle;      ///< how it ended (Running while it runs)
  MoveFailure failure = MoveFailure::None;   ///< why it did not succeed
  std::string message;                       ///< human-readable detail of the failure
  PlanResult plan;                           ///< the plan (metrics: planning time, length, clearance) or its failure
  std::vector<TimedPose> poses;              ///< the poses to stream (the plan's path, re-timed when asked)
  std::size_t poses_sent = 0;                ///< finger poses delivered to the sink
  double execution_duration_s = 0.0;         ///< move time from the first pose to the last pose sent
  bool stolen_by_child = false;              ///< a child grabbed the item while the robot dragged it
  bool start_in_reach = true;                ///< item centre inside the arm-reach disc (true when no reach is set)
  bool target_in_reach = true;               ///< target inside the arm-reach disc (true when no reach is set)
  SyncMetrics sync;                          ///< arm synchronisation (empty without an `ArmFollower`)
  std::optional<double> placement_error_m;   ///< item centre vs target once released (see `observe_release`)

  /// "none" when it succeeded, otherwise the failure name, or the planner's reason when planning failed.
  std::string reason() const;
};

/// What the executor does when a child grabs the item the robot is dragging.
enum class StealResponse {
  Stop,      ///< stop streaming at once (the 1 s auto-release follows) and abort with `StolenByChild`
  Continue,  ///< keep streaming as the real system did (both joints act); the outcome still flags the steal
};

/// Settings of an executor.
struct MoveExecutorConfig {
  /// Planning budget per move (wall clock, anytime planners use it all).
  double time_budget_s = kDefaultTimeBudgetS;
  std::uint64_t iteration_budget = 0;     ///< planning iteration budget (0 = none), for reproducible anytime plans
  double pose_period_s = kPosePeriodS;    ///< time between finger poses (`/poses` at 10 Hz)
  /// Finger speed (m/s) of a re-timed path (one pose every speed × period along it); nullopt streams the plan's
  /// own poses (A*: one per 5 mm cell, 5 cm/s straight, 7 cm/s diagonal, as the real system).
  std::optional<double> finger_speed_mps;
  /// Stream the first pose at the item centre and the last at the target (the real A* path starts and ends at the
  /// corners of their 5 mm cells, up to 7 mm off each; false = as the real system). No effect on OMPL paths.
  bool exact_endpoints = true;
  std::optional<ArmReach> arm_reach;      ///< reported, not enforced (the real server moves anything)
  /// Refuse a goal whose item a child holds (`ItemHeldByChild`); false = the real system (both joints act).
  bool check_child_holding = true;
  StealResponse on_steal = StealResponse::Stop;  ///< response to a child grabbing the dragged item
  double max_lag_search_s = 2.0;          ///< `SyncMetrics::best_lag_s` is searched in [0, this]
};

/// The executor settings of a scenario's planner settings: its time budget, and its finger speed for re-timing.
MoveExecutorConfig move_executor_config(const PlannerSettings& settings);

/// Counts over every move of an executor (an episode's "items a child took from the robot" and so on).
struct MoveTally {
  std::size_t started = 0;           ///< goals accepted (valid input)
  std::size_t succeeded = 0;         ///< moves that sent their last pose
  std::size_t planning_failed = 0;   ///< moves without a path
  std::size_t refused_held = 0;      ///< goals refused because a child held the item
  std::size_t stolen_by_child = 0;   ///< moves during which a child took the item from the robot
  std::size_t preempted = 0;         ///< moves cancelled before their last pose
};

/// Plans and streams one move at a time; owns only per-move state (one instance per episode).
class MoveExecutor {
 public:
  /// Uses `planner` (shared, immutable) for every move; throws InputError for a null planner or bad settings.
  MoveExecutor(std::shared_ptr<const MotionPlanner> planner, MoveExecutorConfig config);

  /// Starts a move (pre-empting a running one): looks up the item, checks a child's hold, plans (one draw from
  /// `rng`) and readies the stream, or ends at once as Aborted; throws InputError for an unknown item or a
  /// non-finite target and then leaves the executor unchanged.
  void start(const MoveGoal& goal, const MoveWorld& world, Rng& rng);
  /// Covers the next `dt` seconds of the move: delivers (to the sink, feedback and follower) every pose whose stamp
  /// falls in [elapsed, elapsed + dt), checks whether a child took the item, then advances the move clock.
  void step(double dt, const MoveWorld& world, const MoveOutputs& outputs);
  /// Cancels the running move (pre-emption: status Preempted, no further poses); no effect when none runs.
  void cancel();
  /// Records where the moved item's centre is once the sandtray released it (`releasing_<item>`), filling the
  /// last outcome's `placement_error_m`; no effect while a move runs or when none ran.
  void observe_release(const Vec2& item_centre);

  /// Current status.
  MoveStatus status() const { return current_.status; }
  /// Last feedback percentage sent (0 before the first pose).
  int feedback() const { return last_feedback_; }
  /// The current or last move (its metrics fill in while it runs).
  const MoveOutcome& current() const { return current_; }
  /// The outcome once the move is no longer running (nullopt while Idle or Running).
  std::optional<MoveOutcome> outcome() const;
  /// Counts over every move so far.
  const MoveTally& tally() const { return tally_; }
  /// The settings.
  const MoveExecutorConfig& config() const { return config_; }

 private:
  void finish(MoveStatus status, MoveFailure failure, std::string message);
  void deliver(std::size_t index, const MoveOutputs& outputs);

  std::shared_ptr<const MotionPlanner> planner_;
  MoveExecutorConfig config_;
  MoveOutcome current_;
  MoveTally tally_;
  std::int64_t elapsed_ns_ = 0;
  std::vector<std::int64_t> stamps_ns_;
  std::vector<FollowReport> fingertips_;
  bool child_was_holding_ = false;
  int last_feedback_ = 0;
};

/// Re-times a path at constant speed: poses every `speed_mps × period_s` along it, stamped i × period, the first at
/// its start and the last exactly at its end; throws InputError for a non-positive speed or period.
std::vector<TimedPose> retime_path(const std::vector<TimedPose>& path, double speed_mps, double period_s);

/// Where the finger stream is at time `t`, later than its first pose: linear between the poses around `t`, the last
/// pose from its time on. `segment` is a cursor that only moves forward: start it at 0 and pass non-decreasing times.
inline Vec2 finger_position_after_start(const std::vector<TimedPose>& finger, double t, std::size_t& segment) {
  if (t >= finger.back().t) return finger.back().position;
  while (finger[segment + 1].t <= t) ++segment;
  const TimedPose& a = finger[segment];
  const TimedPose& b = finger[segment + 1];
  const double span = b.t - a.t;
  return a.position + (span > 0.0 ? (t - a.t) / span : 1.0) * (b.position - a.position);
}

/// Synchronisation metrics of a fingertip stream against the finger stream it followed (equal lengths; the i-th
/// fingertip was reported when the i-th finger pose was sent, at `finger[i].t`); lags searched in [0, max_lag_s].
SyncMetrics sync_metrics(const std::vector<TimedPose>& finger, const std::vector<FollowReport>& fingertip,
                         double max_lag_s = 2.0);

}  // namespace freeplay::planning
