#include "freeplay/web/experiment.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <ctime>
#include <fstream>

#include "freeplay/core/error.hpp"

namespace freeplay::web {

ExperimentManager::ExperimentManager(std::filesystem::path path, scenario::Condition condition,
                                     std::int64_t created_unix_s, SessionLog& log)
    : path_(std::move(path)), log_(log) {
  const std::time_t created = created_unix_s;
  std::tm utc{};
  gmtime_r(&created, &utc);
  id_prefix_ = fmt::format("{:%Y-%m-%d-%H:%M}", utc);  // the supervisor's participant ids: YYYY-MM-DD-HH:MM-p1
  info_.header = fmt::format("{:%Y-%m-%d %H:%M:%S} UTC (freeplay serve --web)", utc);
  info_.condition = condition;
}

void ExperimentManager::freeplay_started(std::uint64_t unix_ns) {
  std::lock_guard lock(mutex_);
  info_.timestamp_ns = unix_ns;
  write();
}

void ExperimentManager::apply(const Command& command, double freeplay_t, double t) {
  std::lock_guard lock(mutex_);
  const auto& a = command.args;
  if (finalised_) throw CommandError(409, "the session is finalised: experiment.yaml is written");
  if (command.type == "condition") {
    agents::from_pinsoro_name(a["condition"].get<std::string>(), info_.condition);  // validated by parse_command
  } else if (command.type == "demographics") {
    const bool robot = info_.condition == agents::Condition::ChildRobot;
    const auto participant = [&](const nlohmann::json& c, const std::string& suffix) {
      return recording::Participant{id_prefix_ + "-" + suffix, c["age"].get<int>(), c["gender"].get<std::string>(),
                                    c["tablet_familiarity"].get<std::string>()};
    };
    if (robot && a.contains("yellow")) {
      throw CommandError(400, "command 'demographics': 'yellow' is not allowed in a child-robot session (the robot "
                              "takes the yellow place; allowed: purple)");
    }
    info_.purple = participant(a["purple"], robot ? "p2" : "p1");
    if (a.contains("yellow")) info_.yellow = participant(a["yellow"], "y1");
  } else if (command.type == "marker") {
    if (freeplay_t < 0.0) throw CommandError(409, "markers are timed from the start of free play, which has not started");
    info_.markers[freeplay_t] = a["kind"].get<std::string>();
    if (!a["text"].get<std::string>().empty()) info_.notes[fmt::format("{:.1f}", freeplay_t)] = a["text"].get<std::string>();
  } else if (command.type == "note") {
    auto& general = info_.notes["general"];
    if (!general.empty()) general += '\n';
    general += a["text"].get<std::string>();
  } else if (command.type == "likert") {
    info_.social_engagement = a["social_engagement"].get<int>();
  } else if (command.type == "finalise") {
    finalised_ = true;
  }
  auto data = a;
  if (freeplay_t >= 0.0) data["freeplay_t"] = freeplay_t;
  log_.add({t, "experiment", command.type, std::move(data)});
  write();
}

void ExperimentManager::write() const {
  const auto tmp = path_.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << recording::to_experiment_yaml(info_);
    if (!out) throw CommandError(500, fmt::format("cannot write {}", tmp));
  }
  std::filesystem::rename(tmp, path_);
}

nlohmann::json ExperimentManager::state() const {
  std::lock_guard lock(mutex_);
  const auto participant = [](const std::optional<recording::Participant>& p) -> nlohmann::json {
    if (!p) return nullptr;
    return {{"id", p->id}, {"age", p->age}, {"gender", p->gender}, {"tablet_familiarity", p->tablet_familiarity}};
  };
  nlohmann::json markers = nlohmann::json::array();
  for (const auto& [t, kind] : info_.markers) markers.push_back({{"t", t}, {"kind", kind}});
  return {{"condition", std::string(agents::pinsoro_name(info_.condition))},
          {"purple", participant(info_.purple)},
          {"yellow", participant(info_.yellow)},
          {"markers", markers},
          {"social_engagement", info_.social_engagement ? nlohmann::json(*info_.social_engagement) : nlohmann::json()},
          {"finalised", finalised_},
          {"file", path_.string()}};
}

}  // namespace freeplay::web
