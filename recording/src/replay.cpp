#include "freeplay/recording/replay.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "freeplay/agents/annotations.hpp"
#include "freeplay/agents/perception.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/statistics.hpp"
#include "freeplay/recording/bag_recorder.hpp"
#include "freeplay/recording/publishers.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/runner/summary.hpp"
#include "freeplay/sim/canvas.hpp"

namespace freeplay::recording {

namespace {

// The episode loop's constants (runner/src/episode.cpp), which the metrics' definitions use.
constexpr double kTickS = 0.1;
constexpr double kMinMoveM = 0.02;
constexpr double kTakenWindowS = 30.0;

/// An item's position on the game's /tf at a tick; InputError when the recording lacks it.
Vec2 item_position(const SessionRecording& rec, double tick, const std::string& item) {
  const auto it = rec.item_positions.find(publication_tick(tick));
  if (it == rec.item_positions.end() || !it->second.contains(item)) {
    throw InputError(fmt::format("no /tf pose of '{}' at t = {} s", item, tick), "/tf", "a complete recording");
  }
  return it->second.at(item);
}

/// What the episode loop measures tick by tick in free play, and the robot's move reports, rebuilt from a recording.
struct FreeplayReplay {
  double drawing_coverage = std::nan("");
  double mutual_gaze_s = 0.0;
  int joint_attention_episodes = 0;
  std::vector<double> path_lengths_m, clearances_mm, move_durations_s, placement_errors_mm, sync_mean_mm, sync_lag_ms;
  double sync_max_mm = 0.0;
  int moves_stolen = 0;
};

cv::Mat decode_background(const std::vector<std::uint8_t>& png) {
  const cv::Mat bgr = cv::imdecode(cv::Mat(1, static_cast<int>(png.size()), CV_8UC1, const_cast<std::uint8_t*>(png.data())),
                                   cv::IMREAD_COLOR);
  if (bgr.empty()) throw InputError("a background image does not decode", topics::kBackground, "PNG");
  return bgr;
}

/// The drawing's coverage: the last background published in free play against the one published when it began.
double replay_drawing_coverage(const SessionRecording& rec, double freeplay_start, double freeplay_end) {
  const std::vector<std::uint8_t>* map = nullptr;
  const std::vector<std::uint8_t>* last = nullptr;
  for (const auto& [t, png] : rec.backgrounds) {
    if (t <= freeplay_start + 1e-9 || t > freeplay_end + 0.5 * kTickS) continue;
    if (map == nullptr) map = &png;
    last = &png;
  }
  if (map == nullptr) return std::nan("");
  return sim::differing_pixel_share(decode_background(*last), decode_background(*map));
}

FreeplayReplay replay_freeplay(const SessionRecording& rec, double freeplay_start, double duration, bool child_robot) {
  FreeplayReplay out;
  if (std::isnan(duration)) return out;
  std::string ended_by = "cap";
  for (const auto& [tick, e] : rec.events) {
    if (e.source == "protocol" && e.type == "freeplay_ended") ended_by = e.data.value("ended_by", "cap");
  }
  out.drawing_coverage = replay_drawing_coverage(rec, freeplay_start, freeplay_start + duration);
  // The loop's ticks: k = 0, 1, … while k·0.1 < cap, or up to the tick at which the children quit.
  long ticks = 0;
  if (ended_by == "quit") {
    ticks = std::lround(duration / kTickS);
  } else {
    while (static_cast<double>(ticks) * kTickS < duration) ++ticks;
  }
  struct Gaze {
    std::string kind = "away";  // the episode's gaze names (child) or tray / item / child (robot)
    std::string target;         // item name or seat
  };
  std::map<std::string, Gaze> children;
  Gaze robot{"tray", ""};
  bool joint_before = false;
  std::map<std::string, Vec2> move_targets;  // item → the target of its last move_goal
  std::map<std::string, Vec2> pending_placement;
  std::size_t next = 0;
  auto apply = [&](const RecordedEvent& recorded) {
    const auto& e = recorded.event;
    if (e.source.rfind("child.", 0) == 0 && e.type == "gaze") {
      children[e.source.substr(6)] = {e.data.value("target", "away"), e.data.value("item", "")};
    } else if (e.source == "robot" && e.type == "move_goal") {
      robot = {"item", e.data.value("item", "")};
      move_targets[robot.target] = Vec2(e.data.value("x", 0.0), e.data.value("y", 0.0));
    } else if (e.source == "robot" && e.type == "look_at") {
      if (e.data.contains("child")) robot = {"child", e.data.value("child", "")};
      else if (e.data.contains("item")) robot = {"item", e.data.value("item", "")};
      else robot = {"tray", ""};
    } else if (e.source == "robot" && e.type == "move_result") {
      robot = {"tray", ""};
      const auto& d = e.data;
      if (d.contains("path_length_m")) out.path_lengths_m.push_back(d["path_length_m"].get<double>());
      if (d.contains("min_clearance_mm")) out.clearances_mm.push_back(d["min_clearance_mm"].get<double>());
      if (d.contains("sync_error_mm_mean")) {
        out.sync_mean_mm.push_back(d["sync_error_mm_mean"].get<double>());
        out.sync_max_mm = std::max(out.sync_max_mm, d.value("sync_error_mm_max", 0.0));
        out.sync_lag_ms.push_back(d.value("sync_lag_ms", std::nan("")));
      }
      if (d.contains("duration_s")) out.move_durations_s.push_back(d["duration_s"].get<double>());
      if (d.value("stolen_by_child", false)) ++out.moves_stolen;
      const auto item = d.value("item", "");
      if (d.value("status", "") == "succeeded" && move_targets.contains(item)) pending_placement[item] = move_targets[item];
    } else if (e.type == "interaction_event") {
      const auto message = e.data.value("message", "");
      if (message.rfind("releasing_", 0) != 0) return;
      const auto item = message.substr(10);
      const auto target = pending_placement.find(item);
      if (target == pending_placement.end()) return;
      out.placement_errors_mm.push_back((item_position(rec, recorded.tick, item) - target->second).norm() * 1000.0);
      pending_placement.erase(target);
    }
  };
  auto gaze_tick = [&] {
    bool joint = false;
    if (child_robot) {
      const auto& c = children["purple"];
      if ((c.kind == "robot" || c.kind == "partner") && robot.kind == "child" && robot.target == "purple") {
        out.mutual_gaze_s += kTickS;
      }
      joint = c.kind == "item" && !c.target.empty() && robot.kind == "item" && robot.target == c.target;
    } else {
      const auto& a = children["purple"];
      const auto& b = children["yellow"];
      if (a.kind == "partner" && b.kind == "partner") out.mutual_gaze_s += kTickS;
      joint = a.kind == "item" && b.kind == "item" && !a.target.empty() && a.target == b.target;
    }
    if (joint && !joint_before) ++out.joint_attention_episodes;
    joint_before = joint;
  };
  // Events before free play, then each free-play tick's events followed by that tick's gaze measurement.
  for (; next < rec.events.size() && rec.events[next].tick <= freeplay_start + 1e-9; ++next) apply(rec.events[next]);
  for (long k = 0; k < ticks; ++k) {
    const double tick_end = freeplay_start + static_cast<double>(k + 1) * kTickS + 0.5 * kTickS;
    for (; next < rec.events.size() && rec.events[next].tick < tick_end; ++next) apply(rec.events[next]);
    gaze_tick();
  }
  for (; next < rec.events.size(); ++next) apply(rec.events[next]);  // a release in the debriefing
  return out;
}

}  // namespace

std::filesystem::path open_session_bag(const std::filesystem::path& path, Bag& bag) {
  std::filesystem::path file = path;
  if (!std::filesystem::is_regular_file(path)) {
    const auto paths = session_paths(path);
    if (std::filesystem::exists(paths.bag)) {
      file = paths.bag;
    } else if (std::filesystem::exists(paths.active_bag)) {
      file = paths.active_bag;
    } else {
      throw InputError(fmt::format("no freeplay.bag in '{}'", path.string()), "SESSION_DIR",
                       "a session folder (<run>/sessions/<episode id>) or a .bag file");
    }
  }
  try {
    bag.open(file.string(), rosbag::bagmode::Read);
  } catch (const rosbag::BagUnindexedException&) {
    throw InputError(fmt::format("'{}' is not indexed (the recording was killed)", file.string()), "SESSION_DIR",
                     fmt::format("an indexed bag: run `rosbag reindex {}` first", file.string()));
  } catch (const rosbag::BagException& e) {
    throw InputError(fmt::format("'{}' is not a readable bag: {}", file.string(), e.what()), "SESSION_DIR",
                     "a ROS 1 bag written by `freeplay run --record`");
  }
  return file;
}

SessionRecording read_session(const std::filesystem::path& path) {
  SessionRecording out;
  Bag bag;
  out.bag = open_session_bag(path, bag);
  rosbag::View view(bag.get());
  bool first = true;
  for (const auto& m : view) {
    const auto topic = m.getTopic();
    const double t = sandtray_time(m.getTime());
    ++out.topic_counts[topic];
    out.topic_types[topic] = m.getDataType();
    if (first) out.start_s = t;
    first = false;
    out.end_s = std::max(out.end_s, t);
    if (topic == topics::kEvents) {
      const auto text = m.instantiate<msg::String>();
      const auto json = nlohmann::json::parse(std_string(text->data));
      RecordedEvent e;
      e.tick = json.at("tick").get<double>();
      e.event.t = json.at("t").get<double>();
      e.event.source = json.at("source").get<std::string>();
      e.event.type = json.at("type").get<std::string>();
      e.event.data = json.value("data", nlohmann::json());
      out.events.push_back(std::move(e));
    } else if (topic == topics::kTf) {
      const auto tf = m.instantiate<msg::TFMessage>();
      for (const auto& x : tf->transforms) {
        const auto child = std_string(x.child_frame_id);
        if (child.rfind("touch", 0) == 0 || child.find('_') != std::string::npos) continue;
        if (std_string(x.header.frame_id) != "sandtray") continue;  // the Nao's links hang from base_link
        out.item_positions[publication_tick(sandtray_time(x.header.stamp))][child] = Vec2(x.transform.translation.x, x.transform.translation.y);
      }
    } else if (topic == topics::kZones) {
      const auto markers = m.instantiate<msg::MarkerArray>();
      std::vector<RecordedZone> zones;
      for (const auto& marker : markers->markers) {
        if (marker.action != msg::Marker::ADD) continue;
        RecordedZone z;
        z.colour = std_string(marker.ns).substr(std::string("sandbox_zone_").size());
        for (std::size_t i = 0; i + 1 < marker.points.size(); ++i) z.polygon.emplace_back(marker.points[i].x, marker.points[i].y);
        z.area_m2 = std::abs(signed_area(z.polygon));
        zones.push_back(std::move(z));
      }
      out.zones.emplace_back(tick_time(publication_tick(t)), std::move(zones));
    } else if (topic == topics::kAnnotations) {
      out.annotations_yaml = std_string(m.instantiate<msg::String>()->data);
    } else if (topic == topics::kInteractionEvents) {
      out.interaction_events.push_back(std_string(m.instantiate<msg::String>()->data));
    } else if (topic == topics::kBackground) {
      const auto image = m.instantiate<msg::CompressedImage>();
      out.backgrounds.emplace_back(tick_time(publication_tick(t)), std::vector<std::uint8_t>(image->data.begin(), image->data.end()));
    }
  }
  return out;
}

nlohmann::json recompute_metrics(const SessionRecording& rec) {
  double freeplay_start = 0.0;
  double duration = std::nan("");
  bool child_robot = false;
  std::set<std::string> seats;
  for (const auto& [tick, e] : rec.events) {
    if (e.source == "protocol" && e.type == "stage" && e.data.value("stage", "") == "freeplay") freeplay_start = e.t;
    if (e.source == "protocol" && e.type == "freeplay_ended") duration = e.data.value("duration_s", std::nan(""));
    if (e.source == "robot") child_robot = true;
    if (e.source.rfind("child.", 0) == 0) seats.insert(e.source.substr(6));
  }
  nlohmann::json metrics;
  const double minutes = std::max(duration / 60.0, 1e-9);

  if (!rec.annotations_yaml.empty()) {
    const auto annotations = agents::parse_pinsoro_yaml(rec.annotations_yaml, rec.bag.string() + ":/freeplay/annotations");
    auto shares = [&](const std::string& seat, const agents::ChildTimeline& timeline) {
      for (const auto axis : agents::kAxes) {
        const auto s = agents::label_shares(timeline, axis);
        for (std::size_t i = 0; i < agents::label_count(axis); ++i) {
          metrics["label_share"][seat][std::string(agents::label_name(axis, i))] = s[i];
        }
      }
    };
    if (annotations.purple) shares("purple", *annotations.purple);
    if (annotations.yellow) shares("yellow", *annotations.yellow);
    if (annotations.yellow) child_robot = false;
  }

  auto zone_at = [&](double tick, const Vec2& p) -> std::string {
    const std::vector<RecordedZone>* zones = nullptr;
    for (const auto& [t, z] : rec.zones) {
      if (t <= tick + 1e-9) zones = &z;
    }
    if (zones == nullptr) return "";
    const RecordedZone* best = nullptr;
    double best_area = std::numeric_limits<double>::infinity();
    for (const auto& zone : *zones) {
      if (zone.polygon.size() >= 3 && zone.area_m2 < best_area && point_in_polygon(zone.polygon, p)) {
        best = &zone;
        best_area = zone.area_m2;
      }
    }
    return best != nullptr ? best->colour : "";
  };
  auto mover_of = [](const nlohmann::json& data) -> std::string {
    if (data.value("holder", "") == "robot") return "robot";
    const int finger = data.value("finger", 0);
    if (finger >= 1 && finger <= agents::kFingersPerChild) return "purple";
    if (finger > agents::kFingersPerChild && finger <= 2 * agents::kFingersPerChild) return "yellow";
    return "";
  };

  struct History {
    Vec2 grabbed_at = Vec2::Zero();
    std::string zone_at_grab;
    std::string last_mover;
    double last_move_t = -1e9;
  };
  std::map<std::string, History> history;
  std::map<std::string, int> touches;
  std::map<std::string, int> item_moves;
  std::map<std::string, int> actions;
  std::map<std::string, int> interaction;
  int robot_item_moves = 0;
  int taken_by_robot = 0;
  int taken_by_child = 0;
  int zone_transitions = 0;
  int moves_started = 0;
  int moves_succeeded = 0;
  int moves_failed = 0;
  int moves_cancelled = 0;
  double awaiting = -1.0;
  std::vector<double> latencies;
  bool in_freeplay = false;
  for (const auto& [tick, e] : rec.events) {
    const double t = tick - freeplay_start;
    if (e.source == "protocol" && e.type == "stage") in_freeplay = e.data.value("stage", "") == "freeplay";
    if (e.source.rfind("child.", 0) == 0 && e.type == "touch_down") ++touches[e.source.substr(6)];
    if (e.type == "interaction_event") ++interaction[e.data.value("message", "")];
    if (e.source == "robot") {
      // The loop's `t` of the tick that decided the action (observers see it after the tray step).
      const double loop_t = static_cast<double>(std::lround(t / kTickS) - 1) * kTickS;
      std::string action;
      if (e.type == "move_goal") action = "move", ++moves_started;
      if (e.type == "look_at") action = "look";
      if (e.type == "point_at") action = "point";
      if (e.type == "cancel") action = "cancel";
      if (e.type == "say" && in_freeplay) action = "say";
      if (!action.empty()) {
        ++actions[action];
        if (awaiting >= 0) {
          latencies.push_back(loop_t - awaiting);
          awaiting = -1.0;
        }
      }
      if (e.type == "move_result") {
        const auto status = e.data.value("status", "");
        if (status == "succeeded") ++moves_succeeded;
        else if (status == "preempted") ++moves_cancelled;
        else ++moves_failed;
      }
    }
    if (e.type == "item_grabbed") {
      const auto item = e.data.value("item", "");
      const auto mover = mover_of(e.data);
      auto& h = history[item];
      h.grabbed_at = item_position(rec, tick, item);
      h.zone_at_grab = zone_at(tick, h.grabbed_at);
      const bool recently_other = !h.last_mover.empty() && h.last_mover != mover && t - h.last_move_t < kTakenWindowS;
      bool shared_with_robot = false;
      bool shared_with_child = false;
      for (const auto& other : e.data.value("shared_with", nlohmann::json::array())) {
        if (other == "robot") shared_with_robot = true; else shared_with_child = true;
      }
      if (mover == "robot" && (shared_with_child || (recently_other && h.last_mover != "robot"))) ++taken_by_robot;
      if (mover != "robot" && (shared_with_robot || (recently_other && h.last_mover == "robot"))) ++taken_by_child;
    }
    if (e.type == "item_released") {
      const auto item = e.data.value("item", "");
      const auto mover = mover_of(e.data);
      auto& h = history[item];
      const Vec2 at = item_position(rec, tick, item);
      if ((at - h.grabbed_at).norm() < kMinMoveM) continue;
      h.last_mover = mover;
      h.last_move_t = t;
      if (zone_at(tick, at) != h.zone_at_grab) ++zone_transitions;
      if (mover == "robot") {
        ++robot_item_moves;
      } else {
        ++item_moves[mover];
        awaiting = t;
      }
    }
  }
  const auto freeplay = replay_freeplay(rec, freeplay_start, duration, child_robot);
  metrics["drawing_coverage"] = freeplay.drawing_coverage;
  metrics["mutual_gaze_s"] = freeplay.mutual_gaze_s;
  metrics["joint_attention_episodes"] = freeplay.joint_attention_episodes;
  int child_touches = 0;
  int child_moves = 0;
  for (const auto& seat : {"purple", "yellow"}) {
    if (!seats.contains(seat) && !(std::string(seat) == "purple")) continue;
    if (std::string(seat) == "yellow" && child_robot) continue;
    child_touches += touches[seat];
    child_moves += item_moves[seat];
    metrics["child"][seat]["touches_per_min"] = touches[seat] / minutes;
    metrics["child"][seat]["item_moves_per_min"] = item_moves[seat] / minutes;
  }
  metrics["child_touches_per_min"] = child_touches / minutes;
  metrics["child_item_moves_per_min"] = child_moves / minutes;
  metrics["zone_transitions"] = zone_transitions;
  if (child_robot) {
    int total = 0;
    for (const char* type : {"move", "look", "point", "say", "cancel"}) {
      metrics["robot_actions"][type] = actions[type];
      total += actions[type];
    }
    metrics["robot_actions_per_min"] = total / minutes;
    metrics["robot_item_moves_per_min"] = robot_item_moves / minutes;
    metrics["items_taken_by_robot_from_child"] = taken_by_robot;
    metrics["items_taken_by_child_from_robot"] = taken_by_child;
    metrics["robot_response_latency_s"] = freeplay::mean(latencies);
    metrics["planner"]["moves_started"] = moves_started;
    metrics["planner"]["success_rate"] =
        moves_started > 0 ? static_cast<double>(moves_succeeded) / moves_started : std::nan("");
    metrics["planner"]["moves_failed"] = moves_failed;
    metrics["planner"]["moves_cancelled"] = moves_cancelled;
    metrics["planner"]["path_length_m"] = freeplay::mean(freeplay.path_lengths_m);
    metrics["planner"]["min_clearance_mm"] = freeplay::mean(freeplay.clearances_mm);
    metrics["executor"]["moves_stolen_by_child"] = freeplay.moves_stolen;
    metrics["executor"]["move_duration_s"] = freeplay::mean(freeplay.move_durations_s);
    metrics["executor"]["placement_error_mm"] = freeplay::mean(freeplay.placement_errors_mm);
    metrics["executor"]["sync_error_mm_mean"] = freeplay::mean(freeplay.sync_mean_mm);
    metrics["executor"]["sync_error_mm_max"] = freeplay.sync_mean_mm.empty() ? std::nan("") : freeplay.sync_max_mm;
    metrics["executor"]["sync_lag_ms"] = freeplay::mean(freeplay.sync_lag_ms);
  }
  nlohmann::json extra;
  extra["events"] = rec.events.size();
  extra["interaction_events"] = interaction;
  extra["bag_duration_s"] = rec.end_s - rec.start_s;
  extra["complete"] = !rec.annotations_yaml.empty();
  return {{"duration_s", duration}, {"metrics", metrics}, {"extra", extra}};
}

std::map<std::string, double> metric_values(const nlohmann::json& record) {
  return runner::flatten_numbers(record.value("metrics", nlohmann::json::object()), "metrics", runner::NullLeaves::as_nan);
}

std::vector<MetricComparison> compare_with_record(const nlohmann::json& recomputed, const nlohmann::json& record) {
  auto replayed = metric_values(recomputed);
  replayed["duration_s"] = recomputed.value("duration_s", std::nan(""));
  auto recorded = metric_values(record);
  if (record.contains("duration_s")) recorded["duration_s"] = record["duration_s"].get<double>();
  std::vector<MetricComparison> out;
  for (const auto& [name, value] : replayed) {
    MetricComparison c;
    c.name = name;
    c.replayed = value;
    const auto it = recorded.find(name);
    c.recorded = it != recorded.end() ? it->second : std::nan("");
    c.equal = it != recorded.end() && (c.replayed == c.recorded || (std::isnan(c.replayed) && std::isnan(c.recorded)));
    out.push_back(std::move(c));
  }
  for (const auto& [name, value] : recorded) {
    if (!replayed.contains(name)) out.push_back({name, std::nan(""), value, false});
  }
  return out;
}

}  // namespace freeplay::recording
