// `yoked`: the yoked control of contingency research. Against the child of episode k it replays the robot actions
// (content and free-play time) that another run's policy took in its episode (k + offset) mod N, read from that
// run's event logs: the robot is as active, but nothing it does depends on this child. The offset defaults to 1
// because runs with the same seed have the same children: replaying a child's own session to the same
// deterministic child reproduces that session exactly (offset 0), contingency included. docs/validity.md.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <nlohmann/json.hpp>

#include "freeplay/core/error.hpp"
#include "freeplay/core/settings_archive.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/policies/yoked.hpp"

namespace freeplay::policies {

namespace {

namespace fs = std::filesystem;

constexpr double kTickToleranceS = 1e-6;  // a logged action at free-play t is due at the tick of the same t
constexpr const char* kEpisodesFile = "episodes.jsonl";
constexpr const char* kEventLogHint =
    "a run folder with plain event logs: run the source with `--events all` (a gz log: `gunzip -k events/*.gz`)";

/// The yoked policy's `robot.params`.
struct YokedParams {
  std::string from;                    ///< run folder of the source run
  std::optional<std::string> variant;  ///< variant of the source run (needed when it holds several)
  int episode_offset = 1;              ///< episode k replays source episode (k + offset) mod N

  /// The keys of the yoked policy's `robot.params`.
  template <typename Archive>
  void visit(Archive& a) {
    a.required("from", from, Schema::string(), "run folder of the source run (relative to the working folder)");
    a.optional("variant", variant, Schema::string(), "variant of the source run (required when it holds several)");
    a.field("episode_offset", episode_offset, Schema::integer(0, 1000000),
            "episode k replays source episode (k + offset) mod N: another child's session (0: the same "
            "child's, which reproduces the source exactly)");
  }
};

/// The episodes of a source run folder: per variant, each episode's file id (`<variant>-<index>`) by index.
struct SourceRun {
  std::map<std::string, std::vector<std::string>> episode_ids;  // variant → episode file id by index ("" if missing)

  /// The variant names, comma-separated.
  std::string variant_list() const {
    std::vector<std::string> names;
    for (const auto& [name, ids] : episode_ids) names.push_back(name);
    return fmt::format("{}", fmt::join(names, ", "));
  }
};

/// Reads `dir`/episodes.jsonl into a SourceRun (a torn last line, from an interrupted run, is skipped).
SourceRun read_source_run(const fs::path& dir) {
  SourceRun run;
  std::ifstream in(dir / kEpisodesFile);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto record = nlohmann::json::parse(line, nullptr, false);
    if (record.is_discarded() || !record.is_object()) continue;
    const int index = record.value("episode", -1);
    const auto id = record.value("episode_id", std::string{});
    if (index < 0 || id.empty()) continue;
    auto& ids = run.episode_ids[record.value("variant", std::string{})];
    if (static_cast<std::size_t>(index) >= ids.size()) ids.resize(static_cast<std::size_t>(index) + 1);
    ids[static_cast<std::size_t>(index)] = id;
  }
  return run;
}

/// The source run of `dir`, read once per process and state of its episodes.jsonl (a policy is made per episode).
std::shared_ptr<const SourceRun> source_run(const fs::path& dir) {
  static std::mutex mutex;
  static std::map<std::string, std::pair<std::string, std::shared_ptr<const SourceRun>>> cache;
  const auto file = dir / kEpisodesFile;
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  const auto stamp = fs::last_write_time(file, ec).time_since_epoch().count();
  const auto version = fmt::format("{}:{}", size, stamp);
  const auto key = fs::absolute(dir).lexically_normal().string();
  std::lock_guard lock(mutex);
  auto& entry = cache[key];
  if (!entry.second || entry.first != version) entry = {version, std::make_shared<const SourceRun>(read_source_run(dir))};
  return entry.second;
}

/// The robot action of one logged robot event, or nullopt for events that are outcomes, not actions.
std::optional<Action> action_of(const std::string& type, const nlohmann::json& data) {
  if (type == "say") return Say{data.at("text").get<std::string>(), data.value("to", std::string{})};
  if (type == "move_goal") {
    return MoveItem{data.at("item").get<std::string>(), {data.at("x").get<double>(), data.at("y").get<double>()}};
  }
  if (type == "look_at") {
    LookAt look;
    if (data.contains("child")) {
      look.child = data.at("child").get<std::string>();
    } else {
      look.point = Eigen::Vector3d(data.at("x").get<double>(), data.at("y").get<double>(), data.at("z").get<double>());
    }
    return look;
  }
  if (type == "point_at") return PointAt{{data.at("x").get<double>(), data.at("y").get<double>()}};
  if (type == "cancel") return CancelMove{};
  return std::nullopt;  // move_result and any later outcome event
}

}  // namespace

std::vector<std::pair<double, Action>> read_robot_actions(const std::filesystem::path& event_log) {
  std::ifstream in(event_log);
  if (!in) throw InputError("cannot read the event log", "robot.params.from", kEventLogHint, {event_log.string(), 0, 0});
  std::vector<std::pair<double, Action>> actions;
  std::optional<double> freeplay_start;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    // Cheap filter first: only the stage events and the robot's events matter (the children's are most lines).
    const bool robot = line.find("\"source\":\"robot\"") != std::string::npos;
    if (!robot && line.find("\"type\":\"stage\"") == std::string::npos) continue;
    try {
      const auto event = nlohmann::json::parse(line);
      const auto type = event.at("type").get<std::string>();
      const double t = event.at("t").get<double>();
      if (type == "stage" && event.at("source") == "protocol") {
        const auto stage = event.at("data").value("stage", std::string{});
        if (stage == "freeplay") freeplay_start = t;
        if (stage == "debriefing") break;
        continue;
      }
      if (!freeplay_start || event.at("source") != "robot") continue;  // the greeting is every robot's own
      if (auto action = action_of(type, event.value("data", nlohmann::json::object()))) {
        actions.emplace_back(t - *freeplay_start, std::move(*action));
      }
    } catch (const nlohmann::json::exception& e) {
      throw InputError(fmt::format("not an event of a freeplay event log: {}", e.what()), "robot.params.from",
                       "a run folder written by `freeplay run`", {event_log.string(), line_number, 1});
    }
  }
  if (!freeplay_start) {
    throw InputError("the event log has no free-play stage", "robot.params.from",
                     "the event log of a child-robot episode", {event_log.string(), 0, 0});
  }
  return actions;
}

