#pragma once
// A scenario: one experimental condition (participants, policy, protocol, planner, perception, cameras),
// validated completely before anything runs and immutable afterwards.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/agents/condition.hpp"
#include "freeplay/scenario/settings.hpp"

namespace freeplay::scenario {

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
  stage::StageMode mode = stage::StageMode::dynamic;  ///< dynamic (simulated actuators) or kinematic
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
  std::vector<ControllerTarget> targets;    ///< the sequence, in order (its own schema: `targets`)

  /// The keys of `controller:` besides `targets`.
  template <typename Archive>
  void visit(Archive& a) {
    a.field("mode", mode, Schema::enumeration(enum_names({stage::StageMode::dynamic, stage::StageMode::kinematic})),
            "robot simulation mode");
    a.field("speed_fraction", speed_fraction, Schema::number(0.01, 50.0),
            "joint speed of the commanded profile as a fraction of the Nao's velocity limits (> 1 exceeds them "
            "deliberately)");
    a.field("torque_fraction", torque_fraction, Schema::number(0.01, 50.0),
            "profile speed at most this fraction of each joint's effort limit / its damping (> 1 exceeds the "
            "motors' efforts deliberately)");
    a.field("trace_interval_steps", trace_interval_steps, Schema::integer(1, 1000000),
            "golden-trace checkpoint every N steps");
    a.field("settle_tolerance_m", settle_tolerance_m, Schema::number(1e-5, 0.1));
    a.field("settle_tolerance_rad", settle_tolerance_rad, Schema::number(1e-5, 1.0));
    a.field("settle_speed_rad_s", settle_speed_rad_s, Schema::number(1e-4, 10.0));
    a.field("hold_s", hold_s, Schema::number(0.0, 60.0), "time held at a target once settled");
    a.field("timeout_s", timeout_s, Schema::number(0.1, 600.0), "longest time spent on one target");
  }
};

/// What a scenario runs (`kind:`).
enum class ScenarioKind {
  episode,     ///< a session with children
  controller,  ///< the Nao alone through a target sequence
};

/// The name scenarios use for a kind ("episode", "controller").
std::string_view to_string(ScenarioKind kind);
/// Sets `kind` to the kind named `text`; false (and `kind` unchanged) when `text` names none.
bool from_string(std::string_view text, ScenarioKind& kind);

/// Who plays (`condition:`): the agents' enum, with its names and its PInSoRo spelling (freeplay/agents/condition.hpp).
using agents::Condition;
using agents::from_string;
using agents::pinsoro_name;
using agents::to_string;

/// A validated scenario. Each block's settings are declared by the library that uses them (settings.hpp lists where).
struct Scenario {
  std::string name;                      ///< short identifier, used in output names
  std::string description;               ///< one line for people
  std::string file;                      ///< where it was loaded from ("" when built in code)
  ScenarioKind kind = ScenarioKind::episode;  ///< a session with children, or the Nao alone
  ControllerSpec controller;             ///< the controller sequence (kind "controller" only)
  Condition condition = Condition::ChildChild;  ///< who plays (controller for kind controller)
  int episodes = 1;                      ///< episodes to run
  std::uint64_t seed = 1;                ///< root seed; episode i uses SeedSequence(seed).derive("episode/i")
  agents::ChildrenSettings children;     ///< who plays (population, explicit profile fields)
  RobotSettings robot;                   ///< the robot's policy and body (child-robot only)
  planning::PlannerSettings planner;     ///< the motion planner of the robot's item moves
  PerceptionSettings perception;         ///< the robot's perception noise and latency
  Protocol protocol;                     ///< stage durations
  std::vector<stage::CameraStream> cameras;  ///< camera output (none: no rendering)
  stage::RenderingSettings rendering;    ///< GL backend and visual preset of the cameras
  bool record = false;                   ///< write a ROS bag per episode
  recording::RecordSettings recording;   ///< how (when `record`)
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

}  // namespace freeplay::scenario
