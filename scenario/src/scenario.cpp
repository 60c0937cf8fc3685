#include "freeplay/scenario/scenario.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <limits>

#include "freeplay/core/rng.hpp"
#include "freeplay/core/settings_archive.hpp"
#include "freeplay/stage/camera_names.hpp"
#include "freeplay/stage/nao_description.hpp"

namespace freeplay::scenario {

namespace {

using S = Schema;

// ---- controller scenarios (kind: controller) ----------------------------------------------------------------

/// Keys of the episode-only sections that a controller scenario rejects (the Nao runs alone: no children).
constexpr std::array<const char*, 4> kEpisodeOnlyKeys = {"children", "robot", "protocol", "perception"};

constexpr const char* kTargetForms =
    "one of point: [x, y] | look: [x, y, z] | move: {item, to, from} | posture: NAME | wait: S | "
    "random_points: {count, region}";

std::shared_ptr<const Schema> controller_target_schema(const ScenarioVocabulary& vocabulary) {
  const auto xy = S::list(S::number(-2.0, 2.0), 2, 2);
  const auto xyz = S::list(S::number(-3.0, 3.0), 3, 3);
  const auto move = S::map({
      required("item", S::enumeration(vocabulary.items)),
      required("to", xy, "target of the item centre (sandtray x, y, m)"),
      optional("from", xy, "place the item here first (default: where it is)"),
  });
  const auto random_points = S::map({
      required("count", S::integer(1, 10000)),
      with_default("region", S::enumeration({"reach", "screen"}), "reach",
                   "reach: the band the standing Nao reaches; screen: the whole screen"),
  });
  const std::vector<std::string> postures(stage::kNaoPostureNames.begin(), stage::kNaoPostureNames.end());
  // One map with every key optional (exactly one present, checked in check_kind_sections), so that errors inside a
  // target name the nested key and its allowed values.
  return S::map({optional("point", xy, "screen point (sandtray x, y, m)"),
                 optional("look", xyz, "gaze point (sandtray x, y, z, m)"),
                 optional("move", move, "an item drag through the planner and MoveExecutor"),
                 optional("posture", S::enumeration(postures)),
                 optional("wait", S::number(0.0, 600.0), "seconds"),
                 optional("random_points", random_points, "seeded random screen points")});
}

std::shared_ptr<const Schema> controller_schema(const ScenarioVocabulary& vocabulary) {
  auto fields = SchemaArchive::fields_of<ControllerSpec>();
  fields.push_back(required("targets", S::list(controller_target_schema(vocabulary), 1), "the target sequence"));
  return S::map(std::move(fields));
}

// The conditions a scenario of kind episode may name.
constexpr std::initializer_list<Condition> kEpisodeConditions = {Condition::ChildChild, Condition::ChildRobot};

void check_kind_sections(const YAML::Node& root, ScenarioKind kind,
                         const std::vector<std::string>& episode_only_keys, const std::string& file,
                         ValidationErrors& errors) {
  if (kind == ScenarioKind::controller) {
    if (!root["controller"].IsDefined()) {
      errors.add(InputError("a scenario of kind controller needs a 'controller' section", "controller",
                            "controller: {targets: [...]}", location_of(root, file)));
    }
    for (const auto& key : episode_only_keys) {
      errors.add(InputError(fmt::format("'{}' belongs to episodes with children; controller scenarios drive the Nao "
                                        "alone (robot mode and gains go in 'controller')", key),
                            key, "remove it, or use kind: episode", location_of(root[key], file)));
    }
    const YAML::Node condition = root["condition"];
    if (condition.IsDefined() && condition.IsScalar() && condition.Scalar() != to_string(Condition::ChildRobot)) {
      errors.add(InputError("controller scenarios run the child-robot stage", "condition",
                            "child-robot, or leave it out", location_of(root["condition"], file)));
    }
    if (!root["controller"].IsDefined() || !root["controller"].IsMap()) return;
    const YAML::Node targets = root["controller"]["targets"];
    if (!targets.IsDefined() || !targets.IsSequence()) return;
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const YAML::Node target = targets[i];
      if (target.IsMap() && target.size() == 1) continue;
      errors.add(InputError(fmt::format("controller target {} needs exactly one key, found {}", i,
                                        target.IsMap() ? target.size() : 0),
                            fmt::format("controller.targets[{}]", i), kTargetForms, location_of(target, file)));
    }
    return;
  }
  if (root["controller"].IsDefined()) {
    errors.add(InputError("a 'controller' section needs kind: controller", "controller",
                          "kind: controller, or remove the section", location_of(root["controller"], file)));
  }
  if (!root["condition"].IsDefined()) {
    errors.add(InputError("missing required key 'condition'", "condition",
                          fmt::format("{}", fmt::join(enum_names(kEpisodeConditions), ", ")),
                          location_of(root, file)));
  }
}

std::vector<double> numbers_of(const YAML::Node& list) {
  std::vector<double> out;
  for (const auto& v : list) out.push_back(v.as<double>());
  return out;
}

ControllerSpec controller_from(const YAML::Node& node) {
  ControllerSpec c = read_settings<ControllerSpec>(node);
  for (const auto& t : node["targets"]) {
    ControllerTarget target;
    if (t["point"]) {
      target.kind = ControllerTarget::Kind::Point;
      target.point = numbers_of(t["point"]);
    } else if (t["look"]) {
      target.kind = ControllerTarget::Kind::Look;
      target.point = numbers_of(t["look"]);
    } else if (t["move"]) {
      target.kind = ControllerTarget::Kind::Move;
      target.item = t["move"]["item"].as<std::string>();
      target.point = numbers_of(t["move"]["to"]);
      if (t["move"]["from"]) target.from = numbers_of(t["move"]["from"]);
    } else if (t["posture"]) {
      target.kind = ControllerTarget::Kind::Posture;
      target.posture = t["posture"].as<std::string>();
    } else if (t["wait"]) {
      target.kind = ControllerTarget::Kind::Wait;
      target.seconds = t["wait"].as<double>();
    } else {
      target.kind = ControllerTarget::Kind::RandomPoints;
      target.count = t["random_points"]["count"].as<int>();
      target.region = t["random_points"]["region"].as<std::string>();
    }
    c.targets.push_back(std::move(target));
  }
  return c;
}

std::shared_ptr<const Schema> build_scenario_schema(const ScenarioVocabulary& vocabulary) {
  auto record_map = std::vector<Field>{with_default("bag", S::boolean(), "true", "write the ROS bag")};
  for (auto& f : SchemaArchive::fields_of<recording::RecordSettings>(vocabulary.voices)) {
    record_map.push_back(std::move(f));
  }
  return S::map({
      required("name", S::string(), "short identifier"),
      with_default("description", S::string(), "\"\""),
      with_default("kind", S::enumeration(enum_names({ScenarioKind::episode, ScenarioKind::controller})),
                   std::string(to_string(ScenarioKind::episode)),
                   "episode: a session with children; controller: the Nao alone through a target sequence"),
      optional("controller", controller_schema(vocabulary), "the target sequence (kind: controller only)"),
      optional("condition", S::enumeration(enum_names(kEpisodeConditions)), "required for kind: episode"),
      with_default("episodes", S::integer(1, 1000000), "1"),
      with_default("seed", S::integer(0, std::numeric_limits<long long>::max()), "1"),
      with_default("children", settings_schema<agents::ChildrenSettings>(), "{}"),
      with_default("robot", settings_schema<runner::RobotSettings>(vocabulary.policies), "{}"),
      with_default("planner", settings_schema<planning::PlannerSettings>(vocabulary.planners), "{}"),
      with_default("perception", settings_schema<runner::PerceptionSettings>(), "{}"),
      with_default("protocol", settings_schema<runner::Protocol>(), "{}"),
      with_default("cameras", S::list(settings_schema<stage::CameraStream>(vocabulary.cameras)), "[]"),
      with_default("rendering", settings_schema<stage::RenderingSettings>(), "{}", "how the cameras are rendered"),
      with_default("record",
                   S::one_of({S::boolean(), S::map(std::move(record_map))},
                             "true, false, or a map {bag: bool, jpeg_quality: 1–100, png_level: 0–9, "
                             "chunk_kb: 16–1048576, compression: none|lz4|bz2, encoder_threads: 0–64}"),
                   "false",
                   "true, or a map {bag, jpeg_quality, png_level, chunk_kb, compression, encoder_threads} "
                   "(docs/recording.md)"),
  });
}

}  // namespace

