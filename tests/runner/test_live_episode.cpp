// The live episode on a fake wall clock: pacing, pause and resume, stop, observers switched while it runs, timing.
// No assertion reads the real wall clock.

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <vector>

#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/live_episode.hpp"

using namespace freeplay;
using namespace freeplay::runner;
using namespace freeplay::scenario;
using namespace std::chrono_literals;

namespace {

// A wall clock that only moves when slept on, waited on while paused, or told to.
struct FakeClock final : LiveClock {
  time_point at{};
  int paused_waits = 0;
  std::function<void()> on_paused_wait;  // called at every wait while paused

  time_point now() override { return at; }
  void sleep_until(time_point due) override { at = std::max(at, due); }
  void wait_paused() override {
    at += 100ms;
    ++paused_waits;
    if (on_paused_wait) on_paused_wait();
  }
};

// 1 s greeting, 0.5 s tutorial, 2 s free play (cap), 0.5 s debriefing: 40 ticks of 0.1 s.
Scenario short_scenario() {
  return scenario_from_document(parse_yaml(
      "name: live\ncondition: child-child\n"
      "protocol: {greeting_s: 1, tutorial_s: 0.5, freeplay_cap_s: 2, debriefing_s: 0.5}\n",
      "live.yaml"));
}

// Notes every tick (its simulated time and the fake wall time it was handed over at) and runs a hook.
struct Watcher final : EpisodeObserver {
  FakeClock* clock = nullptr;
  std::vector<double> t;
  std::vector<LiveClock::time_point> wall;
  int begun = 0, ended = 0, aborted = 0;
  std::function<void(std::size_t tick)> hook;

