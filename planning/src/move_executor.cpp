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
constexpr double kCoarseLagStepS = 0.010;  // best-lag search: 10 ms grid, then 1 ms around the best
constexpr double kFineLagStepS = 0.001;

std::int64_t to_ns(double seconds) { return std::llround(seconds * kNanosecondsPerSecond); }

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

std::string item_names(const std::vector<Obstacle>& footprints) {
  std::string names;
  for (const auto& footprint : footprints) names += (names.empty() ? "" : ", ") + footprint.name;
  return names;
}

// Mean distance between the fingertip stream and the finger stream delayed by `lag` (the finger stream is linear
// between poses and held before the first and after the last); one forward walk, as the query times increase.
// `from_first[i]` is fingertip i's distance to the first pose, which every lag's held-at-the-start prefix adds;
// `from_first_sums[k]`, when the pose times never decrease, is the sum of its first k terms added in order — the
// same value the walk would reach over a prefix of k held poses. The walk gives up once the mean can no longer fall
// below `give_up_at` (the distances are non-negative and rounded sums of them never decrease) and then returns a
// value ≥ `give_up_at`.
double mean_error_at_lag(const std::vector<TimedPose>& finger, const std::vector<FollowReport>& fingertip,
                         const std::vector<double>& from_first, const std::vector<double>* from_first_sums,
                         double lag, double give_up_at) {
  const double n = static_cast<double>(finger.size());
  const double first_t = finger.front().t;
  double sum = 0.0;
  std::size_t i = 0;
  if (from_first_sums != nullptr) {
    const auto held = std::partition_point(finger.begin(), finger.end(),
                                           [&](const TimedPose& pose) { return pose.t - lag <= first_t; });
    i = static_cast<std::size_t>(held - finger.begin());
    sum = (*from_first_sums)[i];
  }
  std::size_t segment = 0;  // finger[segment].t <= query < finger[segment + 1].t
  for (; i < finger.size(); ++i) {
    const double t = finger[i].t - lag;
    if (t <= first_t) {
      sum += from_first[i];
      continue;
    }
    Vec2 p;
    if (t >= finger.back().t) {
      p = finger.back().position;
    } else {
      while (finger[segment + 1].t <= t) ++segment;
      const TimedPose& a = finger[segment];
      const TimedPose& b = finger[segment + 1];
      const double span = b.t - a.t;
      p = a.position + (span > 0.0 ? (t - a.t) / span : 1.0) * (b.position - a.position);
    }
    sum += (fingertip[i].fingertip_on_screen - p).norm();
    if ((i & 7U) == 7U && sum / n >= give_up_at) return sum / n;
  }
  return sum / n;
}

// The finger stream's segments as boxes, for the closest-point search of `lag_behind`: a point farther than d from a
// segment's box is farther than d from the segment, with `margin` (far above rounding) on each side.
struct SegmentBoxes {
  std::vector<Vec2> low, high;

  void build(const std::vector<TimedPose>& finger, double margin) {
    const std::size_t segments = finger.size() - 1;
    low.resize(segments);
    high.resize(segments);
    for (std::size_t j = 0; j < segments; ++j) {
      const Vec2& a = finger[j].position;
      const Vec2& b = finger[j + 1].position;
      low[j] = a.cwiseMin(b).array() - margin;
      high[j] = a.cwiseMax(b).array() + margin;
    }
  }

  // True when segment j is certainly farther than `distance` from `point`.
  bool beyond(std::size_t j, const Vec2& point, double distance) const {
    const double dx = std::max({0.0, low[j].x() - point.x(), point.x() - high[j].x()});
    const double dy = std::max({0.0, low[j].y() - point.y(), point.y() - high[j].y()});
    return dx * dx + dy * dy > distance * distance;
  }
};

// Distance from `point` to segment j of the finger stream and where along it (0…1) the closest point lies.
double distance_to_segment(const std::vector<TimedPose>& finger, std::size_t j, const Vec2& point, double& u) {
  const Vec2& a = finger[j].position;
  const Vec2 segment = finger[j + 1].position - a;
  const double length2 = segment.squaredNorm();
  u = length2 > 0.0 ? std::clamp((point - a).dot(segment) / length2, 0.0, 1.0) : 1.0;
  return (point - (a + u * segment)).norm();
}

