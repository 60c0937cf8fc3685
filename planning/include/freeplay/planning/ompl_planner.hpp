#pragma once
// Sampling planners from OMPL 1.5 on the same occupancy grid as the A* planner.

#include "freeplay/planning/plan.hpp"

namespace freeplay::planning {

/// Which OMPL algorithm an `OmplPlanner` runs.
enum class OmplAlgorithm {
  RRTConnect,  ///< bidirectional RRT; stops at the first solution
  PRMstar,     ///< PRM* (single-threaded variant, see docs); stops at the first solution or the iteration budget
  RRTstar,     ///< anytime asymptotically optimal RRT*; uses the time (or iteration) budget
  BITstar,     ///< anytime Batch Informed Trees; uses the time budget; not seed-reproducible
};

/// A sampling planner: valid states are cells with occupancy below `blocked_occupancy`; path simplified and
/// re-timed at the finger speed. Every OMPL random generator it can reach is seeded from the request's `Rng`.
class OmplPlanner final : public MotionPlanner {
 public:
  /// Keeps the algorithm and a copy of the options.
  OmplPlanner(OmplAlgorithm algorithm, PlannerOptions options = {});
  /// Registry name ("rrtconnect", "prmstar", "rrtstar", "bitstar").
  std::string_view name() const override;
  /// Plans in the continuous plane; see `MotionPlanner::plan`.
  PlanResult plan(const PlanRequest& request, Rng& rng) const override;

 private:
  OmplAlgorithm algorithm_;
  PlannerOptions options_;
};

/// Resamples a polyline so that consecutive poses are at most `speed × period` apart, stamped i × period.
std::vector<TimedPose> retime_path(const std::vector<Vec2>& waypoints, double speed_mps, double period_s);

}  // namespace freeplay::planning
