#include "freeplay/planning/ompl_planner.hpp"

#include <chrono>
#include <cmath>
#include <deque>
#include <mutex>

#include <fmt/format.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/terminationconditions/IterationTerminationCondition.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>

#include "freeplay/core/error.hpp"
#include "freeplay/planning/occupancy_grid.hpp"
#include "path_metrics.hpp"

namespace freeplay::planning {

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

constexpr std::uint64_t kPrmBatchChecks = 50;   // termination checks per PRM* growth batch (~25 milestones)
constexpr double kMotionCheckCells = 1.0;       // motion validation step, in cells

std::uint_fast32_t draw_seed(Rng& rng) { return static_cast<std::uint_fast32_t>((rng() >> 32) | 1U); }

// OMPL logs through one process-wide handler; quieten it once (errors still show).
void quieten_ompl_logging() {
  static std::once_flag once;
  std::call_once(once, [] { ompl::msg::setLogLevel(ompl::msg::LOG_ERROR); });
}

// Valid cells: occupancy below the threshold, plus the "escape" cells that lead downhill out of an obstacle from
// the start or the goal (so that an item starting or ending on another item's blurred rim can still move).
class ValidityMap {
 public:
  ValidityMap(const OccupancyGrid& grid, int blocked, const Cell& start, const Cell& goal)
      : grid_(grid), blocked_(blocked), escape_(static_cast<std::size_t>(OccupancyGrid::kCols) * OccupancyGrid::kRows) {
    mark_escape(OccupancyGrid::clamp(start));
    mark_escape(OccupancyGrid::clamp(goal));
  }

  bool valid(const Cell& any) const {
    const Cell c = OccupancyGrid::clamp(any);
    return grid_.occupancy(c) < blocked_ || escape_[index(c)] != 0;
  }
  bool valid(const Vec2& p) const { return valid(OccupancyGrid::cell_of(p)); }

  // True when an 8-connected chain of valid cells links the two cells.
  bool connected(const Cell& from_any, const Cell& to_any) const {
    const Cell from = OccupancyGrid::clamp(from_any);
    const Cell to = OccupancyGrid::clamp(to_any);
    if (!valid(from) || !valid(to)) return false;
    std::vector<char> seen(escape_.size(), 0);
    std::deque<Cell> queue{from};
    seen[index(from)] = 1;
    while (!queue.empty()) {
      const Cell here = queue.front();
      queue.pop_front();
      if (here == to) return true;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const Cell next{here.col + dc, here.row + dr};
          if (!OccupancyGrid::contains(next) || seen[index(next)] != 0 || !valid(next)) continue;
          seen[index(next)] = 1;
          queue.push_back(next);
        }
      }
    }
    return false;
  }

 private:
  static std::size_t index(const Cell& c) {
    return static_cast<std::size_t>(c.row) * OccupancyGrid::kCols + static_cast<std::size_t>(c.col);
  }
  void mark_escape(const Cell& seed) {
    if (grid_.occupancy(seed) < blocked_ || escape_[index(seed)] != 0) return;
    std::deque<Cell> queue{seed};
    escape_[index(seed)] = 1;
    while (!queue.empty()) {
      const Cell here = queue.front();
      queue.pop_front();
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const Cell next{here.col + dc, here.row + dr};
          if (!OccupancyGrid::contains(next) || escape_[index(next)] != 0) continue;
          const int occupancy = grid_.occupancy(next);
          if (occupancy < blocked_ || occupancy > grid_.occupancy(here)) continue;
          escape_[index(next)] = 1;
          queue.push_back(next);
        }
      }
    }
  }

  const OccupancyGrid& grid_;
  int blocked_;
  std::vector<char> escape_;
};

// A uniform sampler whose generator is seeded by the request, not by OMPL's process-wide seed.
class SeededSampler final : public ob::RealVectorStateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::uint_fast32_t seed) : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

// A planner whose own generator (goal bias, bounces) is seeded by the request.
template <typename Planner>
class Seeded final : public Planner {
 public:
  Seeded(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed) : Planner(si) { this->rng_.setLocalSeed(seed); }
};

// PRM* without OMPL's solution-checking thread (whose timing decides when growth stops): grows the roadmap in
// fixed batches and checks for a solution between batches, so a seed gives one roadmap and one path.
class SingleThreadPRMstar final : public og::PRMstar {
 public:
  SingleThreadPRMstar(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed, std::uint64_t min_milestones)
      : og::PRMstar(si), min_milestones_(min_milestones) {
    rng_.setLocalSeed(seed);
  }

