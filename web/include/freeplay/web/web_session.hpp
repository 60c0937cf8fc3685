#pragma once
// `freeplay serve SCENARIO --web [ADDR:]PORT`: one live episode in real time (or `rate`×) watched and driven from
// the experimenter's web page, without a ROS master. See docs/web.md.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/frame_sink.hpp"
#include "freeplay/runner/live_episode.hpp"
#include "freeplay/web/server.hpp"
#include "freeplay/web/wizard_source.hpp"

namespace freeplay::web {

/// Submits a command body as `POST /api/command` does (any thread) and answers as the API would.
using CommandSink = std::function<HttpReply(const std::string& body)>;

/// Settings of a web session.
struct WebSessionOptions {
  ServerOptions server;                        ///< where to listen, token, queue caps
  double rate = 1.0;                           ///< simulated seconds per wall second
  std::filesystem::path out;                   ///< session folder: events.jsonl, experiment.yaml
  RobotMode mode = RobotMode::Autonomous;      ///< who drives the robot at the start
  double sparc_timeout_s = 2.0;                ///< SPARC: a proposal executes after this many seconds unless vetoed
  bool linger = true;                          ///< after the episode, serve until `finalise` or the stop flag
  bool record = false;                         ///< the bag recorder writes from the start (else paused until the
                                               ///< page starts it; the scenario's `record: true` also starts it)
  runner::SignalSource* signals = nullptr;     ///< `sandtray/signals/*` from another source (a ROS graph), or null
  runner::EpisodeObserver* also_observe = nullptr;  ///< another observer of the episode (a ROS graph's publisher)
  runner::FrameSink* also_frames = nullptr;    ///< another sink of the scenario cameras' frames (the graph's topics)
  std::function<void(const std::string& url)> on_listening;  ///< told the page's URL once the server listens
  std::function<void(CommandSink)> on_commands;  ///< given the session's command entry (other sources: ROS), then
                                                 ///< an empty one when the session ends
};

/// What a web session produced besides the episode.
struct WebSessionReport {
  runner::EpisodeResult result;  ///< the episode
  ServerStats server;            ///< the server's counters
  std::size_t ticks = 0;         ///< state frames built
  runner::PacingTiming timing;   ///< how late the episode's ticks finished against the wall-clock schedule
};

/// Runs one live episode of `scenario` from root seed `seed` (runner::LiveEpisode, paced at `options.rate`) served on
/// the web; returns once it ended and (with `linger`) the session was finalised, or early (aborted) when `stop` is
/// set during the episode.
WebSessionReport serve_web(const scenario::Scenario& scenario, std::uint64_t seed, const WebSessionOptions& options,
                           const std::atomic<bool>& stop);

}  // namespace freeplay::web
