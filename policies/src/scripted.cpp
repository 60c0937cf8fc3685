#include <fmt/format.h>

#include <algorithm>

#include "freeplay/core/error.hpp"
#include "freeplay/core/yaml_schema.hpp"
#include "freeplay/policies/play_policy.hpp"

namespace freeplay::policies {

namespace {

std::shared_ptr<const Schema> script_schema() {
  const auto point2 = Schema::list(Schema::number(-10, 10), 2, 2);
  const auto point3 = Schema::list(Schema::number(-10, 10), 3, 3);
  const auto action = Schema::map({
      required("t", Schema::number(0, 1e6), "seconds since the start of free play"),
      optional("move", Schema::map({required("item", Schema::string()), required("to", point2)})),
      optional("say", Schema::map({required("text", Schema::string()),
                                   with_default("to", Schema::enumeration({"purple", "yellow", "both"}), "both")})),
      optional("look_at", Schema::map({optional("child", Schema::enumeration({"purple", "yellow"})),
                                       optional("point", point3)})),
      optional("point_at", point2),
      optional("cancel", Schema::boolean()),
      optional("wait", Schema::number(0, 1e6)),
  });
  return Schema::map({
      optional("file", Schema::string(), "YAML file holding `actions:` (relative to the working folder)"),
      optional("actions", Schema::list(action), "timed actions"),
  });
}

struct TimedAction {
  double t;
  Action action;
};

}  // namespace

/// `scripted`: replays a timed action file, like a Wizard-of-Oz operator with a script.
class ScriptedPolicy final : public PlayPolicy {
 public:
  /// Parameters: `actions: [{t, move|say|look_at|point_at|cancel|wait}]` or `file: script.yaml`.
  explicit ScriptedPolicy(const YAML::Node& params) {
    YAML::Node node = params.IsDefined() && !params.IsNull() ? YAML::Clone(params) : YAML::Node(YAML::NodeType::Map);
    std::string file;
    if (node["file"].IsDefined() && !node["actions"].IsDefined()) {
      file = node["file"].as<std::string>();
      const auto doc = load_yaml_file(file);
      node["actions"] = doc.root["actions"];
    }
    ValidationErrors errors;
    script_schema()->validate(node, file.empty() ? "robot.params" : "", file, errors);
    errors.throw_if_any();
    if (!node["actions"].IsDefined()) {
      throw InputError("a scripted policy needs `actions:` or `file:`", "robot.params", "actions, file");
    }
    for (std::size_t i = 0; i < node["actions"].size(); ++i) {
      const auto a = node["actions"][i];
      const double t = a["t"].as<double>();
      int kinds = 0;
      if (a["move"]) {
        ++kinds;
        const auto to = a["move"]["to"];
        script_.push_back({t, MoveItem{a["move"]["item"].as<std::string>(), {to[0].as<double>(), to[1].as<double>()}}});
      }
      if (a["say"]) {
        ++kinds;
        const auto to = a["say"]["to"].as<std::string>();
        script_.push_back({t, Say{a["say"]["text"].as<std::string>(), to == "both" ? "" : to}});
      }
      if (a["look_at"]) {
        ++kinds;
        LookAt look;
        if (a["look_at"]["child"]) look.child = a["look_at"]["child"].as<std::string>();
        if (a["look_at"]["point"]) {
          const auto p = a["look_at"]["point"];
          look.point = Eigen::Vector3d(p[0].as<double>(), p[1].as<double>(), p[2].as<double>());
        }
        script_.push_back({t, look});
      }
      if (a["point_at"]) {
        ++kinds;
        script_.push_back({t, PointAt{{a["point_at"][0].as<double>(), a["point_at"][1].as<double>()}}});
      }
      if (a["cancel"] && a["cancel"].as<bool>()) {
        ++kinds;
        script_.push_back({t, CancelMove{}});
      }
      if (a["wait"]) {
        ++kinds;
        script_.push_back({t, Wait{a["wait"].as<double>()}});
      }
      if (kinds != 1) {
        throw InputError(fmt::format("action {} must have exactly one of move, say, look_at, point_at, cancel, wait",
                                     i),
                         fmt::format("robot.params.actions[{}]", i), "move, say, look_at, point_at, cancel, wait",
                         location_of(a, file));
      }
    }
    std::stable_sort(script_.begin(), script_.end(), [](const auto& x, const auto& y) { return x.t < y.t; });
  }
  std::string name() const override { return "scripted"; }
  void reset(const PolicyContext& /*context*/, Rng /*rng*/) override { next_ = 0; }
  std::vector<Action> decide(const Observation& observation) override {
    std::vector<Action> due;
    while (next_ < script_.size() && script_[next_].t <= observation.t) due.push_back(script_[next_++].action);
    return due;
  }

 private:
  std::vector<TimedAction> script_;
  std::size_t next_ = 0;
};

FREEPLAY_REGISTER_POLICY(ScriptedPolicy, "scripted", "replays a timed action file (a Wizard-of-Oz script)");

}  // namespace freeplay::policies
