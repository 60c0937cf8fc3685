#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/core/error.hpp"
#include "freeplay/core/settings_archive.hpp"
#include "freeplay/core/yaml_schema.hpp"
#include "freeplay/policies/play_policy.hpp"

namespace freeplay::policies {

namespace {

constexpr double kMinimumPeriodS = 0.1;  // the decision tick: a shorter period would repeat within one tick
constexpr const char* kActionKinds = "move, say, look_at, point_at, cancel, wait";  // the keys of ScriptEntry's kinds

/// A point on the screen (m, `sandtray`), as a script writes it: `[x, y]`.
std::shared_ptr<const Schema> screen_point_schema() { return Schema::list(Schema::number(-10, 10), 2, 2); }

/// `move:` of a script entry.
struct ScriptMove {
  std::string item;           ///< item name
  std::array<double, 2> to{};  ///< goal point

  /// The keys of `move:`.
  template <typename Archive>
  void visit(Archive& a) {
    a.required("item", item, Schema::string(), "item to move");
    a.required("to", to, screen_point_schema(), "goal point [x, y] (m, sandtray)");
  }
};

/// `say:` of a script entry.
struct ScriptSay {
  std::string text;         ///< utterance
  std::string to = "both";  ///< addressee: purple, yellow or both

  /// The keys of `say:`.
  template <typename Archive>
  void visit(Archive& a) {
    a.required("text", text, Schema::string(), "utterance");
    a.field("to", to, Schema::enumeration({"purple", "yellow", "both"}), "addressee");
  }
};

/// `look_at:` of a script entry (a child's face or a point; neither: the robot's current gaze target).
struct ScriptLookAt {
  std::optional<std::string> child;           ///< purple or yellow
  std::optional<std::array<double, 3>> point;  ///< a 3-D point in `sandtray`

  /// The keys of `look_at:`.
  template <typename Archive>
  void visit(Archive& a) {
    a.optional("child", child, Schema::enumeration({"purple", "yellow"}), "look at this child's face");
    a.optional("point", point, Schema::list(Schema::number(-10, 10), 3, 3), "look at [x, y, z] (m, sandtray)");
  }
};

/// One entry of `actions:`: its time, its repetition and exactly one action kind (checked after reading).
struct ScriptEntry {
  double t = 0.0;                                ///< free-play second of the (first) occurrence
  std::optional<double> every;                   ///< repetition period (s)
  std::optional<double> until;                   ///< last free-play second of a repetition
  std::optional<ScriptMove> move;                ///< move an item
  std::optional<ScriptSay> say;                  ///< say something
  std::optional<ScriptLookAt> look_at;           ///< look at a child or a point
  std::optional<std::array<double, 2>> point_at;  ///< point at a screen point
  std::optional<bool> cancel;                    ///< cancel the running move (when true)
  std::optional<double> wait;                    ///< wait this many seconds

  /// The keys of one script entry.
  template <typename Archive>
  void visit(Archive& a) {
    a.required("t", t, Schema::number(0, 1e6), "seconds since the start of free play");
    a.optional("every", every, Schema::number(kMinimumPeriodS, 1e6),
               "repeat the action every this many seconds from `t` (at least one 0.1 s decision tick)");
    a.optional("until", until, Schema::number(0, 1e6), "last free-play second of a repeated action (default: no end)");
    a.optional("move", move, settings_schema<ScriptMove>(), "move an item");
    a.optional("say", say, settings_schema<ScriptSay>(), "say something");
    a.optional("look_at", look_at, settings_schema<ScriptLookAt>(), "look at a child's face or a point");
    a.optional("point_at", point_at, screen_point_schema(), "point at [x, y] (m, sandtray) with the right arm");
    a.optional("cancel", cancel, Schema::boolean(), "true: cancel the running move");
    a.optional("wait", wait, Schema::number(0, 1e6), "do nothing new for this many seconds");
  }
};

/// The scripted policy's `robot.params`: the script itself or the file that holds it.
struct ScriptParams {
  std::optional<std::string> file;                 ///< YAML file holding `actions:`
  std::optional<std::vector<ScriptEntry>> actions;  ///< the timed actions

