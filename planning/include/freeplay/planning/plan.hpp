#pragma once
// The `plan_motion` service of the real system as a C++ interface: plain inputs in, a timed finger path out.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/core/geometry.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/planning/planner_settings.hpp"

namespace freeplay::planning {

/// Time between finger poses: the `/poses` topic at 10 Hz.
inline constexpr double kPosePeriodS = 0.1;

/// Another item on the tray: its name (TF frame) and its footprint polygon in the `sandtray` frame.
struct Obstacle {
  std::string name;   ///< item name, e.g. "zebra"
  Polygon2 footprint; ///< vertices in `sandtray` (metres)
};

/// One request to move `item` from `start` to `goal` (all in the `sandtray` frame, metres).
struct PlanRequest {
  std::string item;                       ///< moved item; its own footprint is ignored (the "inhibited" frame)
  Vec2 start = Vec2::Zero();              ///< moved item centre
  Vec2 goal = Vec2::Zero();               ///< target of the item centre
  std::vector<Obstacle> obstacles;        ///< footprints of the items on the tray (the moved one may be included)
  std::optional<Polygon2> moved_footprint;///< moved item's footprint at `start` (only used for the clearance metric)
  /// Wall-clock budget; anytime planners use all of it.
  double time_budget_s = kDefaultTimeBudgetS;
  std::uint64_t iteration_budget = 0;     ///< anytime planners / PRM*: stop after this many iterations (0 = none)
};

/// Why a plan failed.
enum class FailureReason {
  None,               ///< the plan succeeded
  GoalOffScreen,      ///< goal outside the 0.600 × 0.335 m screen rectangle
  GoalInsideObstacle, ///< the goal cell's blurred occupancy is at least `goal_blocked_occupancy`
  NoPath,             ///< no chain of free cells links start and goal (sampling planners only)
  TimeBudgetExceeded, ///< the planner ran out of time before finding a path
  InvalidRequest,     ///< the request was malformed (only from `plan_or_report`)
};

/// Lower-case name of a failure reason ("none", "goal_off_screen", …).
std::string_view failure_reason_name(FailureReason reason);

/// One pose of the finger path: position in `sandtray` and its relative time stamp.
struct TimedPose {
  double t = 0.0;                ///< seconds since the start of the move (i × pose period)
  Vec2 position = Vec2::Zero();  ///< `sandtray` frame, metres
};

/// Measurements of one plan (planning time is measured; nothing else depends on the clock).
struct PlanMetrics {
  double planning_time_s = 0.0;  ///< wall-clock time spent planning (metric only)
  double path_length_m = 0.0;    ///< length of the timed path
  double min_clearance_m = 0.0;  ///< least signed distance from the moved item (or path point) to other footprints
  double path_cost = 0.0;        ///< A*: sum of step costs on the grid; sampling planners: 0
  std::uint64_t expanded_nodes = 0; ///< A*: nodes expanded; sampling planners: vertices of the planner's graph
};

/// The answer to a request.
struct PlanResult {
  bool ok = false;                             ///< true when `path` leads from start to goal
  FailureReason reason = FailureReason::None;  ///< why it failed (None when ok)
  std::string message;                         ///< human-readable detail
  std::vector<TimedPose> path;                 ///< finger poses in `sandtray`, stamped i × pose period
  PlanMetrics metrics;                         ///< measurements
};

/// Heuristic of the A* search.
enum class AStarHeuristic {
  Manhattan,  ///< as the real planner (inadmissible with equal-cost diagonal steps)
  Chebyshev,  ///< admissible for unit-minimum step costs: the path cost is then minimal
};

/// Tunable parameters shared by the planners (defaults = the real system where it fixes them).
struct PlannerOptions {
  int blocked_occupancy = 50;       ///< sampling planners: a cell is an obstacle when its occupancy is >= this
  int goal_blocked_occupancy = 99;  ///< every planner: goal rejected when its cell's occupancy is >= this
  /// Sampling planners: finger speed of the re-timed path (5 mm per 0.1 s).
  double finger_speed_mps = kDefaultFingerSpeedMps;
  double pose_period_s = kPosePeriodS;  ///< time between finger poses (`/poses` at 10 Hz)
  bool simplify = true;             ///< sampling planners: shorten the path with OMPL's PathSimplifier
  int outside_margin_cells = 20;    ///< A*: how far (cells) a path may leave the map
  AStarHeuristic heuristic = AStarHeuristic::Manhattan;  ///< A* heuristic
};

/// A motion planner: immutable after construction, so one instance may serve several threads.
class MotionPlanner {
 public:
  virtual ~MotionPlanner() = default;
  /// Registry name ("astar", "rrtconnect", …).
  virtual std::string_view name() const = 0;
  /// Plans the move; draws exactly one value from `rng`; throws InputError on a malformed request.
  virtual PlanResult plan(const PlanRequest& request, Rng& rng) const = 0;
};

/// Names accepted by `make_planner` (kPlannerNames, planner_settings.hpp), sorted.
std::vector<std::string> planner_names();
/// Comma-separated `planner_names()` (for error messages and help texts).
std::string planner_names_joined();
/// The planner registered under `name`; throws InputError listing the allowed names when unknown.
std::unique_ptr<MotionPlanner> make_planner(std::string_view name, const PlannerOptions& options = {});
/// The options a scenario's planner settings ask for: `reject_blocked_goals` off lets every goal through (the real
/// planner plans to any point); the finger speed is the executor's re-timing (`move_executor_config`), not this.
PlannerOptions planner_options(const PlannerSettings& settings);
/// The planner named by `settings`, with `planner_options(settings)`; throws InputError for an unknown name.
std::unique_ptr<MotionPlanner> make_planner(const PlannerSettings& settings);
/// Checks a request (finite coordinates, positive budget, polygons of >= 3 finite vertices); throws InputError.
void validate_request(const PlanRequest& request);
/// Runs `planner` and turns an InputError into a failed result with reason InvalidRequest.
PlanResult plan_or_report(const MotionPlanner& planner, const PlanRequest& request, Rng& rng);
/// Plans with the planner called `planner_name` (the `plan_motion` service of the real system).
PlanResult plan_motion(std::string_view planner_name, const PlanRequest& request, Rng& rng,
                       const PlannerOptions& options = {});

}  // namespace freeplay::planning
