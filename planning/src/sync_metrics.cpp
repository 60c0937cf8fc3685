// Synchronisation metrics of a followed finger stream (MoveExecutor's `sync`): the closest-point lags and the best
// delay. Both searches skip work that cannot change their answers, and every number they compare is computed as the
// plain scans compute it; tests/planning/test_sync_metrics.cpp holds them to those scans bit for bit.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "freeplay/core/error.hpp"
#include "freeplay/planning/move_executor.hpp"

namespace freeplay::planning {
namespace {

constexpr double kCoarseLagStepS = 0.010;  // best-lag search: 10 ms grid, then 1 ms around the best
constexpr double kFineLagStepS = 0.001;

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

// What every lag of the best-delay search reuses, worked out once per move.
struct LagScan {
  // from_first[i]: fingertip i's distance to the first pose, which a lag's held-at-the-start prefix adds.
  std::vector<double> from_first;
  // held_sums[k]: the first k from_first terms added in order, the value the walk reaches over k held poses (used
  // only when the pose times never decrease, so that the held poses are a prefix).
  std::vector<double> held_sums;
  bool times_never_decrease = false;
  // rest_bounds[i]: a lower bound of what poses i, i + 1, … add to any lag's sum (0 where none is known): the
  // distance from each fingertip to the box of the poses its delayed finger can lie between.
  std::vector<double> rest_bounds;

  void build(const std::vector<TimedPose>& finger, const std::vector<FollowReport>& fingertip, double max_lag,
             double margin);
};

void LagScan::build(const std::vector<TimedPose>& finger, const std::vector<FollowReport>& fingertip,
                    double max_lag, double margin) {
  const std::size_t n = finger.size();
  from_first.resize(n);
  held_sums.resize(n + 1);
  held_sums[0] = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    from_first[i] = (fingertip[i].fingertip_on_screen - finger.front().position).norm();
    held_sums[i + 1] = held_sums[i] + from_first[i];
  }
  times_never_decrease =
      std::all_of(finger.begin(), finger.end(), [](const TimedPose& pose) { return std::isfinite(pose.t); }) &&
      std::is_sorted(finger.begin(), finger.end(), [](const TimedPose& a, const TimedPose& b) { return a.t < b.t; });
  rest_bounds.assign(n + 1, 0.0);
  if (!times_never_decrease) return;
  // Delayed by a lag in [0, max_lag], pose i's finger is the first pose, the last, or a point between two poses
  // whose times bracket t_i − lag: all within the poses from the last at or before t_i − max_lag to the first
  // after t_i.
  std::size_t from = 0;
  std::size_t to = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = finger[i].t;
    const double earliest = t - max_lag - 1e-9 * (1.0 + std::abs(t) + max_lag);
    while (from + 1 < n && finger[from + 1].t <= earliest) ++from;
    while (to + 1 < n && finger[to].t <= t) ++to;
    Vec2 low = finger[from].position;
    Vec2 high = low;
    for (std::size_t j = from + 1; j <= to; ++j) {
      low = low.cwiseMin(finger[j].position);
      high = high.cwiseMax(finger[j].position);
    }
    const Vec2& tip = fingertip[i].fingertip_on_screen;
    const double dx = std::max({0.0, low.x() - margin - tip.x(), tip.x() - high.x() - margin});
    const double dy = std::max({0.0, low.y() - margin - tip.y(), tip.y() - high.y() - margin});
    rest_bounds[i] = std::sqrt(dx * dx + dy * dy);
  }
  for (std::size_t i = n; i-- > 0;) rest_bounds[i] += rest_bounds[i + 1];
}

// Mean distance between the fingertip stream and the finger stream delayed by `lag` (the finger stream is linear
// between poses and held before the first and after the last); one forward walk, as the query times increase.
// The walk gives up, returning `give_up_at`, once the mean can no longer fall below `give_up_at`: the sum so far
// plus the bound of the rest, less a margin far above the rounding of up to a million additions, already reaches
// it (the distances are non-negative, and rounded sums of non-negative numbers never fall below their first
// terms' sum by more than that rounding).
double mean_error_at_lag(const std::vector<TimedPose>& finger, const std::vector<FollowReport>& fingertip,
                         const LagScan& scan, double lag, double give_up_at) {
  constexpr double kRoundingMargin = 1e-9;
  const std::size_t count = finger.size();
  const double n = static_cast<double>(count);
  const bool may_give_up = count <= 1'000'000;
  const double give_up_sum = give_up_at * n * (1.0 + kRoundingMargin);
  const double first_t = finger.front().t;
  double sum = 0.0;
  std::size_t i = 0;
  if (scan.times_never_decrease) {
    const auto held = std::partition_point(finger.begin(), finger.end(),
                                           [&](const TimedPose& pose) { return pose.t - lag <= first_t; });
    i = static_cast<std::size_t>(held - finger.begin());
    sum = scan.held_sums[i];
  }
  std::size_t segment = 0;  // finger[segment].t <= query < finger[segment + 1].t
  for (; i < count; ++i) {
    const double t = finger[i].t - lag;
    if (t <= first_t) {
      sum += scan.from_first[i];
      continue;
    }
    sum += (fingertip[i].fingertip_on_screen - finger_position_after_start(finger, t, segment)).norm();
    if (may_give_up && (sum + scan.rest_bounds[i + 1]) * (1.0 - kRoundingMargin) >= give_up_sum) return give_up_at;
  }
  return sum / n;
}

}  // namespace

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
  thread_local LagScan lag_scan;  // reused: no allocation once a long move has been measured
  lag_scan.build(finger, fingertip, max_lag_s, 1e-9 * scale);
  const auto scan = [&](long first, long last, double step, double& best_lag, double& best_error) {
    for (long k = first; k <= last; ++k) {
      const double lag = static_cast<double>(k) * step;
      if (lag < 0.0 || lag > max_lag_s + 1e-12) continue;
      const double error = mean_error_at_lag(finger, fingertip, lag_scan, lag, best_error - 1e-15);
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

}  // namespace freeplay::planning