  /// The keys of the scripted policy's `robot.params`.
  template <typename Archive>
  void visit(Archive& a) {
    a.optional("file", file, Schema::string(), "YAML file holding `actions:` (relative to the working folder)");
    a.optional("actions", actions, Schema::list(settings_schema<ScriptEntry>()), "timed actions");
  }
};

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

/// `scripted`: replays a timed action file, like a Wizard-of-Oz operator with a script.
class ScriptedPolicy final : public PlayPolicy {
 public:
  /// Parameters: ScriptParams, `actions: [{t, move|say|look_at|point_at|cancel|wait, every?, until?}]` or
  /// `file: script.yaml` (a file holding `actions:`, whose problems are named at their place in that file).
  explicit ScriptedPolicy(const YAML::Node& params) {
    YAML::Node node = params.IsDefined() && !params.IsNull() ? YAML::Clone(params) : YAML::Node(YAML::NodeType::Map);
    std::string file;
    if (node.IsMap() && node["file"].IsScalar() && !node["actions"].IsDefined()) {
      file = node["file"].Scalar();
      const auto doc = load_yaml_file(file);
      if (!doc.root.IsMap() || !doc.root["actions"].IsDefined()) {
        throw InputError("a script file needs `actions:`", "actions", "a list of timed actions",
                         location_of(doc.root, file));
      }
      node["actions"] = doc.root["actions"];  // the file's own nodes: their marks name positions in `file`
    }
    ValidationErrors errors;
    settings_schema<ScriptParams>()->validate(node, file.empty() ? "robot.params" : "", file, errors);
    errors.throw_if_any();
    const auto script = read_settings<ScriptParams>(node);
    if (!script.actions) {
      throw InputError("a scripted policy needs `actions:` or `file:`", "robot.params", "actions, file");
    }
    const YAML::Node& validated = node;
    for (std::size_t i = 0; i < script.actions->size(); ++i) {
      script_.push_back(timed_action((*script.actions)[i], i, validated["actions"][i], file));
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
  /// Script entry `index` as a TimedAction: exactly one action kind, and `until` only with `every` and not before
  /// `t` (`at` is its node, for the position of a problem).
  static TimedAction timed_action(const ScriptEntry& e, std::size_t index, const YAML::Node& at,
                                  const std::string& file) {
    std::vector<Action> kinds;
    if (e.move) kinds.push_back(MoveItem{e.move->item, {e.move->to[0], e.move->to[1]}});
    if (e.say) kinds.push_back(Say{e.say->text, e.say->to == "both" ? "" : e.say->to});
    if (e.look_at) {
      LookAt look;
      look.child = e.look_at->child;
      if (const auto& p = e.look_at->point) look.point = Eigen::Vector3d((*p)[0], (*p)[1], (*p)[2]);
      kinds.push_back(look);
    }
    if (e.point_at) kinds.push_back(PointAt{{(*e.point_at)[0], (*e.point_at)[1]}});
    if (e.cancel.value_or(false)) kinds.push_back(CancelMove{});
    if (e.wait) kinds.push_back(Wait{*e.wait});
    if (kinds.size() != 1) {
      throw InputError(fmt::format("action {} must have exactly one of {}", index, kActionKinds),
                       fmt::format("robot.params.actions[{}]", index), kActionKinds, location_of(at, file));
    }
    TimedAction entry{e.t, kinds.front()};
    entry.every = e.every.value_or(0.0);
    if (!e.until) return entry;
    const auto key = fmt::format("robot.params.actions[{}].until", index);
    if (!e.every) {
      throw InputError("`until` ends a repetition: it needs `every`", key, "until together with every",
                       location_of(at["until"], file));
    }
    entry.until = *e.until;
    if (entry.until < entry.t) {
      throw InputError(fmt::format("until {} lies before the first time t = {}", entry.until, entry.t), key,
                       fmt::format("a number ≥ t ({})", entry.t), location_of(at["until"], file));
    }
    return entry;
  }

  /// Free-play time of the next occurrence of entry `index` (t + n · every, computed without accumulating error).
  double occurrence_time(std::size_t index) const {
    return script_[index].t + static_cast<double>(progress_[index].fired) * script_[index].every;
  }

  std::vector<TimedAction> script_;
  std::vector<EntryProgress> progress_;
};

}  // namespace

FREEPLAY_REGISTER_POLICY(ScriptedPolicy, "scripted", "replays a timed action file (a Wizard-of-Oz script)");

}  // namespace freeplay::policies
