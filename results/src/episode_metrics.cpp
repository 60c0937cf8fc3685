#include "freeplay/results/episode_metrics.hpp"

#include <cmath>

#include "freeplay/agents/labels.hpp"
#include "freeplay/agents/perception.hpp"
#include "freeplay/core/statistics.hpp"

namespace freeplay::results {

namespace {

constexpr double kTickS = 0.1;          // the game's 10 Hz tick
constexpr double kMinMoveM = 0.02;      // displacement that counts as an item move
constexpr double kTakenWindowS = 30.0;  // "took an item from" window after the other's last move

bool starts_with(const std::string& s, std::string_view prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

EpisodeMetrics::EpisodeMetrics(bool child_robot) : child_robot_(child_robot) {
  seats_ = child_robot ? std::vector<std::string>{"purple"} : std::vector<std::string>{"purple", "yellow"};
}

void EpisodeMetrics::observe_new(const EventLog& log, double tick, const MetricsWorld& world) {
  const auto& events = log.events();
  for (; fed_ < events.size(); ++fed_) observe(events[fed_], tick, world);
}

std::string EpisodeMetrics::mover_of(const std::optional<int>& finger) const {
  if (!finger) return "robot";
  for (std::size_t i = 0; i < seats_.size(); ++i) {
    const int offset = static_cast<int>(i) * agents::kFingersPerChild;  // purple: touch1…3, yellow: touch4…6
    if (*finger > offset && *finger <= offset + agents::kFingersPerChild) return seats_[i];
  }
  return "";
}

void EpisodeMetrics::observe(const Event& e, double tick, const MetricsWorld& world) {
  if (const auto* stage = e.get<events::Stage>(); stage && e.source == "protocol") {
    in_freeplay_ = stage->stage == "freeplay";
    if (in_freeplay_) freeplay_start_ = e.t;
  }
  const double t = tick - freeplay_start_;  // free-play time of the snapshot that carried the event
  if (starts_with(e.source, "child.")) {
    const auto seat = e.source.substr(6);
    if (e.get<events::TouchDown>() != nullptr) ++touches_[seat];
    if (const auto* gaze = e.get<events::ChildGaze>()) children_gaze_[seat] = {gaze->target, gaze->item.value_or("")};
  }
  if (e.source == "robot") on_robot_event(e, t);
  if (const auto* grab = e.get<events::ItemGrabbed>()) on_grab(*grab, t, world);
  if (const auto* release = e.get<events::ItemReleased>()) on_release(*release, t, world);
  if (const auto* interaction = e.get<events::InteractionEvent>()) {
    const auto& message = interaction->message;
    if (!starts_with(message, "releasing_")) return;
    const auto target = pending_placement_.find(message.substr(10));
    if (target == pending_placement_.end()) return;
    placement_errors_mm_.push_back((world.item_position(target->first) - target->second).norm() * 1000.0);
    pending_placement_.erase(target);
  }
}

void EpisodeMetrics::on_robot_event(const Event& e, double t) {
  std::string action;
  if (const auto* goal = e.get<events::MoveGoal>()) {
    action = "move";
    ++moves_started_;
    robot_gaze_ = {"item", goal->item};
    move_targets_[robot_gaze_.target] = Vec2(goal->x, goal->y);
  } else if (const auto* look = e.get<events::LookAt>()) {
    action = "look";
    if (look->child) robot_gaze_ = {"child", *look->child};
    else if (look->item) robot_gaze_ = {"item", *look->item};
    else robot_gaze_ = {"tray", ""};
  } else if (e.get<events::PointAt>() != nullptr) {
    action = "point";
  } else if (e.get<events::Cancel>() != nullptr) {
    action = "cancel";
  } else if (e.get<events::Say>() != nullptr) {
    if (in_freeplay_) action = "say";
  } else if (e.type() == "move_result") {  // by its fields: events::MoveResult, or Other in an older log
    robot_gaze_ = {"tray", ""};
    const auto d = e.data();
    if (d.contains("path_length_m")) path_lengths_m_.push_back(d["path_length_m"].get<double>());
    if (d.contains("min_clearance_mm")) clearances_mm_.push_back(d["min_clearance_mm"].get<double>());
    if (d.contains("sync_error_mm_mean")) {
      sync_mean_mm_.push_back(d["sync_error_mm_mean"].get<double>());
      sync_max_mm_ = std::max(sync_max_mm_, d.value("sync_error_mm_max", 0.0));
      sync_lag_ms_.push_back(d.value("sync_lag_ms", std::nan("")));
    }
    if (d.contains("duration_s")) move_durations_s_.push_back(d["duration_s"].get<double>());
    if (d.value("stolen_by_child", false)) ++moves_stolen_;
    const auto item = d.value("item", "");
    const auto status = d.value("status", "");
    if (status == "succeeded") {
      ++moves_succeeded_;
      if (move_targets_.contains(item)) pending_placement_[item] = move_targets_[item];
    } else if (status == "preempted") {
      ++moves_cancelled_;
    } else {
      ++moves_failed_;
    }
  }
  if (action.empty()) return;
  ++actions_[action];
  if (awaiting_response_since_ >= 0) {
    // The loop's time of the tick that decided the action (the snapshot is taken after the tray step).
    const double decided_t = static_cast<double>(std::lround(t / kTickS) - 1) * kTickS;
    response_latencies_.push_back(decided_t - awaiting_response_since_);
    awaiting_response_since_ = -1.0;
  }
}

void EpisodeMetrics::on_grab(const events::ItemGrabbed& grab, double t, const MetricsWorld& world) {
  const auto& item = grab.item;
  const auto mover = mover_of(grab.finger);
  auto& h = history_[item];
  h.grabbed_at = world.item_position(item);
  h.zone_at_grab = world.zone_at(h.grabbed_at);
  const bool recently_other = !h.last_mover.empty() && h.last_mover != mover && t - h.last_move_t < kTakenWindowS;
  bool shared_with_robot = false;
  bool shared_with_child = false;
  for (const auto& other : grab.shared_with) {
    if (other == "robot") shared_with_robot = true; else shared_with_child = true;
  }
  if (mover == "robot" && (shared_with_child || (recently_other && h.last_mover != "robot"))) ++taken_by_robot_;
  if (mover != "robot" && (shared_with_robot || (recently_other && h.last_mover == "robot"))) ++taken_by_child_;
}

void EpisodeMetrics::on_release(const events::ItemReleased& release, double t, const MetricsWorld& world) {
  const auto& item = release.item;
  const auto mover = mover_of(release.finger);
  auto& h = history_[item];
  const Vec2 at = world.item_position(item);
  if ((at - h.grabbed_at).norm() < kMinMoveM) return;
  h.last_mover = mover;
  h.last_move_t = t;
  if (world.zone_at(at) != h.zone_at_grab) ++zone_transitions_;
  if (mover == "robot") {
    ++robot_item_moves_;
  } else {
    ++item_moves_[mover];
    awaiting_response_since_ = t;
  }
}

void EpisodeMetrics::measure_gaze() {
  bool joint = false;
  if (child_robot_) {
    const auto& c = children_gaze_["purple"];
    if ((c.kind == "robot" || c.kind == "partner") && robot_gaze_.kind == "child" && robot_gaze_.target == "purple") {
      mutual_gaze_s_ += kTickS;
    }
    joint = c.kind == "item" && !c.target.empty() && robot_gaze_.kind == "item" && robot_gaze_.target == c.target;
  } else {
    const auto& a = children_gaze_["purple"];
    const auto& b = children_gaze_["yellow"];
    if (a.kind == "partner" && b.kind == "partner") mutual_gaze_s_ += kTickS;
    joint = a.kind == "item" && b.kind == "item" && !a.target.empty() && a.target == b.target;
  }
  if (joint && !joint_before_) ++joint_attention_episodes_;
  joint_before_ = joint;
}

nlohmann::json EpisodeMetrics::to_json(double duration_s, const agents::SessionAnnotations& annotations,
                                       double drawing_coverage) const {
  const double minutes = std::max(duration_s / 60.0, 1e-9);
  nlohmann::json metrics;
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
  auto count = [](const std::map<std::string, int>& counts, const std::string& key) {
    const auto it = counts.find(key);
    return it != counts.end() ? it->second : 0;
  };
  int child_touches = 0;
  int child_moves = 0;
  for (const auto& seat : seats_) {
    child_touches += count(touches_, seat);
    child_moves += count(item_moves_, seat);
    metrics["child"][seat]["touches_per_min"] = count(touches_, seat) / minutes;
    metrics["child"][seat]["item_moves_per_min"] = count(item_moves_, seat) / minutes;
  }
  metrics["child_touches_per_min"] = child_touches / minutes;
  metrics["child_item_moves_per_min"] = child_moves / minutes;
  metrics["zone_transitions"] = zone_transitions_;
  metrics["drawing_coverage"] = drawing_coverage;
  metrics["mutual_gaze_s"] = mutual_gaze_s_;
  metrics["joint_attention_episodes"] = joint_attention_episodes_;
  if (!child_robot_) return metrics;
  int actions = 0;
  for (const char* type : {"move", "look", "point", "say", "cancel"}) {
    metrics["robot_actions"][type] = count(actions_, type);
    actions += count(actions_, type);
  }
  metrics["robot_actions_per_min"] = actions / minutes;
  metrics["robot_item_moves_per_min"] = robot_item_moves_ / minutes;
  metrics["items_taken_by_robot_from_child"] = taken_by_robot_;
  metrics["items_taken_by_child_from_robot"] = taken_by_child_;
  metrics["robot_response_latency_s"] = freeplay::mean(response_latencies_);
  metrics["planner"]["moves_started"] = moves_started_;
  metrics["planner"]["success_rate"] = moves_started_ > 0 ? static_cast<double>(moves_succeeded_) / moves_started_ : std::nan("");
  metrics["planner"]["moves_failed"] = moves_failed_;
  metrics["planner"]["moves_cancelled"] = moves_cancelled_;
  metrics["planner"]["path_length_m"] = freeplay::mean(path_lengths_m_);
  metrics["planner"]["min_clearance_mm"] = freeplay::mean(clearances_mm_);
  metrics["executor"]["moves_stolen_by_child"] = moves_stolen_;
  metrics["executor"]["move_duration_s"] = freeplay::mean(move_durations_s_);
  metrics["executor"]["placement_error_mm"] = freeplay::mean(placement_errors_mm_);
  metrics["executor"]["sync_error_mm_mean"] = freeplay::mean(sync_mean_mm_);
  metrics["executor"]["sync_error_mm_max"] = sync_mean_mm_.empty() ? std::nan("") : sync_max_mm_;
  metrics["executor"]["sync_lag_ms"] = freeplay::mean(sync_lag_ms_);
  return metrics;
}

}  // namespace freeplay::results
