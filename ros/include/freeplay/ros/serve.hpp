#pragma once
// `freeplay serve`: one live episode of a scenario on a ROS 1 graph, in real time (or `rate`× with `/clock`),
// exposing the interface of the real game and core nodes (see docs/hardware.md).

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/frame_sink.hpp"
#include "freeplay/runner/live_episode.hpp"

namespace freeplay::ros_live {

/// Settings of a served episode.
struct ServeOptions {
  double rate = 1.0;                ///< simulated seconds per wall second (≠ 1: `/clock` is published)
  bool external_robot = false;      ///< the robot's decisions come from the graph (`/poses`, move_sandbox_items)
  std::string node_name = "sandtray";  ///< ros::init name, as the real game
  double master_timeout_s = 10.0;   ///< how long to wait for the ROS master
};

/// The ROS graph side of a served episode: publishes every tick of the game and the Nao on the graph (the live
/// episode it is attached to paces the ticks), takes `sandtray/signals/*` from it and, with `external_robot`, the
/// robot's commands. `serve` runs a live episode with it; `freeplay serve --web --web-graph` attaches it to the web
/// session's live episode.
class GraphSide {
 public:
  /// Starts the ROS client (std::runtime_error when no master answers) and the nodes of `scenario`.
  GraphSide(const scenario::Scenario& scenario, std::uint64_t seed, const ServeOptions& options);
  ~GraphSide();
  GraphSide(const GraphSide&) = delete;
  GraphSide& operator=(const GraphSide&) = delete;

  /// The observer publishing each tick (attach it to the episode; valid while this lives).
  runner::EpisodeObserver& publisher();
  /// Where the scenario cameras' frames go: their drivers' topics (colour only).
  runner::FrameSink& cameras();
  /// The signals received from the graph since the last call.
  runner::SignalSource& signals();
  /// The inputs of the served episode of `scenario` (not copied) from `seed`: the graph's signals and, with
  /// `external_robot` in a child-robot scenario, the graph's robot: its `/poses`, its goals, gaze and pointing targets
  /// in front of the episode's one robot side, and the move driver's feedback and result back to the graph.
  runner::EpisodeInputs inputs(const scenario::Scenario& scenario, std::uint64_t seed);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Runs one live episode of `scenario` from root seed `seed` (runner::LiveEpisode, paced at `options.rate`); throws
/// std::runtime_error when no master answers; returns early (aborted) once `stop` is set. `timing` receives how late
/// its ticks finished (topics, cameras and all).
runner::EpisodeResult serve(const scenario::Scenario& scenario, std::uint64_t seed, const ServeOptions& options,
                            const std::atomic<bool>& stop, runner::PacingTiming* timing = nullptr);

}  // namespace freeplay::ros_live