namespace {

/// `yoked`: replays the robot actions of episode k of another run against the child of episode k.
class YokedPolicy final : public PlayPolicy {
 public:
  /// Parameters: YokedParams (`from: RUN_DIR`, `variant: NAME` when that run holds several, `episode_offset`).
  explicit YokedPolicy(const YAML::Node& params)
      : params_(read_unvalidated_settings<YokedParams>(params, "robot.params")), from_(params_.from) {
    if (!fs::is_regular_file(from_ / kEpisodesFile)) {
      throw InputError(fmt::format("'{}' is not a run folder (it has no {})", from_.string(), kEpisodesFile),
                       "robot.params.from", "the folder of a finished `freeplay run` of a child-robot scenario");
    }
    source_ = source_run(from_);
    if (source_->episode_ids.empty()) {
      throw InputError(fmt::format("the run folder '{}' holds no finished episode", from_.string()),
                       "robot.params.from", "a run with finished episodes");
    }
    if (params_.variant) {
      variant_ = *params_.variant;
      if (!source_->episode_ids.contains(variant_)) {
        throw InputError(fmt::format("the run folder '{}' has no variant '{}'", from_.string(), variant_),
                         "robot.params.variant", source_->variant_list());
      }
    } else if (source_->episode_ids.size() > 1) {
      throw InputError(fmt::format("the run folder '{}' holds several variants: name the one to replay",
                                   from_.string()),
                       "robot.params.variant", source_->variant_list());
    } else {
      variant_ = source_->episode_ids.begin()->first;
    }
  }

  std::string name() const override { return "yoked"; }

  /// Loads the source's robot actions of the episode yoked to `context.episode_index`.
  void reset(const PolicyContext& context, Rng /*rng*/) override {
    actions_ = read_robot_actions(event_log(source_episode(context.episode_index)));
    next_ = 0;
  }

  /// The recorded actions due by `observation.t`; after the source episode's last action, nothing more.
  std::vector<Action> decide(const Observation& observation) override {
    std::vector<Action> due;
    while (next_ < actions_.size() && actions_[next_].first <= observation.t + kTickToleranceS) {
      due.push_back(actions_[next_++].second);
    }
    return due;
  }

  /// Every episode 0 … episodes − 1 needs its own finished source episode with a plain event log.
  void check_run(int episodes) const override {
    const auto available = static_cast<int>(source_->episode_ids.at(variant_).size());
    if (episodes > available) {
      throw InputError(fmt::format("the source run '{}' [{}] holds {} episodes, this run has {}: each yoked episode "
                                   "replays its own source episode",
                                   from_.string(), variant_, available, episodes),
                       "robot.params.from", fmt::format("a source run with at least {} episodes, or at most {} "
                                                        "episodes in this run", episodes, available));
    }
    for (int k = 0; k < episodes; ++k) event_log(source_episode(k));
  }

 private:
  /// The source episode replayed in episode `index`: (index + offset) mod the source's episode count.
  int source_episode(int index) const {
    const auto available = static_cast<long>(source_->episode_ids.at(variant_).size());
    return static_cast<int>((static_cast<long>(index) + params_.episode_offset) % available);
  }

  /// The event log of source episode `index`; InputError naming what is missing.
  fs::path event_log(int index) const {
    const auto& ids = source_->episode_ids.at(variant_);
    if (index < 0 || static_cast<std::size_t>(index) >= ids.size() || ids[static_cast<std::size_t>(index)].empty()) {
      throw InputError(fmt::format("the source run '{}' [{}] has no finished episode {} (it holds {}): yoked episode k "
                                   "replays source episode (k + episode_offset) mod the source's episode count",
                                   from_.string(), variant_, index, ids.size()),
                       "robot.params.from", fmt::format("a source run with at least {} episodes, or fewer episodes "
                                                        "in this run", index + 1));
    }
    const auto path = from_ / "events" / (ids[static_cast<std::size_t>(index)] + ".jsonl");
    if (fs::is_regular_file(path)) return path;
    const bool gz = fs::is_regular_file(path.string() + ".gz");
    throw InputError(gz ? fmt::format("the source run keeps gzip-compressed event logs ({}.gz)", path.string())
                        : fmt::format("the source run has no event log {} (it ran with `--events none`, or `auto` "
                                      "above 1000 episodes)",
                                      path.string()),
                     "robot.params.from", kEventLogHint);
  }

  YokedParams params_;
  fs::path from_;  // params_.from
  std::string variant_;
  std::shared_ptr<const SourceRun> source_;
  std::vector<std::pair<double, Action>> actions_;  // free-play time → action, in log order
  std::size_t next_ = 0;
};

}  // namespace

FREEPLAY_REGISTER_POLICY(YokedPolicy, "yoked",
                         "replays another run's robot actions, each episode those of another child (yoked control)");

}  // namespace freeplay::policies
