#include "freeplay/runner/live_episode.hpp"

#include <algorithm>
#include <thread>

#include "freeplay/core/statistics.hpp"

namespace freeplay::runner {

namespace {

constexpr auto kPausedPoll = std::chrono::milliseconds(10);

/// The process's steady clock.
class SteadyClock final : public LiveClock {
 public:
  time_point now() override { return std::chrono::steady_clock::now(); }
  void sleep_until(time_point due) override { std::this_thread::sleep_until(due); }
  void wait_paused() override { std::this_thread::sleep_for(kPausedPoll); }
};

}  // namespace

LiveClock& LiveClock::steady() {
  static SteadyClock clock;
  return clock;
}

Pacer::Pacer(double speed, LiveClock& clock) : speed_(speed), clock_(clock) {}

LiveClock::time_point Pacer::wait(double t) {
  if (!origin_) {
    origin_ = clock_.now();
    t0_ = t;
  }
  const auto due = *origin_ + std::chrono::duration_cast<LiveClock::duration>(
                                  std::chrono::duration<double>((t - t0_) / speed_));
  clock_.sleep_until(due);
  return due;
}

void Pacer::shift(LiveClock::duration paused) {
  if (origin_) *origin_ += paused;
}

nlohmann::json timing_json(const PacingTiming& timing) {
  return {{"ticks", timing.ticks},
          {"p50_late_ms", timing.p50_late_ms},
          {"p99_late_ms", timing.p99_late_ms},
          {"max_late_ms", timing.max_late_ms}};
}

ObserverSwitch::ObserverSwitch(EpisodeObserver& inner, bool on, OnChange on_change)
    : inner_(inner), on_change_(std::move(on_change)), requested_(on), on_(on) {}

bool ObserverSwitch::apply(double t) {
  const bool want = requested_;
  {
    std::lock_guard lock(mutex_);
    last_t_ = t;
    if (want != on_) {
      if (want && off_since_ >= 0.0) off_s_ += t - off_since_;
      off_since_ = want ? -1.0 : t;
    } else if (!want && off_since_ < 0.0) {
      off_since_ = t;  // off from the start
    }
  }
  if (want != on_) {
    on_ = want;
    if (on_change_) on_change_(t, want);
  }
  return want;
}

double ObserverSwitch::off_s() const {
  std::lock_guard lock(mutex_);
  return off_s_ + (off_since_ >= 0.0 ? last_t_ - off_since_ : 0.0);
}

void ObserverSwitch::observe(const EpisodeSnapshot& snapshot) {
  if (apply(snapshot.t)) inner_.observe(snapshot);
}

/// The one observer the episode sees: holds a paused episode, paces the tick, hands it to every switch in order and
/// notes how late the tick finished.
class LiveEpisode::Ticks final : public EpisodeObserver {
 public:
  explicit Ticks(LiveEpisode& live) : live_(live) {}

  void begin(const EpisodeInfo& info) override {
    for (auto& s : live_.switches_) s->begin(info);
  }

  void observe(const EpisodeSnapshot& snapshot) override {
    hold_while_paused();
    const auto due = live_.pacer_.wait(snapshot.t);
    for (auto& s : live_.switches_) s->observe(snapshot);
    const double late_ms = std::chrono::duration<double, std::milli>(live_.clock_.now() - due).count();
    {
      std::lock_guard lock(live_.mutex_);
      live_.lateness_ms_.push_back(late_ms);
    }
    stopping();  // a stop during this tick ends the episode before the next
  }

  void end(EpisodeResult& result) override {
    for (auto& s : live_.switches_) s->end(result);
  }

  void abort() override {
    for (auto& s : live_.switches_) s->abort();
  }

 private:
  // A stop from outside ends the episode at its next tick; a pause holds this one until resumed or stopped.
  bool stopping() {
    if (live_.outside_stop_.load()) live_.stop_ = true;
    return live_.stop_;
  }

  void hold_while_paused() {
    if (stopping() || !live_.paused_) return;
    const auto since = live_.clock_.now();
    while (live_.paused_ && !stopping()) live_.clock_.wait_paused();
    live_.pacer_.shift(live_.clock_.now() - since);
  }

  LiveEpisode& live_;
};

LiveEpisode::LiveEpisode(double speed, const std::atomic<bool>& stop, LiveClock& clock)
    : outside_stop_(stop), clock_(clock), pacer_(speed, clock), ticks_(std::make_unique<Ticks>(*this)) {}

LiveEpisode::~LiveEpisode() = default;

ObserverSwitch& LiveEpisode::attach(EpisodeObserver& observer, bool on, ObserverSwitch::OnChange on_change) {
  switches_.push_back(std::make_unique<ObserverSwitch>(observer, on, std::move(on_change)));
  return *switches_.back();
}

EpisodeResult LiveEpisode::run(const EpisodeInputs& inputs) {
  if (outside_stop_.load()) stop_ = true;
  return run_episode(inputs.stopped_by(stop_), {.observers = {ticks_.get()}});
}

PacingTiming LiveEpisode::timing() const {
  std::vector<double> late_ms;
  {
    std::lock_guard lock(mutex_);
    late_ms = lateness_ms_;
  }
  PacingTiming out;
  out.ticks = late_ms.size();
  if (late_ms.empty()) return out;
  out.p50_late_ms = median(late_ms);
  out.p99_late_ms = quantile(late_ms, 0.99);
  out.max_late_ms = *std::max_element(late_ms.begin(), late_ms.end());
  return out;
}

}  // namespace freeplay::runner
