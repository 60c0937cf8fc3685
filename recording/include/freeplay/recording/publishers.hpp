#pragma once
// When the real nodes' messages reach the bag: every publisher runs on its own timer, so its messages carry its own
// phase after the game's tick plus a little jitter (rosbag then reports a frequency for /tf, which many publishers
// share). Deterministic for a seed: the phase and jitter of a publisher come from the episode seed and its name.

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "freeplay/core/rng.hpp"

namespace freeplay::recording {

/// Length of the game's tick (s): the simulation's state changes every 0.1 s.
inline constexpr double kPublishTickS = 0.1;
/// Length of one frame of PInSoRo's 30 Hz videos, CSV rows and pose frames (s).
inline constexpr double kVideoFrameS = 1.0 / 30.0;
/// The 30 Hz frames of one game tick: the three frames since the previous tick show that tick's state.
inline constexpr int kVideoFramesPerTick = 3;
/// The latest a publisher sends the state of a tick after it (s): phase + jitter stay below half a tick.
inline constexpr double kMaxPublishDelayS = 0.042;

/// One publisher's clock: a fixed phase in [2, 40] ms after each tick (or frame) and ±2 ms of jitter per message.
class PublisherClock {
 public:
  /// The clock of publisher `name` in the episode with root `seed`; `max_phase_s` bounds the phase (cameras, whose
  /// frames come faster than the tick, use a smaller one).
  PublisherClock(std::uint64_t seed, std::string_view name, double max_phase_s = 0.040);
  /// When the message about sandtray time `t` is published (s, sandtray clock; later than `t`, never by more than
  /// kMaxPublishDelayS). Each call draws the next jitter.
  double publish(double t);
  /// The publisher's fixed phase (s).
  double phase() const { return phase_; }

 private:
  double phase_ = 0.0;
  Rng rng_;
};

/// The publisher clocks of one episode, made on first use.
class PublisherClocks {
 public:
  /// Clocks of the episode with root `seed`.
  explicit PublisherClocks(std::uint64_t seed = 0) : seed_(seed) {}
  /// When publisher `name` sends the message about sandtray time `t` (PublisherClock::publish).
  double publish(const std::string& name, double t, double max_phase_s = 0.040);

 private:
  std::uint64_t seed_;
  std::map<std::string, PublisherClock> clocks_;
};

/// The index of the game tick (`t / 0.1`, rounded) a publisher's message of sandtray time `published` is about.
long publication_tick(double published);
/// The sandtray time of tick `tick` (s).
inline double tick_time(long tick) { return static_cast<double>(tick) * kPublishTickS; }

}  // namespace freeplay::recording
