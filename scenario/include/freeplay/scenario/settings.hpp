#pragma once
// The typed settings a scenario configures: one struct per block, whose member initialisers are the defaults and whose
// `visit` lists the keys, ranges and help once; the scenario parser composes their schemas and readers
// (core/settings_archive.hpp). Each library declares its own settings next to the code that uses them, header-only,
// and the parser reaches them through that library's header-only target (freeplay_*_headers), linking none of its
// code: the planner's (planning/planner_settings.hpp), the children's (agents/children_settings.hpp), the cameras' and
// the renderer's (stage/camera_settings.hpp), the recorder's (recording/record_settings.hpp), and the robot's, its
// perception's and the protocol's (runner/episode_settings.hpp; the controller's: runner/controller_settings.hpp,
// re-exported by scenario.hpp). This header re-exports them under freeplay::scenario and adds the vocabulary.

#include <string>
#include <vector>

#include "freeplay/agents/children_settings.hpp"
#include "freeplay/agents/item_names.hpp"
#include "freeplay/core/settings_archive.hpp"
#include "freeplay/planning/planner_settings.hpp"
#include "freeplay/policies/policy_names.hpp"
#include "freeplay/recording/record_settings.hpp"
#include "freeplay/runner/episode_settings.hpp"
#include "freeplay/stage/camera_names.hpp"
#include "freeplay/stage/camera_settings.hpp"

namespace freeplay::scenario {

/// Names the validator accepts for the open-ended choices (filled from the registries of the linked libraries).
struct ScenarioVocabulary {
  std::vector<std::string> policies{policies::kPolicyNames.begin(), policies::kPolicyNames.end()};  ///< play policies
  std::vector<std::string> planners{planning::kPlannerNames.begin(), planning::kPlannerNames.end()};  ///< planners
  std::vector<std::string> cameras = stage::real_camera_names();  ///< stage cameras of the real setup
  std::vector<std::string> items{agents::kItemNames.begin(), agents::kItemNames.end()};  ///< sandtray items
  /// Audio voices (`record.voice`) this binary has.
  std::vector<std::string> voices{recording::kVoiceNames.begin(), recording::kVoiceNames.end()};

  /// Same names in the same order.
  bool operator==(const ScenarioVocabulary&) const = default;
};

/// An explicit child profile (declared by the agents library, agents/children_settings.hpp).
using agents::ChildSpec;
/// `children:` who plays (declared by the agents library, agents/children_settings.hpp).
using agents::ChildrenSettings;

/// `robot:` the robot's play policy and body (declared by the runner, runner/episode_settings.hpp).
using runner::RobotSettings;
/// `planner:` the motion planner of the robot's item moves (declared by the planning library).
using PlannerSettings = planning::PlannerSettings;
/// `perception:` the robot's perception noise and latency (declared by the runner, runner/episode_settings.hpp).
using runner::PerceptionSettings;
/// `protocol:` the protocol's stage durations (declared by the runner, runner/episode_settings.hpp).
using runner::Protocol;

/// One element of `cameras:` (declared by the stage library, stage/camera_settings.hpp).
using stage::CameraStream;
/// `rendering:` how the cameras are rendered (declared by the stage library, stage/camera_settings.hpp).
using stage::RenderingSettings;
/// `record:` as a map: how an episode is recorded (declared by the recording library, recording/record_settings.hpp).
using recording::RecordSettings;

}  // namespace freeplay::scenario