std::string_view to_string(ScenarioKind kind) { return kind == ScenarioKind::controller ? "controller" : "episode"; }

bool from_string(std::string_view text, ScenarioKind& kind) {
  return enum_from_string(text, {ScenarioKind::episode, ScenarioKind::controller}, kind);
}

std::shared_ptr<const Schema> scenario_schema(const ScenarioVocabulary& vocabulary) {
  // Schemas are immutable: each thread keeps the last one built (a suite validates many scenarios with one
  // vocabulary).
  thread_local std::pair<ScenarioVocabulary, std::shared_ptr<const Schema>> last;
  if (!last.second || !(last.first == vocabulary)) last = {vocabulary, build_scenario_schema(vocabulary)};
  return last.second;
}

Scenario scenario_from_document(YamlDocument document, const std::vector<std::string>& overrides,
                                const ScenarioVocabulary& vocabulary) {
  YAML::Node root = document.root;
  if (!root.IsDefined() || root.IsNull()) {
    throw InputError("the file is empty; a scenario needs at least 'name' and 'condition'", {}, {},
                     {document.file, 1, 1});
  }
  for (const auto& assignment : overrides) apply_override(root, assignment);
  ValidationErrors errors;
  std::vector<std::string> episode_only_keys;  // present before validation fills in defaults
  if (root.IsMap()) {
    for (const char* key : kEpisodeOnlyKeys) {
      if (root[key].IsDefined()) episode_only_keys.emplace_back(key);
    }
  }
  scenario_schema(vocabulary)->validate(root, "", document.file, errors);
  ScenarioKind kind = ScenarioKind::episode;  // an unknown name is already an error; check the rest as an episode
  if (root.IsMap() && root["kind"].IsScalar()) from_string(root["kind"].Scalar(), kind);
  if (root.IsMap()) check_kind_sections(root, kind, episode_only_keys, document.file, errors);
  // Without errors an episode names a valid condition (checked above); a controller's is always `controller`.
  Condition condition = Condition::ChildChild;
  if (root.IsMap() && root["condition"].IsScalar()) from_string(root["condition"].Scalar(), condition);
  if (kind == ScenarioKind::controller) condition = Condition::Controller;  // the Nao alone on the child-robot stage
  if (errors.empty() && condition == Condition::ChildRobot && root["children"]["yellow"].IsDefined()) {
    errors.add(InputError("the robot takes the yellow place in child-robot scenarios", "children.yellow",
                          "remove children.yellow, or use condition: child-child",
                          location_of(root["children"]["yellow"], document.file)));
  }
  for (std::size_t i = 0; errors.empty() && i < root["cameras"].size(); ++i) {
    const YAML::Node name = root["cameras"][i]["name"];
    for (std::size_t j = 0; j < i; ++j) {
      if (root["cameras"][j]["name"].Scalar() == name.Scalar()) {
        errors.add(InputError(fmt::format("camera '{}' is listed twice", name.Scalar()), fmt::format("cameras[{}].name", i),
                              "each camera once", location_of(name, document.file)));
      }
    }
  }
  if (errors.empty() && condition == Condition::ChildChild) {
    for (std::size_t i = 0; i < root["cameras"].size(); ++i) {
      const YAML::Node name = root["cameras"][i]["name"];
      if (stage::is_nao_camera(name.Scalar())) {
        errors.add(InputError(fmt::format("'{}' is a camera of the robot's head, absent in child-child scenarios",
                                          name.Scalar()),
                              fmt::format("cameras[{}].name", i),
                              fmt::format("{}", fmt::join(stage::kRoomCameraNames, ", ")),
                              location_of(name, document.file)));
      }
    }
  }
  errors.throw_if_any();

  Scenario s;
  s.file = document.file;
  s.name = root["name"].as<std::string>();
  s.description = root["description"].as<std::string>();
  s.kind = kind;
  if (kind == ScenarioKind::controller) s.controller = controller_from(root["controller"]);
  s.condition = condition;
  s.episodes = root["episodes"].as<int>();
  s.seed = root["seed"].as<std::uint64_t>();
  s.children = read_settings<agents::ChildrenSettings>(root["children"]);
  s.robot = read_settings<runner::RobotSettings>(root["robot"], vocabulary.policies);
  s.planner = read_settings<planning::PlannerSettings>(root["planner"], vocabulary.planners);
  s.perception = read_settings<runner::PerceptionSettings>(root["perception"]);
  s.protocol = read_settings<runner::Protocol>(root["protocol"]);
  for (const auto& c : root["cameras"]) s.cameras.push_back(read_settings<stage::CameraStream>(c, vocabulary.cameras));
  s.rendering = read_settings<stage::RenderingSettings>(root["rendering"]);
  if (const auto& r = root["record"]; r.IsMap()) {
    s.record = r["bag"].as<bool>();
    s.recording = read_settings<recording::RecordSettings>(r, vocabulary.voices);
  } else {
    s.record = r.as<bool>();
  }
  s.source = root;
  YAML::Emitter emitter;
  emitter << root;
  s.config_hash = fnv1a64(emitter.c_str());
  return s;
}

Scenario load_scenario(const std::filesystem::path& path, const std::vector<std::string>& overrides,
                       const ScenarioVocabulary& vocabulary) {
  return scenario_from_document(load_yaml_file(path), overrides, vocabulary);
}

}  // namespace freeplay::scenario
