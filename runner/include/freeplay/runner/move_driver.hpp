#pragma once
// The one way the robot moves an item, for every front: plan the drag, stream it through the move_sandbox_items
// executor as 10 Hz finger poses (the game's `/poses` fake touches, which the Nao's arm follows) and report how the
// move ended. The in-process episode (RobotSide), the web page's wizard and SPARC modes and `freeplay serve --robot
// external` (action sources in front of RobotSide), controller scenarios and `freeplay plan` all drive their moves
// here; only the MoveSink differs (where the poses go and who hears of the move). A MoveObserver hears the same
// moves besides the sink (a live graph's move_sandbox_items server: its feedback, its result and the `/poses` it
// streams).

#include <memory>
#include <optional>
#include <string>

#include "freeplay/core/events.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/planning/move_executor.hpp"
#include "freeplay/policies/play_policy.hpp"

namespace freeplay::runner {

/// The decision and `/poses` rate of a driven move (s): one MoveDriver::step per game tick.
inline constexpr double kMoveTickS = 0.1;

/// Where a driven move acts: the world it plans on, the finger poses it streams and the body that follows them.
class MoveSink {
 public:
  virtual ~MoveSink() = default;
  /// The sandtray as the executor sees it now (TF item centres, footprints, children's fingers).
  virtual planning::MoveWorld move_world() = 0;
  /// The arm that follows the finger poses and reports its fingertip, or null when the body is elsewhere.
  virtual planning::ArmFollower* arm() { return nullptr; }
  /// A move was started (`running` false: the executor refused or could not plan it; its end follows).
  virtual void move_started(const policies::MoveItem& move, bool running, double t) = 0;
  /// One finger pose of the running move (a `/poses` fake touch).
  virtual void finger(const planning::TimedPose& pose, double t) = 0;
  /// A move ended with `status`; `result` is its event (status, reason, measurements).
  virtual void move_ended(const policies::MoveItem& move, planning::MoveStatus status, events::MoveResult result,
                          double t) = 0;
};

/// Hears a driver's moves besides its sink, in the order the sink does (a live graph's action server).
class MoveObserver {
 public:
  virtual ~MoveObserver() = default;
  /// A move was started (`running` false: the executor refused or could not plan it; its end follows).
  virtual void move_started(const policies::MoveItem& move, bool running, double t) = 0;
  /// One finger pose of the running move, after the sink had it.
  virtual void finger(const planning::TimedPose& pose, double t) = 0;
  /// The running move's progress (percent of its poses sent).
  virtual void progress(int percentage) = 0;
  /// A move ended with `outcome` (status, reason, message, measurements), after the sink heard of it.
  virtual void move_ended(const policies::MoveItem& move, const planning::MoveOutcome& outcome, double t) = 0;
};

/// Drives one robot's moves through one move executor and one planner stream (one instance per robot).
class MoveDriver {
 public:
  /// Takes the executor (its planner and settings) and the planner's random stream.
  MoveDriver(std::unique_ptr<planning::MoveExecutor> executor, Rng planner_rng);

  /// Lets `observer` (not owned; null: none) hear every later move besides the sink.
  void set_observer(MoveObserver* observer) { observer_ = observer; }

  /// Plans `move` on the sink's world and starts streaming it; a running move is pre-empted first (its end is
  /// reported and returned). A move that could not start ends at the next `step`.
  std::optional<policies::ActionResult> start(const policies::MoveItem& move, double t, MoveSink& sink);
  /// One tick at `t`: reports a move that could not start, or streams the running move's poses for kMoveTickS and
  /// reports its end; returns how a move ended during this tick, if one did.
  std::optional<policies::ActionResult> step(double t, MoveSink& sink);
  /// Stops the running move (pre-empted); returns its end, or nothing when no move was running.
  std::optional<policies::ActionResult> cancel(double t, MoveSink& sink);
  /// The game released the moved item at `centre` (its placement error).
  void observe_release(const Vec2& centre) { executor_->observe_release(centre); }

  /// True while a move streams poses.
  bool moving() const { return executor_->status() == planning::MoveStatus::Running; }
  /// The current (or last) move.
  const policies::MoveItem& move() const { return move_; }
  /// The current (or last) move's outcome: plan, poses, synchronisation, placement.
  const planning::MoveOutcome& outcome() const { return executor_->current(); }

 private:
  policies::ActionResult finish(double t, MoveSink& sink);

  std::unique_ptr<planning::MoveExecutor> executor_;
  Rng planner_rng_;
  MoveObserver* observer_ = nullptr;
  policies::MoveItem move_;
  bool end_unreported_ = false;  // the move ended in start(), reported at the next step
};

/// The event of a move's end: status, reason, whether the target was in reach, the poses sent and the measurements
/// (path, clearance, synchronisation, duration), so that a recording holds every metric.
events::MoveResult move_result_event(const planning::MoveOutcome& outcome, const std::string& item);

/// What the policy hears of a move that ended with `outcome`.
policies::ActionResult move_action_result(const planning::MoveOutcome& outcome, const std::string& item);

}  // namespace freeplay::runner
