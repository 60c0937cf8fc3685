#include "freeplay/recording/child_replay.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>
#include <optional>

#include "freeplay/agents/condition.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/yaml_schema.hpp"
#include "freeplay/recording/bag_recorder.hpp"
#include "freeplay/recording/publishers.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::recording {

namespace {

// The inverse of the episode's event vocabulary (agents/perception.hpp), with an error naming the field.
template <class E>
E parse_name(const std::optional<E>& value, const std::string& name, const char* what) {
  if (value) return *value;
  throw InputError(fmt::format("unknown {} '{}' in the recorded events", what, name), what,
                   "a bag written by this version of freeplay-sim");
}

// The condition of a recorded scenario document (validated when recorded, so its `condition:` is always there).
agents::Condition recorded_condition(const YAML::Node& scenario) {
  const std::string name = scenario["condition"] ? scenario["condition"].as<std::string>() : "";
  agents::Condition condition{};
  return parse_name(from_string(name, condition) ? std::optional(condition) : std::nullopt, name, "condition");
}

struct Finger {
  bool down = false;
  Vec2 position = Vec2::Zero();
};

// A child's head frame on /tf: where it is and which way it looks.
struct HeadRay {
  Eigen::Vector3d head = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
};

int finger_offset(const std::string& seat) { return seat == "yellow" ? agents::kFingersPerChild : 0; }

void push(agents::ChildActions& a, const agents::TouchCommand& command) {
  if (a.touch_count < static_cast<int>(a.touches.size())) a.push_touch(command);
}

}  // namespace