  ob::PlannerStatus solve(const ob::PlannerTerminationCondition& ptc) override {
    checkValidity();
    while (const ob::State* st = pis_.nextStart()) startM_.push_back(addMilestone(si_->cloneState(st)));
    if (startM_.empty()) return ob::PlannerStatus::INVALID_START;
    if (goalM_.empty()) {
      if (const ob::State* st = pis_.nextGoal(ptc)) goalM_.push_back(addMilestone(si_->cloneState(st)));
    }
    if (goalM_.empty()) return ob::PlannerStatus::INVALID_GOAL;
    if (!sampler_) sampler_ = si_->allocValidStateSampler();
    if (!simpleSampler_) simpleSampler_ = si_->allocStateSampler();
    bestCost_ = opt_->infiniteCost();

    ob::State* work = si_->allocState();
    ob::PathPtr solution;
    while (!ptc) {
      std::uint64_t checks = 0;
      growRoadmap(ob::PlannerTerminationCondition([&] { return ptc() || checks++ >= kPrmBatchChecks; }), work);
      ob::PathPtr candidate;
      maybeConstructSolution(startM_, goalM_, candidate);
      if (candidate) solution = candidate;
      if (solution && milestoneCount() >= min_milestones_) break;
    }
    si_->freeState(work);
    if (!solution) return ob::PlannerStatus::TIMEOUT;
    pdef_->addSolutionPath(solution, false, 0.0, getName());
    return ob::PlannerStatus::EXACT_SOLUTION;
  }

 private:
  std::uint64_t min_milestones_;
};

// OMPL's simplifier with its generator seeded by the request.
class SeededSimplifier final : public og::PathSimplifier {
 public:
  SeededSimplifier(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed) : og::PathSimplifier(si) {
    rng_.setLocalSeed(seed);
  }
};

}  // namespace

OmplPlanner::OmplPlanner(OmplAlgorithm algorithm, PlannerOptions options)
    : algorithm_(algorithm), options_(options) {
  if (!(options_.finger_speed_mps > 0.0) || !std::isfinite(options_.finger_speed_mps)) {
    throw InputError(fmt::format("finger speed {} m/s is not positive", options_.finger_speed_mps),
                     "finger_speed_mps", "> 0");
  }
  if (!(options_.pose_period_s > 0.0) || !std::isfinite(options_.pose_period_s)) {
    throw InputError(fmt::format("pose period {} s is not positive", options_.pose_period_s), "pose_period_s",
                     "> 0");
  }
  if (options_.blocked_occupancy < 1 || options_.blocked_occupancy > OccupancyGrid::kOccupied) {
    throw InputError(fmt::format("blocked occupancy {} out of range", options_.blocked_occupancy),
                     "blocked_occupancy", "1 … 100");
  }
}

std::string_view OmplPlanner::name() const {
  switch (algorithm_) {
    case OmplAlgorithm::RRTConnect: return "rrtconnect";
    case OmplAlgorithm::PRMstar: return "prmstar";
    case OmplAlgorithm::RRTstar: return "rrtstar";
    case OmplAlgorithm::BITstar: return "bitstar";
  }
  return "unknown";
}

