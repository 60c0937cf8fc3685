#pragma once
// The coder on a recorded event log: codes the social engagement of both players of any episode's
// `events/<episode>.jsonl` (live, replayed, or with children from a bag) from what the log shows them doing.

#include <filesystem>
#include <vector>

#include "freeplay/agents/annotations.hpp"
#include "freeplay/agents/params.hpp"
#include "freeplay/core/event_log.hpp"

namespace freeplay::runner {

/// Reads an event log written as JSON Lines; InputError naming the file and line on a malformed line.
std::vector<Event> read_event_log(const std::filesystem::path& path);

/// Codes the free play of an event log with the coder's rules (agents::PairCoder) at the game's 10 Hz: the children's
/// touches (down to up, at the press point), gaze and speech events; the robot's moves (goal to result), gaze (`look_at`) and
/// speech to a child (`say`). Only the social-engagement axis; times in seconds since free play started.
/// InputError when the log has no free-play stage.
agents::SessionAnnotations code_event_log(const std::vector<Event>& events, const agents::CoderParams& params);

}  // namespace freeplay::runner