// Time since the finger was closest to `point`, searching the stream up to pose `last`: the latest segment within
// 1e-12 m of the closest distance seen before it (later times win ties), i.e. the latest one within 1e-12 m of the
// minimum over all. The minimum is searched from segment `hint` first, so that the boxes of most others can be
// skipped; every distance compared is computed as a plain scan computes it.
double lag_behind(const std::vector<TimedPose>& finger, const SegmentBoxes& boxes, std::size_t last,
                  const Vec2& point, std::size_t hint) {
  constexpr double kTie = 1e-12;
  double u = 0.0;
  double closest = (point - finger.front().position).norm();
  const auto visit = [&](std::size_t j) {
    if (!boxes.beyond(j, point, closest)) closest = std::min(closest, distance_to_segment(finger, j, point, u));
  };
  if (hint < last) visit(hint);
  for (std::size_t j = last; j-- > 0;) {
    if (j != hint) visit(j);
  }
  const double within = closest + kTie;
  for (std::size_t j = last; j-- > 0;) {
    if (boxes.beyond(j, point, within)) continue;
    if (distance_to_segment(finger, j, point, u) <= within) {
      return finger[last].t - (finger[j].t + u * (finger[j + 1].t - finger[j].t));
    }
  }
  return finger[last].t - finger.front().t;
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

SyncMetrics sync_metrics(const std::vector<TimedPose>& finger, const std::vector<FollowReport>& fingertip,
                         double max_lag_s) {
  if (finger.size() != fingertip.size()) {
    throw InputError(fmt::format("{} finger poses but {} fingertip reports", finger.size(), fingertip.size()),
                     "fingertip", "one report per finger pose");
  }
  if (!(max_lag_s >= 0.0) || !std::isfinite(max_lag_s)) {
    throw InputError(fmt::format("lag search range {} s is not allowed", max_lag_s), "max_lag_s", ">= 0 s");
  }
  SyncMetrics metrics;
  metrics.samples = finger.size();
  if (finger.empty()) return metrics;
  double scale = 1.0;  // the coordinates' magnitude, for the boxes' margin
  for (std::size_t i = 0; i < finger.size(); ++i) {
    scale = std::max({scale, finger[i].position.cwiseAbs().maxCoeff(),
                      fingertip[i].fingertip_on_screen.cwiseAbs().maxCoeff()});
  }
  thread_local SegmentBoxes boxes;  // reused: no allocation once a long move has been measured
  boxes.build(finger, 1e-9 * scale);
  double error_sum = 0.0;
  double lag_sum = 0.0;
  std::size_t hint = 0;  // the closest segment of the previous fingertip: the next one is usually near it
  for (std::size_t i = 0; i < finger.size(); ++i) {
    if (!fingertip[i].reachable) ++metrics.unreachable;
    const double error = (fingertip[i].fingertip_on_screen - finger[i].position).norm();
    error_sum += error;
    metrics.max_error_m = std::max(metrics.max_error_m, error);
    const double lag = lag_behind(finger, boxes, i, fingertip[i].fingertip_on_screen, hint);
    lag_sum += lag;
    metrics.max_lag_s = std::max(metrics.max_lag_s, lag);
    const double closest_t = finger[i].t - lag;
    while (hint + 1 < i && finger[hint + 1].t <= closest_t) ++hint;
  }
  const auto n = static_cast<double>(finger.size());
  metrics.mean_error_m = error_sum / n;
  metrics.mean_lag_s = lag_sum / n;

  // Best delay: a 10 ms grid over [0, max_lag_s], then 1 ms steps around the best grid point (smaller lag on ties).
  // Once the latest pose delayed by a lag is no later than the first, every delayed position is the first pose, for
  // this lag and every larger one (floating-point subtraction is monotonic): they all give the same error, so only
  // the first of them in a scan can win.
  double latest = finger.front().t;
  for (const TimedPose& pose : finger) latest = std::max(latest, pose.t);
  thread_local std::vector<double> from_first;  // reused: no allocation once a long move has been measured
  thread_local std::vector<double> from_first_sums;
  from_first.resize(finger.size());
  from_first_sums.resize(finger.size() + 1);
  from_first_sums[0] = 0.0;
  for (std::size_t i = 0; i < finger.size(); ++i) {
    from_first[i] = (fingertip[i].fingertip_on_screen - finger.front().position).norm();
    from_first_sums[i + 1] = from_first_sums[i] + from_first[i];
  }
  const bool times_never_decrease =
      std::all_of(finger.begin(), finger.end(), [](const TimedPose& pose) { return std::isfinite(pose.t); }) &&
      std::is_sorted(finger.begin(), finger.end(), [](const TimedPose& a, const TimedPose& b) { return a.t < b.t; });
  const auto scan = [&](long first, long last, double step, double& best_lag, double& best_error) {
    for (long k = first; k <= last; ++k) {
      const double lag = static_cast<double>(k) * step;
      if (lag < 0.0 || lag > max_lag_s + 1e-12) continue;
      const double error = mean_error_at_lag(finger, fingertip, from_first,
                                             times_never_decrease ? &from_first_sums : nullptr, lag,
                                             best_error - 1e-15);
      if (error < best_error - 1e-15) {
        best_error = error;
        best_lag = lag;
      }
      if (latest - lag <= finger.front().t) break;
    }
  };
  double best_lag = 0.0;
  double best_error = std::numeric_limits<double>::infinity();
  scan(0, static_cast<long>(std::floor(max_lag_s / kCoarseLagStepS + 1e-9)), kCoarseLagStepS, best_lag, best_error);
  const long centre = std::lround(best_lag / kFineLagStepS);
  const long half_width = std::lround(kCoarseLagStepS / kFineLagStepS);
  scan(centre - half_width, centre + half_width, kFineLagStepS, best_lag, best_error);
  metrics.best_lag_s = best_lag;
  metrics.error_at_best_lag_m = best_error;
  return metrics;
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
    if (!finite(reach.shoulder_xy) || !std::isfinite(reach.reach) || !std::isfinite(reach.shoulder_height) ||
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
  if (!finite(goal.target)) {
    throw InputError(fmt::format("target ({}, {}) of '{}' is not finite", goal.target.x(), goal.target.y(),
                                 goal.item),
                     "target", "finite x, y in metres (sandtray frame)");
  }
  const std::optional<Vec2> centre = world.item_centre(goal.item);
  std::vector<Obstacle> footprints = world.footprints();
  if (!centre) throw InputError(fmt::format("unknown item '{}'", goal.item), "item", item_names(footprints));
  if (!finite(*centre)) {
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
  if (!finite(item_centre)) {
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