PlanResult OmplPlanner::plan(const PlanRequest& request, Rng& rng) const {
  validate_request(request);
  Rng seeds(rng());  // the single draw from the caller's stream; every OMPL generator is seeded from it
  quieten_ompl_logging();
  const auto started = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  };
  const auto fail = [&](FailureReason reason, std::string message) {
    PlanResult result = detail::failure(reason, std::move(message));
    result.metrics.planning_time_s = elapsed();
    return result;
  };

  const OccupancyGrid grid = OccupancyGrid::build(request.obstacles, request.item);
  if (auto rejected = detail::check_goal(request, grid, options_)) {
    rejected->metrics.planning_time_s = elapsed();
    return *rejected;
  }
  const Cell start_cell = OccupancyGrid::cell_of(request.start);
  const Cell goal_cell = OccupancyGrid::cell_of(request.goal);
  const ValidityMap validity(grid, options_.blocked_occupancy, start_cell, goal_cell);
  if (!validity.connected(start_cell, goal_cell)) {
    return fail(FailureReason::NoPath,
                fmt::format("no chain of free cells (occupancy < {}) links start and goal",
                            options_.blocked_occupancy));
  }

  // State space: the screen, widened to hold a start that lies off it.
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0, std::min(0.0, request.start.x()));
  bounds.setHigh(0, std::max(OccupancyGrid::kWidthM, request.start.x()));
  bounds.setLow(1, std::min(-OccupancyGrid::kHeightM, request.start.y()));
  bounds.setHigh(1, std::max(0.0, request.start.y()));
  space->setBounds(bounds);
  const std::uint_fast32_t planner_seed = draw_seed(seeds);
  const std::uint_fast32_t simplifier_seed = draw_seed(seeds);
  auto sampler_seeds = std::make_shared<Rng>(seeds());
  space->setStateSamplerAllocator([sampler_seeds](const ob::StateSpace* s) -> ob::StateSamplerPtr {
    return std::make_shared<SeededSampler>(s, draw_seed(*sampler_seeds));
  });

  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([&validity, si_raw = si.get()](const ob::State* state) {
    if (!si_raw->satisfiesBounds(state)) return false;
    const auto* xy = state->as<ob::RealVectorStateSpace::StateType>();
    return validity.valid(Vec2(xy->values[0], xy->values[1]));
  });
  si->setStateValidityCheckingResolution(kMotionCheckCells * OccupancyGrid::kResolutionM /
                                         space->getMaximumExtent());
  si->setup();

  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<ob::RealVectorStateSpace> start(space);
  ob::ScopedState<ob::RealVectorStateSpace> goal(space);
  start[0] = request.start.x();
  start[1] = request.start.y();
  goal[0] = request.goal.x();
  goal[1] = request.goal.y();
  pdef->setStartAndGoalStates(start, goal);

  ob::PlannerPtr planner;
  switch (algorithm_) {
    case OmplAlgorithm::RRTConnect: planner = std::make_shared<Seeded<og::RRTConnect>>(si, planner_seed); break;
    case OmplAlgorithm::PRMstar:
      planner = std::make_shared<SingleThreadPRMstar>(si, planner_seed, request.iteration_budget);
      break;
    case OmplAlgorithm::RRTstar: planner = std::make_shared<Seeded<og::RRTstar>>(si, planner_seed); break;
    case OmplAlgorithm::BITstar: planner = std::make_shared<og::BITstar>(si); break;
  }
  if (algorithm_ == OmplAlgorithm::RRTstar || algorithm_ == OmplAlgorithm::BITstar) {
    pdef->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));
  }
  planner->setProblemDefinition(pdef);
  planner->setup();

  const bool iteration_limited = request.iteration_budget > 0 && (algorithm_ == OmplAlgorithm::RRTstar ||
                                                                  algorithm_ == OmplAlgorithm::BITstar);
  ob::IterationTerminationCondition iterations(
      static_cast<unsigned int>(std::min<std::uint64_t>(request.iteration_budget, 0xFFFFFFFFU)));
  const ob::PlannerTerminationCondition timed = ob::timedPlannerTerminationCondition(request.time_budget_s);
  const ob::PlannerStatus status =
      iteration_limited ? planner->solve(ob::plannerOrTerminationCondition(timed, iterations)) : planner->solve(timed);

  if (status != ob::PlannerStatus::EXACT_SOLUTION || !pdef->hasExactSolution()) {
    return fail(FailureReason::TimeBudgetExceeded,
                fmt::format("{} found no path within {} s ({})", name(), request.time_budget_s, status.asString()));
  }
  og::PathGeometric path = *pdef->getSolutionPath()->as<og::PathGeometric>();
  if (options_.simplify) {
    SeededSimplifier simplifier(si, simplifier_seed);
    simplifier.reduceVertices(path);
    simplifier.shortcutPath(path);
  }
  std::vector<Vec2> waypoints;
  waypoints.reserve(path.getStateCount());
  for (const ob::State* state : path.getStates()) {
    const auto* xy = state->as<ob::RealVectorStateSpace::StateType>();
    waypoints.emplace_back(xy->values[0], xy->values[1]);
  }
  PlanResult result;
  result.ok = true;
  result.path = retime_path(waypoints, options_.finger_speed_mps, options_.pose_period_s);
  result.metrics.planning_time_s = elapsed();

  ob::PlannerData data(si);
  planner->getPlannerData(data);
  result.metrics.expanded_nodes = data.numVertices();
  detail::measure_path(request, result);
  return result;
}

std::vector<TimedPose> retime_path(const std::vector<Vec2>& waypoints, double speed_mps, double period_s) {
  std::vector<TimedPose> poses;
  if (waypoints.empty()) return poses;
  const double step = speed_mps * period_s;
  const auto push = [&](const Vec2& p) {
    poses.push_back({static_cast<double>(poses.size()) * period_s, p});
  };
  push(waypoints.front());
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    const Vec2 from = waypoints[i - 1];
    const Vec2 delta = waypoints[i] - from;
    const double length = delta.norm();
    if (length <= 0.0) continue;
    const auto pieces = static_cast<int>(std::ceil(length / step - 1e-9));
    for (int k = 1; k <= pieces; ++k) push(k == pieces ? waypoints[i] : Vec2(from + delta * (k / double(pieces))));
  }
  return poses;
}

}  // namespace freeplay::planning
