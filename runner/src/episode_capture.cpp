#include "freeplay/runner/episode_capture.hpp"

#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <map>

#include "freeplay/core/error.hpp"

namespace freeplay::runner {

namespace {

constexpr double kTickToleranceS = 1e-9;

/// Watches the stage starts and captures the first tick at or after the moment, then raises the stop flag.
class MomentObserver final : public EpisodeObserver {
 public:
  MomentObserver(const EpisodeMoment& moment, const std::function<void(const EpisodeSnapshot&)>& capture,
                 std::atomic<bool>& stop)
      : moment_(moment), capture_(capture), stop_(stop) {}

  void observe(const EpisodeSnapshot& snapshot) override {
    if (captured_) return;
    for (const auto& event : snapshot.new_events) {
      const auto* stage = event.get<events::Stage>();
      if (stage && event.source == "protocol") stage_starts_[stage->stage] = event.t;
    }
    if (snapshot.stage != moment_.stage) return;
    const auto start = stage_starts_.find(moment_.stage);
    if (start == stage_starts_.end()) return;
    const double since = snapshot.t - start->second;
    if (since + kTickToleranceS < moment_.seconds) return;
    capture_(snapshot);
    captured_ = true;
    result_ = {snapshot.t, since, snapshot.freeplay_t};
    stop_.store(true);
  }

  bool captured() const { return captured_; }
  const CaptureResult& result() const { return result_; }

 private:
  const EpisodeMoment& moment_;
  const std::function<void(const EpisodeSnapshot&)>& capture_;
  std::atomic<bool>& stop_;
  std::map<std::string, double> stage_starts_;
  bool captured_ = false;
  CaptureResult result_;
};

/// How long a fixed-length stage lasts, or −1 for free play (it ends when the children quit or at the cap).
double fixed_stage_length(const scenario::Scenario& scenario, const std::string& stage) {
  if (stage == "greeting") return scenario.protocol.greeting_s;
  if (stage == "tutorial") return scenario.protocol.tutorial_s;
  if (stage == "debriefing") return scenario.protocol.debriefing_s;
  if (stage == "freeplay") return -1.0;
  throw InputError(fmt::format("unknown stage '{}'", stage), "--stage", "greeting, tutorial, freeplay, debriefing");
}

}  // namespace

CaptureResult capture_episode_moment(const scenario::Scenario& scenario, std::uint64_t seed, const SharedModels& models,
                                     const EpisodeMoment& moment,
                                     const std::function<void(const EpisodeSnapshot&)>& capture) {
  const double length = fixed_stage_length(scenario, moment.stage);
  if (!std::isfinite(moment.seconds) || moment.seconds < 0.0) {
    throw InputError(fmt::format("{} s is not a time in the episode", moment.seconds), "--time",
                     "seconds ≥ 0 since the stage started");
  }
  if (length >= 0.0 && (moment.seconds > length || length == 0.0)) {
    throw InputError(fmt::format("the {} lasts {:g} s in this scenario (protocol.{}_s)", moment.stage, length,
                                 moment.stage),
                     "--time", fmt::format("0 to {:g}", length));
  }
  if (length < 0.0 && moment.seconds > scenario.protocol.freeplay_cap_s) {
    throw InputError(fmt::format("free play stops at its cap of {:g} s in this scenario (protocol.freeplay_cap_s)",
                                 scenario.protocol.freeplay_cap_s),
                     "--time", fmt::format("0 to {:g}", scenario.protocol.freeplay_cap_s));
  }
  std::atomic<bool> stop{false};
  EpisodeObservers observers;
  observers.push_back(std::make_unique<MomentObserver>(moment, capture, stop));
  const auto* watcher = static_cast<const MomentObserver*>(observers.back().get());
  const auto result = run_episode({.scenario = scenario, .seed = seed, .models = models, .stop = stop, .id = "capture"},
                                  observed_by(observers));
  if (!watcher->captured()) {
    const auto ended_by = result.record.value("ended_by", std::string());
    throw InputError(fmt::format("the episode ended at {:.1f} s of free play ({})", result.duration_s,
                                 ended_by == "quit" ? "children quit" : "the free-play cap"),
                     "--time", fmt::format("0 to {:.1f} for seed {}", result.duration_s, seed));
  }
  return watcher->result();
}

}  // namespace freeplay::runner
