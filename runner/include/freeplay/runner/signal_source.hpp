#pragma once
// Signals sent to the game from outside an episode: `sandtray/signals/*` from the supervisor, a wizard or any node
// of a live graph (`freeplay serve`). The episode applies each as the real game does and lets the stage signals
// move its protocol forward.

#include <vector>

#include "freeplay/sim/sandtray.hpp"

namespace freeplay::runner {

/// Supplies the signals received since the last call (polled at every 10 Hz tick of every stage).
class SignalSource {
 public:
  virtual ~SignalSource() = default;
  /// The signals received since the last call, in order of arrival.
  virtual std::vector<sim::Signal> take() = 0;
};

}  // namespace freeplay::runner
