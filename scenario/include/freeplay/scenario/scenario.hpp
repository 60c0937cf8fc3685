#pragma once
// A scenario: one experimental condition (participants, policy, protocol, planner, perception, cameras),
// validated completely before anything runs and immutable afterwards.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/agents/condition.hpp"
#include "freeplay/runner/controller_settings.hpp"
#include "freeplay/scenario/settings.hpp"

namespace freeplay::scenario {

/// One step of a controller scenario's target sequence (declared by the runner, runner/controller_settings.hpp).
using runner::ControllerTarget;
/// `controller:` of a scenario of kind `controller` (declared by the runner, runner/controller_settings.hpp).
using runner::ControllerSpec;

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
  runner::ControllerSpec controller;     ///< the controller sequence (kind "controller" only)
  Condition condition = Condition::ChildChild;  ///< who plays (controller for kind controller)
  int episodes = 1;                      ///< episodes to run
  std::uint64_t seed = 1;                ///< root seed; episode i uses SeedSequence(seed).derive("episode/i")
  agents::ChildrenSettings children;     ///< who plays (population, explicit profile fields)
  runner::RobotSettings robot;           ///< the robot's policy and body (child-robot only)
  planning::PlannerSettings planner;     ///< the motion planner of the robot's item moves
  runner::PerceptionSettings perception; ///< the robot's perception noise and latency
  runner::Protocol protocol;             ///< stage durations
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
