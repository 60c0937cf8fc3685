#include "freeplay/recording/publishers.hpp"

#include <cmath>

namespace freeplay::recording {

namespace {
constexpr double kMinPhaseS = 0.002;
constexpr double kJitterS = 0.002;
}  // namespace

PublisherClock::PublisherClock(std::uint64_t seed, std::string_view name, double max_phase_s)
    : rng_(splitmix64(seed ^ fnv1a64(name))) {
  phase_ = rng_.uniform(kMinPhaseS + kJitterS, max_phase_s);
}

double PublisherClock::publish(double t) { return t + phase_ + rng_.uniform(-kJitterS, kJitterS); }

double PublisherClocks::publish(const std::string& name, double t, double max_phase_s) {
  auto it = clocks_.find(name);
  if (it == clocks_.end()) it = clocks_.emplace(name, PublisherClock(seed_, name, max_phase_s)).first;
  return it->second.publish(t);
}

long publication_tick(double published) {
  // A message of tick k is published in [k, k + 0.42] ticks: shifting by half that range rounds it back to k.
  return std::lround(published / kPublishTickS - 0.5 * kMaxPublishDelayS / kPublishTickS);
}

}  // namespace freeplay::recording
