#pragma once
// One episode run live for a front (`freeplay serve`, `freeplay serve --web`, any later one): its ticks paced to the
// wall clock at a given speed, observers switched on and off while it runs, the episode paused, resumed and stopped
// from any thread, and how late its ticks finished against their schedule. The episode itself is run_episode's: a
// live episode gives the same event log as the same inputs run headless.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/episode_observer.hpp"

namespace freeplay::runner {

/// The wall clock a live episode is paced against: the process's steady clock, or a fake one in tests.
class LiveClock {
 public:
  using time_point = std::chrono::steady_clock::time_point;  ///< a moment on the wall clock
  using duration = std::chrono::steady_clock::duration;      ///< a span of wall time

  virtual ~LiveClock() = default;
  /// The current moment.
  virtual time_point now() = 0;
  /// Returns at `due` or later (at once when `due` has passed).
  virtual void sleep_until(time_point due) = 0;
  /// Waits a short while (the steady clock: 10 ms) while the episode is paused.
  virtual void wait_paused() = 0;

  /// The process's steady clock.
  static LiveClock& steady();
};

/// Real-time pacing at `speed` simulated seconds per wall second: the tick at simulated time t is due at
/// origin + (t − t₀) / speed, where the first tick (at t₀) set the origin; a late tick does not shift the next ones
/// (an absolute schedule), a pause shifts all the later ones.
class Pacer {
 public:
  /// Paces at `speed` (> 0) against `clock`.
  Pacer(double speed, LiveClock& clock);
  /// Sleeps until the tick at simulated time `t` is due; returns when it was due.
  LiveClock::time_point wait(double t);
  /// Moves the schedule `paused` later (the wall time an episode stood paused; nothing before the first tick).
  void shift(LiveClock::duration paused);

 private:
  double speed_;
  LiveClock& clock_;
  std::optional<LiveClock::time_point> origin_;  // when the first tick was due
  double t0_ = 0.0;                              // the first tick's simulated time
};

/// How late the ticks of a live episode finished (every observer done) against their schedule.
struct PacingTiming {
  std::size_t ticks = 0;     ///< ticks run
  double p50_late_ms = 0.0;  ///< median lateness
  double p99_late_ms = 0.0;  ///< 99th percentile lateness
  double max_late_ms = 0.0;  ///< largest lateness
};

/// The timing as fronts report it: {"ticks", "p50_late_ms", "p99_late_ms", "max_late_ms"}.
nlohmann::json timing_json(const PacingTiming& timing);

/// An observer behind a switch that is turned on and off while the episode runs (any thread; the change takes effect
/// at the next tick): while off it sees no ticks; `begin`, `end` and `abort` always pass. Counts the episode time
/// it was off.
class ObserverSwitch final : public EpisodeObserver {
 public:
  /// Told on the episode's thread at the tick a change takes effect: the episode time and whether it is now on.
  using OnChange = std::function<void(double t, bool on)>;

  /// Passes ticks to `inner` (not owned) while on; `on`: from the start.
  explicit ObserverSwitch(EpisodeObserver& inner, bool on = true, OnChange on_change = {});
  /// Asks for on or off from the next tick (any thread).
  void request(bool on) { requested_ = on; }
  /// True while ticks pass (any thread).
  bool on() const { return on_; }
  /// Applies the requested state at the tick at episode time `t` (observe does it first); returns whether it is on.
  bool apply(double t);
  /// Episode seconds it was off so far, up to the latest tick (any thread).
  double off_s() const;

  void begin(const EpisodeInfo& info) override { inner_.begin(info); }
  void observe(const EpisodeSnapshot& snapshot) override;
  void end(EpisodeResult& result) override { inner_.end(result); }
  void abort() override { inner_.abort(); }

 private:
  EpisodeObserver& inner_;
  OnChange on_change_;
  std::atomic<bool> requested_;
  std::atomic<bool> on_;
  mutable std::mutex mutex_;    // the off-time fields
  double off_since_ = -1.0;     // episode time the current off span began (< 0: on)
  double off_s_ = 0.0;          // episode time of the off spans that ended
  double last_t_ = 0.0;         // episode time of the latest tick
};

/// One episode run live: paced at a speed against a wall clock, its observers behind switches, paused, resumed and
/// stopped from any thread (`pause`, `resume`, `stop`), with the timing of its ticks. Attach observers before `run`.
class LiveEpisode {
 public:
  /// Paces at `speed` simulated seconds per wall second against `clock`; stops once `stop` (Ctrl-C) is set too.
  explicit LiveEpisode(double speed, const std::atomic<bool>& stop = kNeverStop,
                       LiveClock& clock = LiveClock::steady());
  ~LiveEpisode();
  LiveEpisode(const LiveEpisode&) = delete;
  LiveEpisode& operator=(const LiveEpisode&) = delete;

  /// Hands every tick to `observer` (not owned; it must outlive `run`), after those attached before, behind a
  /// switch that starts `on`; `on_change` hears of every change. The switch lives as long as this.
  ObserverSwitch& attach(EpisodeObserver& observer, bool on = true, ObserverSwitch::OnChange on_change = {});

  /// Holds the episode at its next tick until `resume` or a stop (any thread); the schedule then moves on by
  /// the wall time it stood, so the ticks after a pause are not due at once.
  void pause() { paused_ = true; }
  /// Lets a paused episode go on (any thread).
  void resume() { paused_ = false; }
  /// True between `pause` and `resume`.
  bool paused() const { return paused_; }
  /// Ends the episode at its next tick (any thread): `run` returns it aborted.
  void stop() { stop_ = true; }

  /// Runs the episode of `inputs` live on this thread (its stop flag is replaced by this one's) and returns it.
  EpisodeResult run(const EpisodeInputs& inputs);

  /// The ticks so far and how late they finished (any thread).
  PacingTiming timing() const;

 private:
  class Ticks;

  const std::atomic<bool>& outside_stop_;
  LiveClock& clock_;
  Pacer pacer_;
  std::vector<std::unique_ptr<ObserverSwitch>> switches_;
  std::unique_ptr<Ticks> ticks_;
  std::atomic<bool> paused_{false};
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;         // lateness_ms_
  std::vector<double> lateness_ms_;  // per tick: when every observer was done, against when it was due
};

}  // namespace freeplay::runner
