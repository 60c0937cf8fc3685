#pragma once
// `freeplay serve`: one live episode of a scenario on a ROS 1 graph, in real time (or `rate`× with `/clock`),
// exposing the interface of the real game and core nodes (see docs/hardware.md).

#include <atomic>
#include <cstdint>
#include <string>

#include "freeplay/runner/episode.hpp"

namespace freeplay::ros_live {

/// Settings of a served episode.
struct ServeOptions {
  double rate = 1.0;                ///< simulated seconds per wall second (≠ 1: `/clock` is published)
  bool external_robot = false;      ///< the robot's decisions come from the graph (`/poses`, move_sandbox_items)
  std::string node_name = "sandtray";  ///< ros::init name, as the real game
  double master_timeout_s = 10.0;   ///< how long to wait for the ROS master
};

/// Publication timing of a served episode: how late each 10 Hz tick's `/tf` went out against its schedule.
struct ServeTiming {
  std::size_t ticks = 0;     ///< ticks published
  double p50_late_ms = 0.0;  ///< median lateness
  double p99_late_ms = 0.0;  ///< 99th percentile lateness
  double max_late_ms = 0.0;  ///< largest lateness
};

/// Runs one live episode of `scenario` from root seed `seed`; throws std::runtime_error when no master answers;
/// returns early (aborted) once `stop` is set. `timing` receives the publication timing.
runner::EpisodeResult serve(const runner::Scenario& scenario, std::uint64_t seed, const ServeOptions& options,
                            const std::atomic<bool>& stop, ServeTiming* timing = nullptr);

}  // namespace freeplay::ros_live