RecordedChildren read_recorded_children(const std::filesystem::path& session) {
  RecordedChildren out;
  Bag bag;
  out.bag = open_session_bag(session, bag);
  std::vector<Event> child_events;
  std::optional<double> freeplay_start;
  std::optional<double> duration;
  std::map<long, std::map<int, Vec2>> touches;          // snapshot's tick (publication_tick) → finger → position
  std::map<long, std::map<std::string, HeadRay>> heads;  // snapshot's tick → seat → head ray
  rosbag::View view(bag.get(), rosbag::TopicQuery(std::vector<std::string>{topics::kScenario, topics::kEpisode,
                                                                     topics::kEvents, topics::kTf}));
  for (const auto& m : view) try {
    const auto topic = m.getTopic();
    if (topic == topics::kScenario) {
      out.scenario_yaml = std_string(read_message<msg::String>(m)->data);
    } else if (topic == topics::kEpisode) {
      const auto json = nlohmann::json::parse(std_string(read_message<msg::String>(m)->data));
      out.episode_id = json.value("id", "");
      out.seed = json.value("seed", std::uint64_t{0});
    } else if (topic == topics::kEvents) {
      const auto json = nlohmann::json::parse(std_string(read_message<msg::String>(m)->data));
      Event e{json.at("t").get<double>(), json.at("source").get<std::string>(), json.at("type").get<std::string>(),
              json.value("data", nlohmann::json())};
      const auto* stage = e.get<events::Stage>();
      if (stage && e.source == "protocol" && stage->stage == "freeplay") freeplay_start = e.t;
      if (const auto* ended = e.get<events::FreeplayEnded>(); ended && e.source == "protocol") {
        duration = ended->duration_s;
        out.ended_by = ended->ended_by;
      }
      if (e.source.rfind("child.", 0) == 0) child_events.push_back(std::move(e));
    } else if (topic == topics::kTf) {
      const auto tf = read_message<msg::TFMessage>(m);  // keeps the message alive
      for (const auto& x : tf->transforms) {
        const auto child = std_string(x.child_frame_id);
        const long stamp = publication_tick(sandtray_time(x.header.stamp));
        const Eigen::Vector3d xyz(x.transform.translation.x, x.transform.translation.y, x.transform.translation.z);
        if (child.rfind("touch", 0) == 0 && std_string(x.header.frame_id) == "sandtray") {
          touches[stamp][std::stoi(child.substr(5))] = xyz.head<2>();
        } else if (child.rfind("child_", 0) == 0 && child.size() > 8 && child.substr(child.size() - 2) == "_0") {
          const Eigen::Quaterniond q(x.transform.rotation.w, x.transform.rotation.x, x.transform.rotation.y,
                                     x.transform.rotation.z);
          heads[stamp][child.substr(6, child.size() - 8)] = {xyz, q * Eigen::Vector3d::UnitX()};
        }
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("'{}': a malformed {} message at {:.3f} s: {}", out.bag.string(), m.getTopic(),
                                 sandtray_time(m.getTime()), e.what()),
                     "SESSION_DIR", "a session recorded by freeplay-sim");
  }
  const auto where = out.bag.string();
  if (out.scenario_yaml.empty()) {
    throw InputError(fmt::format("'{}' has no /freeplay/scenario (recorded by an older freeplay-sim?)", where),
                     "SESSION_DIR", "a session recorded by this version (`freeplay run --record`): record it again");
  }
  if (!freeplay_start) {
    throw InputError(fmt::format("'{}' has no free play (no `stage: freeplay` event)", where), "SESSION_DIR",
                     "a recording that reached free play");
  }
  if (!duration) {
    throw InputError(fmt::format("'{}' is incomplete: free play did not end in the recording", where), "SESSION_DIR",
                     "a complete recording (the episode was interrupted)");
  }
  out.freeplay_duration_s = *duration;
  const auto scenario = YAML::Load(out.scenario_yaml);
  out.seats = {"purple"};
  if (recorded_condition(scenario) == agents::Condition::ChildChild) out.seats.push_back("yellow");

  const double t0 = *freeplay_start;
  const auto tick_of = [&](double t) { return std::lround((t - t0) / kPublishTickS); };
  // Snapshots are stamped after the tick's step: the state after free-play tick k is about t0 + (k + 1) × 0.1.
  const long first_tick = publication_tick(t0);
  std::map<long, std::map<int, Vec2>> touches_after;
  for (auto& [tick, fingers] : touches) touches_after[tick - first_tick - 1] = std::move(fingers);
  std::map<long, std::map<std::string, HeadRay>> heads_after;
  for (auto& [tick, seats] : heads) heads_after[tick - first_tick - 1] = std::move(seats);
  std::map<std::pair<std::string, long>, std::vector<const Event*>> events_at;
  for (const auto& e : child_events) events_at[{e.source.substr(6), tick_of(e.t)}].push_back(&e);

  const long ticks = std::lround(*duration / kPublishTickS);
  for (const auto& seat : out.seats) {
    std::array<Finger, agents::kFingersPerChild + 1> fingers{};
    const int offset = finger_offset(seat);
    agents::GazeTarget gaze;
    bool quit = false;
    auto& actions = out.actions[seat];
    for (long k = 0; k < ticks; ++k) {
      agents::ChildActions a;
      if (const auto it = events_at.find({seat, k}); it != events_at.end()) {
        for (const Event* e : it->second) {
          const auto d = e->data();
          if (e->type() == "touch_down") {
            const int local = d.at("finger").get<int>() - offset;
            if (local < 1 || local > agents::kFingersPerChild) continue;
            const Vec2 p(d.at("x").get<double>(), d.at("y").get<double>());
            push(a, {local, agents::TouchPhase::Down, p});
            fingers[static_cast<std::size_t>(local)] = {true, p};
          } else if (e->type() == "touch_missed") {  // an off-screen press: the event does not name the finger
            int local = 1;
            while (local < agents::kFingersPerChild && fingers[static_cast<std::size_t>(local)].down) ++local;
            push(a, {local, agents::TouchPhase::Down, Vec2(d.at("x").get<double>(), d.at("y").get<double>())});
            fingers[static_cast<std::size_t>(local)].down = false;
          } else if (e->type() == "touch_up") {
            const int local = d.at("finger").get<int>() - offset;
            if (local < 1 || local > agents::kFingersPerChild) continue;
            push(a, {local, agents::TouchPhase::Up, Vec2::Zero()});
            fingers[static_cast<std::size_t>(local)].down = false;
          } else if (e->type() == "palette") {
            a.select_colour = sim::palette_from_name(d.value("colour", ""));
          } else if (e->type() == "speech") {
            agents::SpeechEvent speech;
            speech.kind = parse_name(agents::parse_utterance(d.value("kind", "")), d.value("kind", ""), "speech.kind");
            speech.to = parse_name(agents::parse_addressee(d.value("to", "")), d.value("to", ""), "speech.to");
            speech.duration_s = d.value("duration_s", 0.0);
            speech.syllables = d.value("syllables", 0);
            a.speech = speech;
          } else if (e->type() == "gaze") {
            gaze.kind = parse_name(agents::parse_gaze_kind(d.value("target", "")), d.value("target", ""), "gaze.target");
            gaze.item = d.contains("item") ? agents::item_index(d["item"].get<std::string>()) : -1;
          } else if (e->type() == "wants_to_stop") {
            quit = true;
          }
        }
      }
      // Drags: the /tf touch point after the tick differs from where the finger was.
      if (const auto it = touches_after.find(k); it != touches_after.end()) {
        for (int local = 1; local <= agents::kFingersPerChild; ++local) {
          auto& finger = fingers[static_cast<std::size_t>(local)];
          const auto seen = it->second.find(offset + local);
          if (!finger.down || seen == it->second.end() || seen->second == finger.position) continue;
          push(a, {local, agents::TouchPhase::Move, seen->second});
          finger.position = seen->second;
        }
      }
      // Gaze points on the screen: the head ray of /tf meets the table (z = 0).
      if (gaze.kind == agents::GazeKind::Tray || gaze.kind == agents::GazeKind::Item) {
        if (const auto it = heads_after.find(k); it != heads_after.end()) {
          if (const auto ray = it->second.find(seat); ray != it->second.end() && ray->second.direction.z() < -1e-12) {
            const auto& r = ray->second;
            gaze.point = (r.head + r.direction * (-r.head.z() / r.direction.z())).head<2>();
          }
        }
      }
      a.gaze = gaze;
      a.quit = quit;
      actions[k] = a;
    }
  }
  return out;
}

agents::ChildActions ReplayedChildren::actions(const std::string& seat, double t, double dt) {
  agents::ChildActions none;
  none.quit = true;  // past the recording (or a seat it does not have): the child has stopped
  const auto by_seat = recording_.actions.find(seat);
  if (by_seat == recording_.actions.end()) return none;
  const auto it = by_seat->second.find(std::lround(t / dt));
  return it != by_seat->second.end() ? it->second : none;
}

scenario::Scenario replay_scenario(const RecordedChildren& recording, const std::string& policy,
                                 const scenario::ScenarioVocabulary& vocabulary) {
  auto root = YAML::Load(recording.scenario_yaml);
  const bool child_robot = recorded_condition(root) == agents::Condition::ChildRobot;
  if (!policy.empty()) {
    if (!child_robot) {
      throw InputError(fmt::format("'{}' is a child-child session: there is no robot policy to change",
                                   recording.bag.string()),
                       "--policy", "a child-robot session, or no --policy");
    }
    if (root["robot"]["policy"].as<std::string>() != policy) {
      root["robot"]["policy"] = policy;
      root["robot"]["params"] = YAML::Node(YAML::NodeType::Map);
    }
  }
  root["episodes"] = 1;
  root["protocol"]["freeplay_cap_s"] = std::max(1.0, recording.freeplay_duration_s);
  root["record"] = false;
  root["cameras"] = YAML::Node(YAML::NodeType::Sequence);
  YAML::Emitter text;
  text.SetDoublePrecision(17);
  text << root;
  return scenario::scenario_from_document(parse_yaml(text.c_str(), recording.bag.string() + "#/freeplay/scenario"), {},
                                        vocabulary);
}

runner::EpisodeResult replay_children(const RecordedChildren& recording, const scenario::Scenario& scenario,
                                      const runner::SharedModels& models) {
  ReplayedChildren source(recording);
  auto result = runner::run_episode({.scenario = scenario,
                                     .seed = recording.seed,
                                     .models = models,
                                     .id = recording.episode_id,
                                     .children = &source});
  auto& record = result.record;
  if (record.contains("metrics")) record["metrics"].erase("label_share");
  if (record.contains("children")) {
    for (auto& [seat, child] : record["children"].items()) child.erase("quit_time_s");
  }
  record["replayed_from"] = recording.bag.string();
  result.annotations = {};
  return result;
}

}  // namespace freeplay::recording
