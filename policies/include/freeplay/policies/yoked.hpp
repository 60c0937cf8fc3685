#pragma once
// The yoked control's source: the robot actions of one episode, read back from its event log (docs/validity.md).

#include <filesystem>
#include <utility>
#include <vector>

#include "freeplay/policies/play_policy.hpp"

namespace freeplay::policies {

/// The robot's actions (`say`, `move_goal`, `look_at`, `point_at`, `cancel` events) of the free-play stage of an
/// episode's event log, with their free-play times, in log order (the greeting and outcome events are left out);
/// InputError naming the file and line when it is not a readable event log of a child-robot episode.
std::vector<std::pair<double, Action>> read_robot_actions(const std::filesystem::path& event_log);

}  // namespace freeplay::policies
