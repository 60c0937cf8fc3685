#pragma once
// The typed settings of each subsystem a scenario configures (children, robot, planner, perception, protocol,
// cameras, rendering, recording, controller): one struct each, whose member initialisers are the defaults and whose
// `visit` lists the keys, ranges and help once; the scenario parser composes their schemas and readers
// (core/settings_archive.hpp). The planner's settings are declared by the planning library
// (planning/planner_settings.hpp) and the children's by the agents library (agents/children_settings.hpp); the others
// still live here.

#include <optional>
#include <string>
#include <vector>

#include "freeplay/agents/children_settings.hpp"
#include "freeplay/agents/item_names.hpp"
#include "freeplay/core/settings_archive.hpp"
#include "freeplay/planning/planner_settings.hpp"
#include "freeplay/policies/policy_names.hpp"
#include "freeplay/stage/camera_names.hpp"
#include "freeplay/stage/stage_mode.hpp"

namespace freeplay::scenario {

/// Names the validator accepts for the open-ended choices (filled from the registries of the linked libraries).
struct ScenarioVocabulary {
  std::vector<std::string> policies{policies::kPolicyNames.begin(), policies::kPolicyNames.end()};  ///< play policies
  std::vector<std::string> planners{planning::kPlannerNames.begin(), planning::kPlannerNames.end()};  ///< planners
  std::vector<std::string> cameras = stage::real_camera_names();  ///< stage cameras of the real setup
  std::vector<std::string> items{agents::kItemNames.begin(), agents::kItemNames.end()};  ///< sandtray items
  std::vector<std::string> voices = {"babble", "espeak"};  ///< audio voices (`record.voice`) this binary has

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

/// One camera stream the scenario asks for (an element of `cameras:`).
struct CameraStream {
  std::string name;      ///< stage camera name
  double rate_hz = 30;   ///< frames per simulated second
  int width = 960;       ///< pixels
  int height = 540;      ///< pixels
  bool depth = false;    ///< also read back depth
  bool video = false;    ///< write `videos/<episode>/<name>.mp4`

  /// The keys of one camera (names from `vocabulary`).
  template <typename Archive>
  void visit(Archive& a, const ScenarioVocabulary& vocabulary) {
    a.required("name", name, Schema::enumeration(vocabulary.cameras));
    a.field("rate_hz", rate_hz, Schema::number(0.1, 60));
    a.field("width", width, Schema::integer(16, 4096));
    a.field("height", height, Schema::integer(16, 4096));
    a.field("depth", depth, Schema::boolean());
    a.field("video", video, Schema::boolean(), "write videos/<episode>/<name>.mp4 (mp4v, fps = rate_hz)");
  }
};

/// `rendering:` how the cameras are rendered.
struct RenderingSettings {
  std::string backend;          ///< "osmesa" | "egl"; empty: $MUJOCO_GL, else osmesa
  std::string preset = "fast";  ///< "fast" | "pretty"

  /// The keys of `rendering:`.
  template <typename Archive>
  void visit(Archive& a) {
    a.optional("backend", backend, Schema::enumeration({"osmesa", "egl"}), "GL provider; default $MUJOCO_GL, else osmesa");
    a.field("preset", preset, Schema::enumeration({"fast", "pretty"}),
            "fast: no MSAA/shadows/reflections/skybox; pretty: 4x MSAA, shadows, skybox");
  }
};

/// How an episode is recorded (`record:` as a map; docs/recording.md).
struct RecordSettings {
  int jpeg_quality = 90;              ///< colour JPEG quality (the real launch files: 90)
  int png_level = 3;                  ///< PNG level of depth and background images (the real launch files: 3)
  int chunk_kb = 768;                 ///< bag chunk size (rosbag's default): at most this much is lost on a kill
  std::string compression = "none";   ///< bag chunk compression: "none" (as the real bags), "lz4", "bz2"
  int encoder_threads = 2;            ///< threads compressing camera images (0: on the episode's own thread)
  std::string voice = "babble";       ///< speech synthesiser of the audio: "babble" (ours) or "espeak" (espeak-ng)

  /// The keys of the `record:` map besides `bag`.
  template <typename Archive>
  void visit(Archive& a, const ScenarioVocabulary& vocabulary) {
    a.field("jpeg_quality", jpeg_quality, Schema::integer(1, 100));
    a.field("png_level", png_level, Schema::integer(0, 9));
    a.field("chunk_kb", chunk_kb, Schema::integer(16, 1 << 20));
    a.field("compression", compression, Schema::enumeration({"none", "lz4", "bz2"}));
    a.field("encoder_threads", encoder_threads, Schema::integer(0, 64),
            "threads compressing camera images (0: the episode's thread)");
    a.field("voice", voice, Schema::enumeration(vocabulary.voices),
            "speech synthesiser of the audio: babble (ours) or espeak (espeak-ng, GPL-3; only in binaries built with it)");
  }
};

}  // namespace freeplay::scenario
