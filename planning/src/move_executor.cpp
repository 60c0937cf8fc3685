#include "freeplay/planning/move_executor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "freeplay/core/error.hpp"
#include "freeplay/planning/reach.hpp"

namespace freeplay::planning {

namespace {

constexpr double kNanosecondsPerSecond = 1e9;

std::int64_t to_ns(double seconds) { return std::llround(seconds * kNanosecondsPerSecond); }

std::string item_names(const std::vector<Obstacle>& footprints) {
  std::string names;
  for (const auto& footprint : footprints) names += (names.empty() ? "" : ", ") + footprint.name;
  return names;
}

}  // namespace

std::string_view move_status_name(MoveStatus status) {
  switch (status) {
    case MoveStatus::Idle: return "idle";
    case MoveStatus::Running: return "running";
    case MoveStatus::Succeeded: return "succeeded";
    case MoveStatus::Aborted: return "aborted";
    case MoveStatus::Preempted: return "preempted";
  }
  return "unknown";
}

std::string_view move_failure_name(MoveFailure failure) {
  switch (failure) {
    case MoveFailure::None: return "none";
    case MoveFailure::PlanningFailed: return "planning_failed";
    case MoveFailure::ItemHeldByChild: return "item_held_by_child";
    case MoveFailure::StolenByChild: return "stolen_by_child";
    case MoveFailure::Preempted: return "preempted";
  }
  return "unknown";
}

std::string MoveOutcome::reason() const {
  if (failure == MoveFailure::PlanningFailed) return std::string(failure_reason_name(plan.reason));
  return std::string(move_failure_name(failure));
}

std::vector<TimedPose> retime_path(const std::vector<TimedPose>& path, double speed_mps, double period_s) {
  if (!(speed_mps > 0.0) || !std::isfinite(speed_mps)) {
    throw InputError(fmt::format("finger speed {} m/s is not a positive number", speed_mps), "finger_speed_mps",
                     "> 0 m/s");
  }
  if (!(period_s > 0.0) || !std::isfinite(period_s)) {
    throw InputError(fmt::format("pose period {} s is not a positive number", period_s), "pose_period_s", "> 0 s");
  }
  std::vector<TimedPose> out;
  if (path.empty()) return out;
  const double spacing = speed_mps * period_s;
  out.push_back({0.0, path.front().position});
  double next_s = spacing;  // arc length of the next pose
  double walked = 0.0;      // arc length at the start of the current segment
  for (std::size_t i = 1; i < path.size(); ++i) {
    const Vec2& a = path[i - 1].position;
    const Vec2& b = path[i].position;
    const double length = (b - a).norm();
    while (length > 0.0 && next_s < walked + length - 1e-9) {
      const double u = (next_s - walked) / length;
      out.push_back({static_cast<double>(out.size()) * period_s, a + u * (b - a)});
      next_s += spacing;
    }
    walked += length;
  }
  if (path.size() > 1 && (path.back().position - out.back().position).norm() > 0.0) {
    out.push_back({static_cast<double>(out.size()) * period_s, path.back().position});
  }
  return out;
}

MoveExecutorConfig move_executor_config(const PlannerSettings& settings) {
  MoveExecutorConfig config;
  config.time_budget_s = settings.time_budget_s;
  config.finger_speed_mps = settings.finger_speed_mps;
  return config;
}

MoveExecutor::MoveExecutor(std::shared_ptr<const MotionPlanner> planner, MoveExecutorConfig config)
    : planner_(std::move(planner)), config_(std::move(config)) {
  if (!planner_) throw InputError("no planner given", "planner", planner_names_joined());
  const auto positive = [](double value, const char* key, const char* allowed) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw InputError(fmt::format("{} is not a positive number", value), key, allowed);
    }
  };
  positive(config_.time_budget_s, "time_budget_s", "> 0 s");
  positive(config_.pose_period_s, "pose_period_s", "> 0 s");
  if (config_.finger_speed_mps) positive(*config_.finger_speed_mps, "finger_speed_mps", "> 0 m/s");
  if (!(config_.max_lag_search_s >= 0.0) || !std::isfinite(config_.max_lag_search_s)) {
    throw InputError(fmt::format("{} is not allowed", config_.max_lag_search_s), "max_lag_search_s", ">= 0 s");
  }
  if (config_.arm_reach) {
    const ArmReach& reach = *config_.arm_reach;
    if (!reach.shoulder_xy.allFinite() || !std::isfinite(reach.reach) || !std::isfinite(reach.shoulder_height) ||
        reach.reach <= 0.0) {
      throw InputError("arm reach must be finite with a positive reach", "arm_reach",
                       "finite shoulder x, y, height (m) and reach > 0 m");
    }
  }
}

