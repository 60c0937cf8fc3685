#pragma once
// A population of full episodes seen as calibration sessions: the product itself (sandtray, policies, planner,
// executor, robot), not the logic-only stand-in, measured with the same statistics as `freeplay calibrate`.

#include <functional>
#include <vector>

#include "freeplay/agents/session.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/scenario/scenario.hpp"

namespace freeplay::runner {

/// Runs episodes 0…`episodes`−1 of `scenario` (episode i with the suite's seed for index i, so two scenarios with
/// the same seed meet the same children) on `threads` threads; `progress` (may be empty) hears each finished one.
std::vector<agents::SessionResult> run_population(const scenario::Scenario& scenario, int episodes, int threads,
                                                  const SharedModels& models,
                                                  const std::function<void(int done)>& progress = {});

/// The calibration view of one full episode: durations, cap, each child's coded and internal timelines.
agents::SessionResult session_result(const EpisodeResult& episode);

}  // namespace freeplay::runner
