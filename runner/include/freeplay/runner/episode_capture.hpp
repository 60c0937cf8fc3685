#pragma once
// One moment of an episode: run it until a protocol stage has lasted a given time, hand that tick's snapshot to
// a callback (render a camera, save the screen), and stop the episode there.

#include <cstdint>
#include <functional>
#include <string>

#include "freeplay/runner/episode.hpp"

namespace freeplay::runner {

/// A time in an episode: `seconds` after the start of a protocol stage.
struct EpisodeMoment {
  std::string stage = "freeplay";  ///< "greeting" | "tutorial" | "freeplay" | "debriefing"
  double seconds = 0.0;            ///< time since the stage started (s, ≥ 0)
};

/// Where the capture happened.
struct CaptureResult {
  double t = 0.0;           ///< sandtray clock of the captured tick (s since the episode started)
  double stage_t = 0.0;     ///< seconds since its stage started (the first 10 Hz tick at or after the moment)
  double freeplay_t = 0.0;  ///< seconds since free play started (negative before it)
};

/// Runs episode `seed` of `scenario` up to the first 10 Hz tick at or after `moment`, calls `capture` with that
/// tick's snapshot, and stops the episode. Throws InputError naming `--time`/`--stage` when the moment lies beyond
/// the stage (e.g. "the episode ended at 742.3 s of free play (children quit)"), and whatever `capture` throws.
CaptureResult capture_episode_moment(const scenario::Scenario& scenario, std::uint64_t seed, const SharedModels& models,
                                     const EpisodeMoment& moment,
                                     const std::function<void(const EpisodeSnapshot&)>& capture);

}  // namespace freeplay::runner