void MoveExecutor::start(const MoveGoal& goal, const MoveWorld& world, Rng& rng) {
  if (!world.item_centre || !world.footprints) {
    throw InputError("the world lacks its item_centre or footprints callback", "world",
                     "item_centre and footprints set");
  }
  if (!goal.target.allFinite()) {
    throw InputError(fmt::format("target ({}, {}) of '{}' is not finite", goal.target.x(), goal.target.y(),
                                 goal.item),
                     "target", "finite x, y in metres (sandtray frame)");
  }
  const std::optional<Vec2> centre = world.item_centre(goal.item);
  std::vector<Obstacle> footprints = world.footprints();
  if (!centre) throw InputError(fmt::format("unknown item '{}'", goal.item), "item", item_names(footprints));
  if (!centre->allFinite()) {
    throw InputError(fmt::format("centre of '{}' is not finite", goal.item), "item", "an item with a finite pose");
  }
  const bool held = world.held_by_child && world.held_by_child(goal.item);
  const bool refuse = held && config_.check_child_holding;

  // Everything that may throw happens before the executor changes (strong guarantee).
  PlanResult plan;
  if (!refuse) {
    PlanRequest request;
    request.item = goal.item;
    request.start = *centre;
    request.goal = goal.target;
    for (const auto& footprint : footprints) {
      if (footprint.name == goal.item) request.moved_footprint = footprint.footprint;
    }
    request.obstacles = std::move(footprints);
    request.time_budget_s = config_.time_budget_s;
    request.iteration_budget = config_.iteration_budget;
    plan = planner_->plan(request, rng);
  }
  std::vector<TimedPose> poses;
  if (plan.ok && !plan.path.empty()) {
    std::vector<TimedPose> path = plan.path;
    if (config_.exact_endpoints) {
      if (path.size() == 1) path.push_back({path.front().t + config_.pose_period_s, goal.target});
      path.front().position = *centre;
      path.back().position = goal.target;
    }
    poses = config_.finger_speed_mps ? retime_path(path, *config_.finger_speed_mps, config_.pose_period_s)
                                     : std::move(path);
  }

  if (current_.status == MoveStatus::Running) cancel();
  current_ = MoveOutcome{};
  current_.goal = goal;
  current_.status = MoveStatus::Running;
  if (config_.arm_reach) {
    const ArmReach& reach = *config_.arm_reach;
    current_.start_in_reach = in_reach_disc(*centre, reach.shoulder_xy, reach.reach, reach.shoulder_height);
    current_.target_in_reach = in_reach_disc(goal.target, reach.shoulder_xy, reach.reach, reach.shoulder_height);
  }
  elapsed_ns_ = 0;
  last_feedback_ = 0;
  fingertips_.clear();
  stamps_ns_.clear();
  child_was_holding_ = held;
  ++tally_.started;

  if (refuse) {
    ++tally_.refused_held;
    finish(MoveStatus::Aborted, MoveFailure::ItemHeldByChild,
           fmt::format("a child is holding '{}'", goal.item));
    return;
  }
  current_.plan = std::move(plan);
  if (!current_.plan.ok || poses.empty()) {
    ++tally_.planning_failed;
    finish(MoveStatus::Aborted, MoveFailure::PlanningFailed,
           current_.plan.message.empty() ? std::string("the planner returned no path") : current_.plan.message);
    return;
  }
  current_.poses = std::move(poses);
  stamps_ns_.reserve(current_.poses.size());
  for (const auto& pose : current_.poses) stamps_ns_.push_back(to_ns(pose.t));
  fingertips_.reserve(current_.poses.size());
}

