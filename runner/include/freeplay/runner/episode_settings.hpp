#pragma once
// The settings of an episode with children that the episode loop reads: the robot's play policy and body (`robot:`,
// robot side and robot body), its perception (`perception:`, perception_model.hpp) and the protocol's stage durations
// (`protocol:`, episode.hpp). Header-only (freeplay_runner_headers), so that the parse-only scenario parser reads
// them without linking the runner. Member initialisers are the defaults; `visit` lists the keys, ranges and help
// (core/settings_archive.hpp).

#include <string>
#include <vector>

#include "freeplay/core/settings_archive.hpp"
#include "freeplay/stage/stage_mode.hpp"

namespace freeplay::runner {

/// `robot:` the robot's play policy and body (child-robot only).
struct RobotSettings {
  std::string policy = "asocial";                         ///< robot play policy
  YAML::Node params = YAML::Node(YAML::NodeType::Map);    ///< policy-specific parameters (validated by the policy)
  stage::StageMode mode = stage::StageMode::kinematic;   ///< how the robot's body moves
  double arm_reach_m = 0.5;                               ///< reach used for the arm-reach disc (real sessions: 0.5)

  /// The keys of `robot:` (`policy_names`: the names `policy` accepts, from the policies' registry).
  template <typename Archive>
  void visit(Archive& a, const std::vector<std::string>& policy_names) {
    a.field("policy", policy, Schema::enumeration(policy_names), "play policy");
    a.field("params", params, Schema::dictionary(Schema::any()), "policy parameters");
    a.field("mode", mode, Schema::enumeration(enum_names({stage::StageMode::kinematic, stage::StageMode::dynamic})),
            "robot simulation mode");
    a.field("arm_reach_m", arm_reach_m, Schema::number(0.1, 1.0), "arm reach for the reachable disc");
  }
};

/// `perception:` noise, latency and dropout of the robot's perception pipeline (PerceptionModel).
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

}  // namespace freeplay::runner
