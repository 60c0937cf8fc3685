#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "freeplay/core/error.hpp"
#include "freeplay/core/yaml_schema.hpp"
#include "freeplay/policies/play_policy.hpp"

namespace freeplay::policies {

namespace {

constexpr double kMinimumPeriodS = 0.1;  // the decision tick: a shorter period would repeat within one tick

std::shared_ptr<const Schema> script_schema() {
  const auto point2 = Schema::list(Schema::number(-10, 10), 2, 2);
  const auto point3 = Schema::list(Schema::number(-10, 10), 3, 3);
  const auto action = Schema::map({
      required("t", Schema::number(0, 1e6), "seconds since the start of free play"),
      optional("every", Schema::number(kMinimumPeriodS, 1e6),
               "repeat the action every this many seconds from `t` (at least one 0.1 s decision tick)"),
      optional("until", Schema::number(0, 1e6), "last free-play second of a repeated action (default: no end)"),
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

/// One script entry: an action at free-play time `t`, repeated every `every` seconds up to `until` when `every` > 0.
struct TimedAction {
  double t;
  Action action;
  double every = 0.0;                                        // 0: once
  double until = std::numeric_limits<double>::infinity();   // last time a repetition may start
};

/// Where a script entry stands: the number of times it has fired.
struct EntryProgress {
  long fired = 0;
  bool done = false;
};

}  // namespace

/// `scripted`: replays a timed action file, like a Wizard-of-Oz operator with a script.
class ScriptedPolicy final : public PlayPolicy {
 public:
  /// Parameters: `actions: [{t, move|say|look_at|point_at|cancel|wait, every?, until?}]` or `file: script.yaml`.
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
      read_repetition(a, i, file, script_.back());
    }
    std::stable_sort(script_.begin(), script_.end(), [](const auto& x, const auto& y) { return x.t < y.t; });
  }
  std::string name() const override { return "scripted"; }
  void reset(const PolicyContext& /*context*/, Rng /*rng*/) override {
    progress_.assign(script_.size(), EntryProgress{});
  }
  /// The actions due by `observation.t`, in time order (entries due at the same time in script order).
  std::vector<Action> decide(const Observation& observation) override {
    progress_.resize(script_.size());
    std::vector<Action> due;
    while (true) {
      std::size_t earliest = script_.size();
      double earliest_t = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < script_.size(); ++i) {
        if (progress_[i].done) continue;
        const double t = occurrence_time(i);
        if (t <= observation.t && t < earliest_t) {
          earliest = i;
          earliest_t = t;
        }
      }
      if (earliest == script_.size()) return due;
      due.push_back(script_[earliest].action);
      auto& p = progress_[earliest];
      ++p.fired;
      p.done = script_[earliest].every <= 0.0 || occurrence_time(earliest) > script_[earliest].until;
    }
  }

 private:
  /// Reads `every` and `until` of action `index` into `entry` (the schema checked their ranges).
  static void read_repetition(const YAML::Node& a, std::size_t index, const std::string& file, TimedAction& entry) {
    if (a["every"]) entry.every = a["every"].as<double>();
    if (!a["until"]) return;
    const auto key = fmt::format("robot.params.actions[{}].until", index);
    if (!a["every"]) {
      throw InputError("`until` ends a repetition: it needs `every`", key, "until together with every",
                       location_of(a["until"], file));
    }
    entry.until = a["until"].as<double>();
    if (entry.until < entry.t) {
      throw InputError(fmt::format("until {} lies before the first time t = {}", entry.until, entry.t), key,
                       fmt::format("a number ≥ t ({})", entry.t), location_of(a["until"], file));
    }
  }

  /// Free-play time of the next occurrence of entry `index` (t + n · every, computed without accumulating error).
  double occurrence_time(std::size_t index) const {
    return script_[index].t + static_cast<double>(progress_[index].fired) * script_[index].every;
  }

  std::vector<TimedAction> script_;
  std::vector<EntryProgress> progress_;
};

FREEPLAY_REGISTER_POLICY(ScriptedPolicy, "scripted", "replays a timed action file (a Wizard-of-Oz script)");

}  // namespace freeplay::policies
