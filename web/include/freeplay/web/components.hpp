#pragma once
// The parts of a web session the experiment manager shows and switches (docs/web.md, "Components"): the page's
// `sandtray/signals/*` into the served episode and the session's bag recorder (paused and resumed from the page).
// The camera rig's switch is the live episode's (runner::ObserverSwitch); the robot side's is the WizardSource's.

#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <vector>

#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/runner/frame_sink.hpp"
#include "freeplay/runner/live_episode.hpp"
#include "freeplay/runner/signal_source.hpp"
#include "freeplay/web/session_log.hpp"

namespace freeplay::recording {
class BagRecorder;
}

namespace freeplay::web {

/// The signals the page sends (any thread), with those of another source (a live ROS graph) after them.
class WebSignals final : public runner::SignalSource {
 public:
  /// Also takes the signals of `also` (may be null) at every tick.
  explicit WebSignals(runner::SignalSource* also = nullptr) : also_(also) {}
  /// Queues a signal for the next tick (any thread).
  void push(sim::Signal signal);
  std::vector<sim::Signal> take() override;

 private:
  runner::SignalSource* also_;
  std::mutex mutex_;
  std::vector<sim::Signal> queue_;
};

/// The session's bag recorder behind a switch: while on, every tick goes to the recorder with the whole session
/// log's new events (the episode's and every wizard, supervision and experiment action); while paused, nothing is
/// written (the next tick written after a resume carries a `recorder`/`resumed` event). Also the recorder's camera
/// frame sink, gated the same way.
class RecorderSwitch final : public runner::EpisodeObserver, public runner::FrameSink {
 public:
  /// Records with `recorder` into its session folder under the episode id `id`; `on`: writing from the start.
  RecorderSwitch(std::unique_ptr<recording::BagRecorder> recorder, std::string id, bool on, SessionLog& log);
  ~RecorderSwitch() override;

  /// Asks for writing on or off from the next tick (any thread).
  void request(bool on) { gate_.request(on); }
  /// {state: recording|paused, folder, messages, paused_s: paused episode seconds so far} (any thread).
  nlohmann::json status() const;

  void begin(const runner::EpisodeInfo& info) override;
  void observe(const runner::EpisodeSnapshot& snapshot) override;
  void end(runner::EpisodeResult& result) override;
  void abort() override;
  void write(const stage::FramePack& frame) override;
  void set_gl_renderer(const std::string& renderer) override;

 private:
  std::unique_ptr<recording::BagRecorder> recorder_;
  std::string id_;
  SessionLog& log_;
  runner::ObserverSwitch gate_;  // the recorder while writing; its off time is the paused time
  std::size_t cursor_ = 0;       // the session log's events up to here are written or skipped
  std::vector<Event> events_;    // this tick's events (reused)
};

}  // namespace freeplay::web
