#pragma once
// The typed settings a scenario configures: one struct per block, whose member initialisers are the defaults and whose
// `visit` lists the keys, ranges and help once; the scenario parser composes their schemas and readers
// (core/settings_archive.hpp). Each library that sits below this parser declares its own settings next to the code
// that uses them, header-only: the planner's (planning/planner_settings.hpp), the children's
// (agents/children_settings.hpp), the cameras' and the renderer's (stage/camera_settings.hpp) and the recorder's
// (recording/record_settings.hpp). The settings of the robot, its perception and the protocol are read by the episode
// loop (runner/), which is built on this library; declaring them there would point the parser up the layering, so they
// stay here (as the controller's do, in scenario.hpp).

#include <optional>
#include <string>
#include <vector>

#include "freeplay/agents/children_settings.hpp"
#include "freeplay/agents/item_names.hpp"
#include "freeplay/core/settings_archive.hpp"
#include "freeplay/planning/planner_settings.hpp"
#include "freeplay/policies/policy_names.hpp"
#include "freeplay/recording/record_settings.hpp"
#include "freeplay/stage/camera_names.hpp"
#include "freeplay/stage/camera_settings.hpp"
#include "freeplay/stage/stage_mode.hpp"

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

/// `robot:` the robot's play policy and body (child-robot only).
struct RobotSettings {
  std::string policy = "asocial";                         ///< robot play policy
  YAML::Node params = YAML::Node(YAML::NodeType::Map);    ///< policy-specific parameters (validated by the policy)
  stage::StageMode mode = stage::StageMode::kinematic;   ///< how the robot's body moves
  double arm_reach_m = 0.5;                               ///< reach used for the arm-reach disc (real sessions: 0.5)

  /// The keys of `robot:` (policies named by `vocabulary`).
  template <typename Archive>
  void visit(Archive& a, const ScenarioVocabulary& vocabulary) {
    a.field("policy", policy, Schema::enumeration(vocabulary.policies), "play policy");
    a.field("params", params, Schema::dictionary(Schema::any()), "policy parameters");
    a.field("mode", mode, Schema::enumeration(enum_names({stage::StageMode::kinematic, stage::StageMode::dynamic})),
            "robot simulation mode");
    a.field("arm_reach_m", arm_reach_m, Schema::number(0.1, 1.0), "arm reach for the reachable disc");
  }
};

/// `planner:` the motion planner of the robot's item moves (declared by the planning library).
using PlannerSettings = planning::PlannerSettings;

/// `perception:` noise, latency and dropout of the robot's perception pipeline.
struct PerceptionSettings {
  double face_detection_rate = 0.98;  ///< fraction of frames with the face found (PInSoRo: 98 %)
  double latency_s = 0.1;             ///< delay between the world and the policy's observation
  double gaze_noise_deg = 5.0;        ///< head-pose noise; the gaze class is confused with p = noise / 90°

  /// The keys of `perception:`.
  template <typename Archive>
  void visit(Archive& a) {
    a.field("face_detection_rate", face_detection_rate, Schema::number(0, 1));
    a.field("latency_s", latency_s, Schema::number(0, 5));
    a.field("gaze_noise_deg", gaze_noise_deg, Schema::number(0, 90));
  }
};

/// `protocol:` the protocol of the paper, with stage durations (s).
struct Protocol {
  double greeting_s = 300;         ///< greetings (the robot says hello in child-robot sessions)
  double tutorial_s = 90;          ///< tutorial background, boy and girl only
  double freeplay_cap_s = 2400;    ///< free play ends when the children quit or at this cap (40 min)
  double debriefing_s = 120;       ///< blank screen, debriefing

  /// The keys of `protocol:`.
  template <typename Archive>
  void visit(Archive& a) {
    a.field("greeting_s", greeting_s, Schema::number(0, 3600), "about 5 min in the paper's protocol");
    a.field("tutorial_s", tutorial_s, Schema::number(0, 3600), "1–2 min");
    a.field("freeplay_cap_s", freeplay_cap_s, Schema::number(1, 4 * 3600));
    a.field("debriefing_s", debriefing_s, Schema::number(0, 3600), "about 2 min");
  }
};

/// One element of `cameras:` (declared by the stage library, stage/camera_settings.hpp).
using stage::CameraStream;
/// `rendering:` how the cameras are rendered (declared by the stage library, stage/camera_settings.hpp).
using stage::RenderingSettings;
/// `record:` as a map: how an episode is recorded (declared by the recording library, recording/record_settings.hpp).
using recording::RecordSettings;

}  // namespace freeplay::scenario
