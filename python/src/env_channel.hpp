#pragma once
// The policy of an episode stepped by `freeplay.Env`: each 10 Hz decision is handed to the Python thread that
// steps the environment, and the episode's worker thread waits for its actions (episode.cpp stays the only loop).

#include <memory>

#include "freeplay/policies/play_policy.hpp"

namespace freeplay::python {

/// The decision channel's policy when the calling thread runs an Env episode, else nullptr.
std::unique_ptr<policies::PlayPolicy> make_env_channel_policy();

}  // namespace freeplay::python