void MoveExecutor::step(double dt, const MoveWorld& world, const MoveOutputs& outputs) {
  if (!std::isfinite(dt) || dt < 0.0) {
    throw InputError(fmt::format("time step {} s is not allowed", dt), "dt", ">= 0 s");
  }
  if (current_.status != MoveStatus::Running) return;
  if (!outputs.finger) throw InputError("no finger sink given", "outputs.finger", "a function receiving poses");

  // A child's finger took hold of the item since the last check while the robot drags it.
  if (world.held_by_child && current_.poses_sent > 0) {
    const bool held = world.held_by_child(current_.goal.item);
    if (held && !child_was_holding_ && !current_.stolen_by_child) {
      current_.stolen_by_child = true;
      ++tally_.stolen_by_child;
      if (config_.on_steal == StealResponse::Stop) {
        child_was_holding_ = held;
        finish(MoveStatus::Aborted, MoveFailure::StolenByChild,
               fmt::format("a child grabbed '{}' from the robot", current_.goal.item));
        return;
      }
    }
    child_was_holding_ = held;
  }

  const std::int64_t end_ns = elapsed_ns_ + to_ns(dt);
  while (current_.poses_sent < current_.poses.size() && stamps_ns_[current_.poses_sent] < end_ns) {
    deliver(current_.poses_sent, outputs);
  }
  elapsed_ns_ = end_ns;
  if (current_.poses_sent == current_.poses.size()) {
    ++tally_.succeeded;
    finish(MoveStatus::Succeeded, MoveFailure::None, {});
  }
}

void MoveExecutor::deliver(std::size_t index, const MoveOutputs& outputs) {
  const TimedPose& pose = current_.poses[index];
  outputs.finger(pose);
  const std::size_t n = current_.poses.size();
  if (index + 1 < n) {  // play_traj: feedback after each of poses[0..N−2], none after the last
    last_feedback_ = static_cast<int>(index * 100 / n);
    if (outputs.feedback) outputs.feedback(last_feedback_);
  }
  if (outputs.arm != nullptr) fingertips_.push_back(outputs.arm->follow(pose.position, pose.t));
  ++current_.poses_sent;
  current_.execution_duration_s = pose.t - current_.poses.front().t;
}

void MoveExecutor::cancel() {
  if (current_.status != MoveStatus::Running) return;
  ++tally_.preempted;
  finish(MoveStatus::Preempted, MoveFailure::Preempted, "cancelled");
}

void MoveExecutor::observe_release(const Vec2& item_centre) {
  if (!item_centre.allFinite()) {
    throw InputError("released item centre is not finite", "item_centre", "finite x, y in metres");
  }
  if (current_.status == MoveStatus::Idle || current_.status == MoveStatus::Running) return;
  if (current_.poses_sent == 0) return;
  current_.placement_error_m = (item_centre - current_.goal.target).norm();
}

std::optional<MoveOutcome> MoveExecutor::outcome() const {
  if (current_.status == MoveStatus::Idle || current_.status == MoveStatus::Running) return std::nullopt;
  return current_;
}

void MoveExecutor::finish(MoveStatus status, MoveFailure failure, std::string message) {
  current_.status = status;
  current_.failure = failure;
  current_.message = std::move(message);
  if (!fingertips_.empty() && fingertips_.size() == current_.poses_sent) {
    const std::vector<TimedPose> sent(current_.poses.begin(),
                                      current_.poses.begin() + static_cast<std::ptrdiff_t>(current_.poses_sent));
    current_.sync = sync_metrics(sent, fingertips_, config_.max_lag_search_s);
  }
}

}  // namespace freeplay::planning
