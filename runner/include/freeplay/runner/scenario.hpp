#pragma once
// A scenario: one experimental condition (participants, policy, protocol, planner, perception, cameras),
// validated completely before anything runs and immutable afterwards.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/core/yaml_schema.hpp"

namespace freeplay::runner {

/// Names the validator accepts for the open-ended choices (filled from the registries of the linked libraries).
struct ScenarioVocabulary {
  std::vector<std::string> policies = {"asocial", "social", "idle", "scripted"};  ///< registered play policies
  std::vector<std::string> planners = {"astar", "rrtconnect", "prmstar", "rrtstar", "bitstar"};  ///< planners
  std::vector<std::string> cameras = {"camera_purple", "camera_yellow", "env_camera", "CameraTop",
                                      "CameraBottom"};  ///< stage cameras
  std::vector<std::string> items = {"zebra", "elephant", "ball", "lion", "giraffe", "caravan", "crocodile",
                                    "hippo", "boy", "girl"};  ///< sandtray items (controller `move` targets)
};

/// An explicit child profile (absent fields are sampled from the population).
struct ChildSpec {
  std::optional<int> age;                    ///< years, 4–8
  std::optional<std::string> gender;         ///< "female" | "male"
  std::optional<double> sociability;         ///< 0–1
  std::optional<double> assertiveness;       ///< 0–1
  std::optional<double> attention_span;      ///< 0–1
  std::optional<int> tablet_familiarity;     ///< 0, 1, 2
};

/// One camera stream the scenario asks for.
struct CameraStream {
  std::string name;      ///< stage camera name
  double rate_hz = 30;   ///< frames per simulated second
  int width = 960;       ///< pixels
  int height = 540;      ///< pixels
  bool depth = false;    ///< also read back depth
  bool video = false;    ///< write `videos/<episode>/<name>.mp4`
};

/// How the cameras are rendered (`rendering:`).
struct RenderingSettings {
  std::string backend;          ///< "osmesa" | "egl"; empty: $MUJOCO_GL, else osmesa
  std::string preset = "fast";  ///< "fast" | "pretty"
};

/// How an episode is recorded (`record:` true or a map; docs/recording.md).
struct RecordSettings {
  int jpeg_quality = 90;              ///< colour JPEG quality (the real launch files: 90)
  int png_level = 3;                  ///< PNG level of depth and background images (the real launch files: 3)
  int chunk_kb = 768;                 ///< bag chunk size (rosbag's default): at most this much is lost on a kill
  std::string compression = "none";   ///< bag chunk compression: "none" (as the real bags), "lz4", "bz2"
  int encoder_threads = 2;            ///< threads compressing camera images (0: on the episode's own thread)
};

/// The protocol of the paper, with stage durations (s).
struct Protocol {
  double greeting_s = 300;         ///< greetings (the robot says hello in child-robot sessions)
  double tutorial_s = 90;          ///< tutorial background, boy and girl only
  double freeplay_cap_s = 2400;    ///< free play ends when the children quit or at this cap (40 min)
  double debriefing_s = 120;       ///< blank screen, debriefing
};

/// One step of a controller scenario's target sequence.
struct ControllerTarget {
  /// What the step asks of the Nao.
  enum class Kind { Point, Look, Move, Posture, Wait, RandomPoints };
  Kind kind = Kind::Wait;                   ///< the step's kind
  std::vector<double> point;                ///< Point: screen x, y (m); Look: x, y, z (m); Move: target x, y
  std::string item;                         ///< Move: the item to drag
  std::optional<std::vector<double>> from;  ///< Move: where the item is placed first (nullopt: where it is)
  std::string posture;                      ///< Posture: NAOqi posture name
  double seconds = 0.0;                     ///< Wait: how long to hold still (s)
  int count = 0;                            ///< RandomPoints: how many points
  std::string region;                       ///< RandomPoints: "reach" or "screen"
};

/// The `controller:` section of a scenario of kind `controller`.
struct ControllerSpec {
  std::string mode = "dynamic";             ///< "dynamic" (simulated actuators) | "kinematic"
  double speed_fraction = 0.3;              ///< joint speed of the commanded profile, as a fraction of each joint's
                                            ///< velocity limit (ALMotion's angleInterpolationWithSpeed fraction)
  double torque_fraction = 0.5;             ///< and no faster than this fraction of each joint's effort limit can
                                            ///< drive against the joint's damping
  int trace_interval_steps = 50;            ///< golden-trace checkpoint every N physics steps (2 ms each)
  double settle_tolerance_m = 0.003;        ///< fingertip distance to its commanded position that counts as settled
  double settle_tolerance_rad = 0.01;       ///< joint error that counts as settled (look and posture targets)
  double settle_speed_rad_s = 0.05;         ///< joint speeds below which the robot counts as still
  double hold_s = 0.2;                      ///< time held at each target once settled
  double timeout_s = 5.0;                   ///< longest time spent on one target
  std::vector<ControllerTarget> targets;    ///< the sequence, in order
};

/// A validated scenario.
struct Scenario {
  std::string name;                      ///< short identifier, used in output names
  std::string description;               ///< one line for people
  std::string file;                      ///< where it was loaded from ("" when built in code)
  std::string kind = "episode";          ///< "episode" (a session with children) | "controller" (the Nao alone)
  ControllerSpec controller;             ///< the controller sequence (kind "controller" only)
  std::string condition;                 ///< "child-child" | "child-robot" ("controller" for kind controller)
  int episodes = 1;                      ///< episodes to run
  std::uint64_t seed = 1;                ///< root seed; episode i uses SeedSequence(seed).derive("episode/i")
  std::string population = "pinsoro";    ///< population the children are sampled from
  ChildSpec purple;                      ///< explicit purple profile fields
  ChildSpec yellow;                      ///< explicit yellow profile fields (child-child only)
  std::string policy = "asocial";        ///< robot play policy (child-robot only)
  YAML::Node policy_params;              ///< policy-specific parameters (validated by the policy)
  std::string robot_mode = "kinematic";  ///< "kinematic" | "dynamic"
  double arm_reach_m = 0.5;              ///< reach used for the arm-reach disc (real sessions: 0.5)
  std::string planner = "astar";         ///< motion planner
  double planner_budget_s = 1.0;         ///< wall-clock planning budget (only anytime planners use it up)
  double finger_speed_mps = 0.05;        ///< robot finger speed (5 mm per 0.1 s)
  bool reject_blocked_goals = false;     ///< refuse goals inside other footprints (the real planner does not)
  double face_detection_rate = 0.98;     ///< perception: fraction of frames with the face found
  double perception_latency_s = 0.1;     ///< perception latency
  double gaze_noise_deg = 5.0;           ///< perception: head-pose noise (SD)
  Protocol protocol;                     ///< stage durations
  std::vector<CameraStream> cameras;     ///< camera output (none: no rendering)
  RenderingSettings rendering;           ///< GL backend and visual preset of the cameras
  bool record = false;                   ///< write a ROS bag per episode
  RecordSettings recording;              ///< how (when `record`)
  YAML::Node source;                     ///< the validated document with defaults filled in
  std::uint64_t config_hash = 0;         ///< hash of the validated document (reproducibility)
};

/// The schema every scenario file is validated against.
std::shared_ptr<const Schema> scenario_schema(const ScenarioVocabulary& vocabulary = {});

/// Loads, overrides (`KEY.PATH=VALUE`), validates completely and converts a scenario file.
Scenario load_scenario(const std::filesystem::path& path, const std::vector<std::string>& overrides = {},
                       const ScenarioVocabulary& vocabulary = {});
/// Same, from a parsed document.
Scenario scenario_from_document(YamlDocument document, const std::vector<std::string>& overrides = {},
                                const ScenarioVocabulary& vocabulary = {});

}  // namespace freeplay::runner