  void begin(const EpisodeInfo&) override { ++begun; }
  void observe(const EpisodeSnapshot& s) override {
    t.push_back(s.t);
    if (clock != nullptr) wall.push_back(clock->now());
    if (hook) hook(t.size() - 1);
  }
  void end(EpisodeResult&) override { ++ended; }
  void abort() override { ++aborted; }
};

double ms_between(LiveClock::time_point a, LiveClock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// A live episode on a fake clock with one watcher that notes the wall time of every tick.
struct WatchedLive {
  FakeClock clock;
  LiveEpisode live;
  Watcher watcher;
  explicit WatchedLive(double speed) : live(speed, kNeverStop, clock) {
    watcher.clock = &clock;
    live.attach(watcher);
  }

  // Every tick was handed over on its schedule at `ms_per_s` wall ms per simulated second, the ticks after
  // `held_at` `held_ms` later.
  void expect_on_schedule(double ms_per_s, std::size_t held_at = ~std::size_t{0}, double held_ms = 0.0) const {
    ASSERT_EQ(watcher.wall.size(), watcher.t.size());
    for (std::size_t i = 0; i < watcher.t.size(); ++i) {
      const double expected = (watcher.t[i] - watcher.t.front()) * ms_per_s + (i > held_at ? held_ms : 0.0);
      EXPECT_NEAR(ms_between(watcher.wall.front(), watcher.wall[i]), expected, 1e-3) << "tick " << i;
    }
  }
};

}  // namespace

TEST(Pacer, TicksAreDueOnAnAbsoluteScheduleAtItsSpeed) {
  FakeClock clock;
  clock.at += 5s;
  Pacer pacer(2.0, clock);
  pacer.shift(1s);  // before the first tick: nothing to move
  const auto origin = pacer.wait(10.0);
  EXPECT_EQ(origin, clock.at);
  EXPECT_EQ(pacer.wait(10.5), origin + 250ms);  // half a simulated second at 2×
  EXPECT_EQ(clock.at, origin + 250ms);
  clock.at += 600ms;  // a slow tick: the next ones keep their times and are not slept for
  EXPECT_EQ(pacer.wait(11.0), origin + 500ms);
  EXPECT_EQ(clock.at, origin + 850ms);
  pacer.shift(1s);  // a pause of one second moves every later tick
  EXPECT_EQ(pacer.wait(12.0), origin + 2000ms);
  EXPECT_EQ(clock.at, origin + 2000ms);
}

TEST(LiveEpisode, PacesEveryTickAndRunsTheSameEpisodeAsHeadless) {
  const auto s = short_scenario();
  WatchedLive run(4.0);
  const auto result = run.live.run({.scenario = s, .seed = 3, .id = "live"});
  ASSERT_FALSE(result.aborted);
  ASSERT_EQ(run.watcher.t.size(), 40u);
  EXPECT_EQ(run.watcher.begun, 1);
  EXPECT_EQ(run.watcher.ended, 1);
  run.expect_on_schedule(250.0);  // 0.1 simulated s at 4× is 25 ms of wall time
  const auto headless = run_episode({.scenario = s, .seed = 3});
  EXPECT_EQ(result.events.to_jsonl(), headless.events.to_jsonl());
}

TEST(LiveEpisode, TimingIsHowLateEachTickFinishedWithEveryObserver) {
  const auto s = short_scenario();
  FakeClock clock;
  LiveEpisode live(1.0, kNeverStop, clock);
  Watcher first;
  Watcher second;  // the tick's work: 5 ms, and 60 ms at tick 20, after the first observer
  second.hook = [&](std::size_t tick) { clock.at += tick == 20 ? 60ms : 5ms; };
  live.attach(first);
  live.attach(second);
  EXPECT_EQ(live.timing().ticks, 0u);
  live.run({.scenario = s, .seed = 3});
  const auto timing = live.timing();
  EXPECT_EQ(timing.ticks, 40u);
  EXPECT_DOUBLE_EQ(timing.p50_late_ms, 5.0);
  // freeplay::quantile (type 7): 0.99 × 39 = 38.61 lies between the 39th value (5) and the 40th (60).
  EXPECT_NEAR(timing.p99_late_ms, 5.0 + 0.61 * 55.0, 1e-9);
  EXPECT_DOUBLE_EQ(timing.max_late_ms, 60.0);
  const auto json = timing_json(timing);
  EXPECT_EQ(json["ticks"], 40);
  EXPECT_DOUBLE_EQ(json["max_late_ms"].get<double>(), 60.0);
  EXPECT_EQ(json.size(), 4u);
}

TEST(LiveEpisode, APauseHoldsTheEpisodeAndMovesTheScheduleOn) {
  const auto s = short_scenario();
  WatchedLive run(1.0);
  run.watcher.hook = [&](std::size_t tick) {
    if (tick == 10) run.live.pause();
  };
  run.clock.on_paused_wait = [&] {
    EXPECT_TRUE(run.live.paused());
    if (run.clock.paused_waits == 3) run.live.resume();
  };
  const auto result = run.live.run({.scenario = s, .seed = 3});
  EXPECT_FALSE(result.aborted);
  EXPECT_FALSE(run.live.paused());
  EXPECT_EQ(run.clock.paused_waits, 3);
  ASSERT_EQ(run.watcher.t.size(), 40u);
  run.expect_on_schedule(1e3, 10, 300.0);  // held before tick 11 for 3 × 100 ms
  EXPECT_DOUBLE_EQ(run.live.timing().max_late_ms, 0.0);
}

TEST(LiveEpisode, StopsFromOutsideFromItselfAndWhilePaused) {
  const auto s = short_scenario();
  {  // the front's stop flag (Ctrl-C), set during tick 5: the episode ends at the next tick
    FakeClock clock;
    std::atomic<bool> ctrl_c{false};
    LiveEpisode live(1.0, ctrl_c, clock);
    Watcher watcher;
    watcher.hook = [&](std::size_t tick) {
      if (tick == 5) ctrl_c = true;
    };
    live.attach(watcher);
    EXPECT_TRUE(live.run({.scenario = s, .seed = 3}).aborted);
    EXPECT_EQ(watcher.t.size(), 6u);
    EXPECT_EQ(watcher.aborted, 1);
    EXPECT_EQ(watcher.ended, 0);
  }
  {  // stop() from another part of the front
    FakeClock clock;
    LiveEpisode live(1.0, kNeverStop, clock);
    Watcher watcher;
    watcher.hook = [&](std::size_t tick) {
      if (tick == 2) live.stop();
    };
    live.attach(watcher);
    EXPECT_TRUE(live.run({.scenario = s, .seed = 3}).aborted);
    EXPECT_EQ(watcher.t.size(), 3u);
  }
  {  // a stop ends a pause
    FakeClock clock;
    LiveEpisode live(1.0, kNeverStop, clock);
    Watcher watcher;
    watcher.hook = [&](std::size_t tick) {
      if (tick == 1) live.pause();
    };
    clock.on_paused_wait = [&] {
      if (clock.paused_waits == 2) live.stop();
    };
    live.attach(watcher);
    EXPECT_TRUE(live.run({.scenario = s, .seed = 3}).aborted);
    EXPECT_EQ(clock.paused_waits, 2);
    EXPECT_EQ(watcher.aborted, 1);
  }
}

TEST(LiveEpisode, ObserversAreSwitchedOffAndOnWhileItRuns) {
  const auto s = short_scenario();
  FakeClock clock;
  LiveEpisode live(1.0, kNeverStop, clock);
  Watcher driver;
  Watcher camera;
  Watcher bag;
  std::vector<std::pair<double, bool>> changes;
  live.attach(driver);
  auto& camera_switch = live.attach(camera, true, [&](double t, bool on) { changes.emplace_back(t, on); });
  auto& bag_switch = live.attach(bag, false);  // off from the start
  driver.hook = [&](std::size_t tick) {
    if (tick == 5) camera_switch.request(false);  // takes effect at this tick: the camera comes after the driver
    if (tick == 15) camera_switch.request(true);
    if (tick == 30) bag_switch.request(true);
  };
  EXPECT_TRUE(camera_switch.on());
  live.run({.scenario = s, .seed = 3});
  EXPECT_EQ(driver.t.size(), 40u);
  ASSERT_EQ(camera.t.size(), 30u);  // ticks 0–4 and 15–39
  EXPECT_DOUBLE_EQ(camera.t[5], driver.t[15]);
  ASSERT_EQ(changes.size(), 2u);
  EXPECT_DOUBLE_EQ(changes[0].first, driver.t[5]);
  EXPECT_FALSE(changes[0].second);
  EXPECT_DOUBLE_EQ(changes[1].first, driver.t[15]);
  EXPECT_TRUE(changes[1].second);
  EXPECT_NEAR(camera_switch.off_s(), 1.0, 1e-9);
  EXPECT_EQ(bag.t.size(), 10u);  // ticks 30–39
  EXPECT_NEAR(bag_switch.off_s(), driver.t[30] - driver.t[0], 1e-9);
  EXPECT_TRUE(bag_switch.on());
  for (const auto* w : {&driver, &camera, &bag}) {  // begin and end pass whatever the switch
    EXPECT_EQ(w->begun, 1);
    EXPECT_EQ(w->ended, 1);
  }
}
