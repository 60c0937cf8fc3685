// sync_metrics skips work (segment boxes, summed held prefixes, lags that can no longer win); these tests hold it to
// the plain scans it replaced, bit for bit, on streams shaped like the robot's and on awkward ones.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "freeplay/core/rng.hpp"
#include "freeplay/planning/move_executor.hpp"

namespace freeplay::planning {
namespace {

// --- the plain scans: every segment for every fingertip, every pose for every lag ---------------------------------
double plain_mean_error_at_lag(const std::vector<TimedPose>& finger, const std::vector<FollowReport>& fingertip,
                               double lag) {
  double sum = 0.0;
  std::size_t segment = 0;
  for (std::size_t i = 0; i < finger.size(); ++i) {
    const double t = finger[i].t - lag;
    if (t <= finger.front().t) {
      sum += (fingertip[i].fingertip_on_screen - finger.front().position).norm();
      continue;
    }
    sum += (fingertip[i].fingertip_on_screen - finger_position_after_start(finger, t, segment)).norm();
  }
  return sum / static_cast<double>(finger.size());
}

double plain_lag_behind(const std::vector<TimedPose>& finger, std::size_t last, const Vec2& point) {
  double best_distance = (point - finger.front().position).norm();
  double best_time = finger.front().t;
  for (std::size_t j = 0; j < last; ++j) {
    const Vec2& a = finger[j].position;
    const Vec2 segment = finger[j + 1].position - a;
    const double length2 = segment.squaredNorm();
    const double u = length2 > 0.0 ? std::clamp((point - a).dot(segment) / length2, 0.0, 1.0) : 1.0;
    const double distance = (point - (a + u * segment)).norm();
    if (distance <= best_distance + 1e-12) {
      best_distance = std::min(best_distance, distance);
      best_time = finger[j].t + u * (finger[j + 1].t - finger[j].t);
    }
  }
  return finger[last].t - best_time;
}

SyncMetrics plain_sync_metrics(const std::vector<TimedPose>& finger, const std::vector<FollowReport>& fingertip,
                               double max_lag_s) {
  SyncMetrics metrics;
  metrics.samples = finger.size();
  double error_sum = 0.0;
  double lag_sum = 0.0;
  for (std::size_t i = 0; i < finger.size(); ++i) {
    if (!fingertip[i].reachable) ++metrics.unreachable;
    const double error = (fingertip[i].fingertip_on_screen - finger[i].position).norm();
    error_sum += error;
    metrics.max_error_m = std::max(metrics.max_error_m, error);
    const double lag = plain_lag_behind(finger, i, fingertip[i].fingertip_on_screen);
    lag_sum += lag;
    metrics.max_lag_s = std::max(metrics.max_lag_s, lag);
  }
  const auto n = static_cast<double>(finger.size());
  metrics.mean_error_m = error_sum / n;
  metrics.mean_lag_s = lag_sum / n;
  double best_lag = 0.0;
  double best_error = std::numeric_limits<double>::infinity();
  const auto scan = [&](long first, long last, double step) {
    for (long k = first; k <= last; ++k) {
      const double lag = static_cast<double>(k) * step;
      if (lag < 0.0 || lag > max_lag_s + 1e-12) continue;
      const double error = plain_mean_error_at_lag(finger, fingertip, lag);
      if (error < best_error - 1e-15) {
        best_error = error;
        best_lag = lag;
      }
    }
  };
  scan(0, static_cast<long>(std::floor(max_lag_s / 0.010 + 1e-9)), 0.010);
  scan(std::lround(best_lag / 0.001) - 10, std::lround(best_lag / 0.001) + 10, 0.001);
  metrics.best_lag_s = best_lag;
  metrics.error_at_best_lag_m = best_error;
  return metrics;
}

void expect_identical(const SyncMetrics& fast, const SyncMetrics& plain, int trial) {
  EXPECT_EQ(fast.samples, plain.samples) << trial;
  EXPECT_EQ(fast.unreachable, plain.unreachable) << trial;
  // Bit for bit: EXPECT_EQ on doubles compares exactly.
  EXPECT_EQ(fast.mean_error_m, plain.mean_error_m) << trial;
  EXPECT_EQ(fast.max_error_m, plain.max_error_m) << trial;
  EXPECT_EQ(fast.mean_lag_s, plain.mean_lag_s) << trial;
  EXPECT_EQ(fast.max_lag_s, plain.max_lag_s) << trial;
  EXPECT_EQ(fast.best_lag_s, plain.best_lag_s) << trial;
  EXPECT_EQ(fast.error_at_best_lag_m, plain.error_at_best_lag_m) << trial;
}

// A finger stream at 10 Hz along a wandering path, followed by a fingertip some ticks behind with jitter, as the
// Nao's arm follows the planner's poses; in some streams the arm cannot reach part of the path and its fingertip
// stops short, at the edge of its reach, far from the finger.
void robot_like(Rng& rng, std::vector<TimedPose>& finger, std::vector<FollowReport>& tips) {
  const auto n = static_cast<std::size_t>(rng.uniform_int(1, 120));
  const auto behind = static_cast<std::size_t>(rng.uniform_int(0, 8));
  const double jitter = rng.uniform() < 0.3 ? 0.0 : rng.uniform(0.0, 0.01);
  Vec2 p(rng.uniform(0.0, 0.6), -rng.uniform(0.0, 0.335));
  double heading = rng.uniform(-3.14, 3.14);
  finger.clear();
  tips.clear();
  for (std::size_t i = 0; i < n; ++i) {
    finger.push_back({0.1 * static_cast<double>(i), p});
    heading += rng.uniform(-0.4, 0.4);
    const double step = rng.uniform() < 0.1 ? 0.0 : rng.uniform(0.0, 0.02);  // pauses give repeated poses
    p += step * Vec2(std::cos(heading), std::sin(heading));
  }
  const bool stretched = rng.uniform() < 0.4;
  const Vec2 shoulder(rng.uniform(0.0, 0.6), 0.1);
  const double reach = rng.uniform(0.05, 0.3);
  for (std::size_t i = 0; i < n; ++i) {
    Vec2 followed = finger[i >= behind ? i - behind : 0].position;
    if (stretched && (followed - shoulder).norm() > reach) followed = shoulder + reach * (followed - shoulder).normalized();
    tips.push_back({followed + Vec2(rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter)), rng.uniform() > 0.1});
  }
}

// Compares sync_metrics with the plain scans on `trials` streams written by `make`, which returns the lag range.
template <typename Make>
void expect_matches_plain_scans(std::uint64_t seed, int trials, Make make) {
  Rng rng(seed);
  std::vector<TimedPose> finger;
  std::vector<FollowReport> tips;
  for (int trial = 0; trial < trials; ++trial) {
    const double max_lag = make(rng, trial, finger, tips);
    expect_identical(sync_metrics(finger, tips, max_lag), plain_sync_metrics(finger, tips, max_lag), trial);
  }
}

TEST(SyncMetrics, MatchesThePlainScansBitForBitOnRobotLikeStreams) {
  expect_matches_plain_scans(20261125, 600, [](Rng& rng, int trial, auto& finger, auto& tips) {
    robot_like(rng, finger, tips);
    return trial % 4 == 0 ? rng.uniform(0.0, 3.0) : 2.0;
  });
}

TEST(SyncMetrics, MatchesThePlainScansOnTiesRepeatsAndUnorderedTimes) {
  expect_matches_plain_scans(7, 300, [](Rng& rng, int trial, auto& finger, auto& tips) {
    const auto n = static_cast<std::size_t>(rng.uniform_int(1, 40));
    finger.clear();
    tips.clear();
    double t = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      // Points on a coarse lattice: many segments at exactly the same distance, back-and-forth paths, repeats.
      const Vec2 p(0.01 * rng.uniform_int(0, 4), -0.01 * rng.uniform_int(0, 4));
      // Times that stall, and in one trial of three go backwards.
      t += trial % 3 == 0 ? rng.uniform(-0.1, 0.2) : (rng.uniform() < 0.2 ? 0.0 : 0.1);
      finger.push_back({t, p});
      tips.push_back({Vec2(0.01 * rng.uniform_int(0, 4), -0.01 * rng.uniform_int(0, 4)), true});
    }
    return 2.0;
  });
}

TEST(SyncMetrics, MatchesThePlainScansFarFromTheOrigin) {
  // The boxes' margin scales with the coordinates, so rounding at large magnitudes cannot skip the closest segment.
  expect_matches_plain_scans(99, 100, [](Rng& rng, int, auto& finger, auto& tips) {
    robot_like(rng, finger, tips);
    const Vec2 offset(1e6, -1e6);
    for (auto& pose : finger) pose.position += offset;
    for (auto& tip : tips) tip.fingertip_on_screen += offset;
    return 2.0;
  });
}

}  // namespace
}  // namespace freeplay::planning
