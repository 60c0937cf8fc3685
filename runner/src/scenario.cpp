#include "freeplay/runner/scenario.hpp"

#include <fmt/format.h>

#include <array>
#include <limits>

#include "freeplay/core/rng.hpp"
#include "freeplay/stage/nao_description.hpp"

namespace freeplay::runner {

namespace {

using S = Schema;

std::shared_ptr<const Schema> child_schema() {
  return S::map({
      optional("age", S::integer(4, 8), "years"),
      optional("gender", S::enumeration({"female", "male"})),
      optional("sociability", S::number(0, 1)),
      optional("assertiveness", S::number(0, 1)),
      optional("attention_span", S::number(0, 1)),
      optional("tablet_familiarity", S::integer(0, 2), "0 not familiar, 1 somewhat, 2 familiar"),
  });
}

template <typename T>
std::optional<T> maybe(const YAML::Node& node, const char* key) {
  const YAML::Node& n = node;
  if (!n[key].IsDefined() || n[key].IsNull()) return std::nullopt;
  return n[key].as<T>();
}

ChildSpec child_from(const YAML::Node& node) {
  ChildSpec spec;
  if (!node.IsDefined() || node.IsNull()) return spec;
  spec.age = maybe<int>(node, "age");
  spec.gender = maybe<std::string>(node, "gender");
  spec.sociability = maybe<double>(node, "sociability");
  spec.assertiveness = maybe<double>(node, "assertiveness");
  spec.attention_span = maybe<double>(node, "attention_span");
  spec.tablet_familiarity = maybe<int>(node, "tablet_familiarity");
  return spec;
}

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
  std::vector<std::string> postures;
  for (const auto p : stage::kAllNaoPostures) postures.emplace_back(stage::posture_name(p));
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
  return S::map({
      with_default("mode", S::enumeration({"dynamic", "kinematic"}), "dynamic", "robot simulation mode"),
      with_default("speed_fraction", S::number(0.01, 50.0), "0.3",
                   "joint speed of the commanded profile as a fraction of the Nao's velocity limits (> 1 exceeds "
                   "them deliberately)"),
      with_default("torque_fraction", S::number(0.01, 50.0), "0.5",
                   "profile speed at most this fraction of each joint's effort limit / its damping (> 1 exceeds the "
                   "motors' efforts deliberately)"),
      with_default("trace_interval_steps", S::integer(1, 1000000), "50", "golden-trace checkpoint every N steps"),
      with_default("settle_tolerance_m", S::number(1e-5, 0.1), "0.003"),
      with_default("settle_tolerance_rad", S::number(1e-5, 1.0), "0.01"),
      with_default("settle_speed_rad_s", S::number(1e-4, 10.0), "0.05"),
      with_default("hold_s", S::number(0.0, 60.0), "0.2", "time held at a target once settled"),
      with_default("timeout_s", S::number(0.1, 600.0), "5", "longest time spent on one target"),
      required("targets", S::list(controller_target_schema(vocabulary), 1), "the target sequence"),
  });
}

void check_kind_sections(const YAML::Node& root, const std::string& kind,
                         const std::vector<std::string>& episode_only_keys, const std::string& file,
                         ValidationErrors& errors) {
  if (kind == "controller") {
    if (!root["controller"].IsDefined()) {
      errors.add(InputError("a scenario of kind controller needs a 'controller' section", "controller",
                            "controller: {targets: [...]}", location_of(root, file)));
    }
    for (const auto& key : episode_only_keys) {
      errors.add(InputError(fmt::format("'{}' belongs to episodes with children; controller scenarios drive the Nao "
                                        "alone (robot mode and gains go in 'controller')", key),
                            key, "remove it, or use kind: episode", location_of(root[key], file)));
    }
    if (root["condition"].IsDefined() && root["condition"].IsScalar() && root["condition"].Scalar() != "child-robot") {
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
    errors.add(InputError("missing required key 'condition'", "condition", "child-child, child-robot",
                          location_of(root, file)));
  }
}

std::vector<double> numbers_of(const YAML::Node& list) {
  std::vector<double> out;
  for (const auto& v : list) out.push_back(v.as<double>());
  return out;
}

ControllerSpec controller_from(const YAML::Node& node) {
  ControllerSpec c;
  c.mode = node["mode"].as<std::string>();
  c.speed_fraction = node["speed_fraction"].as<double>();
  c.torque_fraction = node["torque_fraction"].as<double>();
  c.trace_interval_steps = node["trace_interval_steps"].as<int>();
  c.settle_tolerance_m = node["settle_tolerance_m"].as<double>();
  c.settle_tolerance_rad = node["settle_tolerance_rad"].as<double>();
  c.settle_speed_rad_s = node["settle_speed_rad_s"].as<double>();
  c.hold_s = node["hold_s"].as<double>();
  c.timeout_s = node["timeout_s"].as<double>();
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

}  // namespace

std::shared_ptr<const Schema> scenario_schema(const ScenarioVocabulary& vocabulary) {
  const auto children = S::map({
      with_default("population", S::enumeration({"pinsoro", "pinsoro-cc", "pinsoro-cr"}), "pinsoro",
               "population the children are sampled from"),
      optional("purple", child_schema(), "explicit fields of the purple child's profile"),
      optional("yellow", child_schema(), "explicit fields of the yellow child's profile (child-child)"),
  });
  const auto robot = S::map({
      with_default("policy", S::enumeration(vocabulary.policies), "asocial", "play policy"),
      with_default("params", S::dictionary(S::any()), "{}", "policy parameters"),
      with_default("mode", S::enumeration({"kinematic", "dynamic"}), "kinematic", "robot simulation mode"),
      with_default("arm_reach_m", S::number(0.1, 1.0), "0.5", "arm reach for the reachable disc"),
  });
  const auto planner = S::map({
      with_default("name", S::enumeration(vocabulary.planners), "astar"),
      with_default("time_budget_s", S::number(0.001, 60.0), "1.0",
                   "wall-clock budget; only anytime planners (rrtstar, bitstar) use it up: keep it large so that "
                   "deterministic planners never hit it on a slow machine"),
      with_default("finger_speed_mps", S::number(0.005, 1.0), "0.05", "5 mm per 0.1 s in the real system"),
      with_default("reject_blocked_goals", S::boolean(), "false",
                   "refuse a goal whose cell lies inside other items' footprints; the real planner plans to any "
                   "point (the item then lands on the others and the physics pushes them apart)"),
  });
  const auto perception = S::map({
      with_default("face_detection_rate", S::number(0, 1), "0.98"),
      with_default("latency_s", S::number(0, 5), "0.1"),
      with_default("gaze_noise_deg", S::number(0, 90), "5"),
  });
  const auto protocol = S::map({
      with_default("greeting_s", S::number(0, 3600), "300", "about 5 min in the paper's protocol"),
      with_default("tutorial_s", S::number(0, 3600), "90", "1–2 min"),
      with_default("freeplay_cap_s", S::number(1, 4 * 3600), "2400"),
      with_default("debriefing_s", S::number(0, 3600), "120", "about 2 min"),
  });
  const auto camera = S::map({
      required("name", S::enumeration(vocabulary.cameras)),
      with_default("rate_hz", S::number(0.1, 60), "30"),
      with_default("width", S::integer(16, 4096), "960"),
      with_default("height", S::integer(16, 4096), "540"),
      with_default("depth", S::boolean(), "false"),
      with_default("video", S::boolean(), "false", "write videos/<episode>/<name>.mp4 (mp4v, fps = rate_hz)"),
  });
  const auto rendering = S::map({
      optional("backend", S::enumeration({"osmesa", "egl"}), "GL provider; default $MUJOCO_GL, else osmesa"),
      with_default("preset", S::enumeration({"fast", "pretty"}), "fast",
                   "fast: no MSAA/shadows/reflections/skybox; pretty: 4x MSAA, shadows, skybox"),
  });
  return S::map({
      required("name", S::string(), "short identifier"),
      with_default("description", S::string(), "\"\""),
      with_default("kind", S::enumeration({"episode", "controller"}), "episode",
                   "episode: a session with children; controller: the Nao alone through a target sequence"),
      optional("controller", controller_schema(vocabulary), "the target sequence (kind: controller only)"),
      optional("condition", S::enumeration({"child-child", "child-robot"}), "required for kind: episode"),
      with_default("episodes", S::integer(1, 1000000), "1"),
      with_default("seed", S::integer(0, std::numeric_limits<long long>::max()), "1"),
      with_default("children", children, "{}"),
      with_default("robot", robot, "{}"),
      with_default("planner", planner, "{}"),
      with_default("perception", perception, "{}"),
      with_default("protocol", protocol, "{}"),
      with_default("cameras", S::list(camera), "[]"),
      with_default("rendering", rendering, "{}", "how the cameras are rendered"),
      with_default("record",
                   S::one_of({S::boolean(),
                              S::map({with_default("bag", S::boolean(), "true", "write the ROS bag"),
                                      with_default("jpeg_quality", S::integer(1, 100), "90"),
                                      with_default("png_level", S::integer(0, 9), "3"),
                                      with_default("chunk_kb", S::integer(16, 1 << 20), "768"),
                                      with_default("compression", S::enumeration({"none", "lz4", "bz2"}), "none"),
                                      with_default("encoder_threads", S::integer(0, 64), "2",
                                                   "threads compressing camera images (0: the episode's thread)")})},
                             "true, false, or a map {bag: bool, jpeg_quality: 1–100, png_level: 0–9, "
                             "chunk_kb: 16–1048576, compression: none|lz4|bz2, encoder_threads: 0–64}"),
                   "false",
                   "true, or a map {bag, jpeg_quality, png_level, chunk_kb, compression, encoder_threads} "
                   "(docs/recording.md)"),
  });
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
  const std::string kind = root.IsMap() && root["kind"].IsScalar() ? root["kind"].Scalar() : "episode";
  if (root.IsMap()) check_kind_sections(root, kind, episode_only_keys, document.file, errors);
  std::string condition = root.IsMap() && root["condition"].IsScalar() ? root["condition"].Scalar() : "";
  if (kind == "controller") condition = "controller";  // the Nao alone on the child-robot stage
  if (errors.empty() && condition == "child-robot" && root["children"]["yellow"].IsDefined()) {
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
  if (errors.empty() && condition == "child-child") {
    for (std::size_t i = 0; i < root["cameras"].size(); ++i) {
      const YAML::Node name = root["cameras"][i]["name"];
      if (name.Scalar() == "CameraTop" || name.Scalar() == "CameraBottom") {
        errors.add(InputError(fmt::format("'{}' is a camera of the robot's head, absent in child-child scenarios",
                                          name.Scalar()),
                              fmt::format("cameras[{}].name", i), "camera_purple, camera_yellow, env_camera",
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
  if (kind == "controller") s.controller = controller_from(root["controller"]);
  s.condition = condition;
  s.episodes = root["episodes"].as<int>();
  s.seed = root["seed"].as<std::uint64_t>();
  s.population = root["children"]["population"].as<std::string>();
  s.purple = child_from(root["children"]["purple"]);
  s.yellow = child_from(root["children"]["yellow"]);
  s.policy = root["robot"]["policy"].as<std::string>();
  s.policy_params = root["robot"]["params"];
  s.robot_mode = root["robot"]["mode"].as<std::string>();
  s.arm_reach_m = root["robot"]["arm_reach_m"].as<double>();
  s.planner = root["planner"]["name"].as<std::string>();
  s.planner_budget_s = root["planner"]["time_budget_s"].as<double>();
  s.finger_speed_mps = root["planner"]["finger_speed_mps"].as<double>();
  s.reject_blocked_goals = root["planner"]["reject_blocked_goals"].as<bool>();
  s.face_detection_rate = root["perception"]["face_detection_rate"].as<double>();
  s.perception_latency_s = root["perception"]["latency_s"].as<double>();
  s.gaze_noise_deg = root["perception"]["gaze_noise_deg"].as<double>();
  s.protocol.greeting_s = root["protocol"]["greeting_s"].as<double>();
  s.protocol.tutorial_s = root["protocol"]["tutorial_s"].as<double>();
  s.protocol.freeplay_cap_s = root["protocol"]["freeplay_cap_s"].as<double>();
  s.protocol.debriefing_s = root["protocol"]["debriefing_s"].as<double>();
  for (const auto& c : root["cameras"]) {
    s.cameras.push_back({c["name"].as<std::string>(), c["rate_hz"].as<double>(), c["width"].as<int>(),
                         c["height"].as<int>(), c["depth"].as<bool>(), c["video"].as<bool>()});
  }
  if (root["rendering"]["backend"].IsDefined()) s.rendering.backend = root["rendering"]["backend"].as<std::string>();
  s.rendering.preset = root["rendering"]["preset"].as<std::string>();
  if (const auto& r = root["record"]; r.IsMap()) {
    s.record = r["bag"].as<bool>();
    s.recording = {r["jpeg_quality"].as<int>(), r["png_level"].as<int>(), r["chunk_kb"].as<int>(),
                   r["compression"].as<std::string>(), r["encoder_threads"].as<int>()};
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

}  // namespace freeplay::runner
