// The world side's events and metrics: the game's events into the log, who moved and took which item, gaze
// metrics, and the episode record.

#include <cmath>

#include "freeplay/agents/labels.hpp"
#include "freeplay/core/statistics.hpp"
#include "freeplay/runner/run_folder.hpp"
#include "freeplay/runner/versions.hpp"
#include "freeplay/sim/zones.hpp"
#include "sim_world.hpp"

namespace freeplay::runner::detail {

namespace {

constexpr double kMinMoveM = 0.02;      // displacement that counts as an item move
constexpr double kTakenWindowS = 30.0;  // "took an item from" window after the other's last move

nlohmann::json profile_json(const agents::ChildProfile& p) {
  static const char* tablet[] = {"0", "1", "2", "na"};
  return {{"age", p.age_years},
          {"gender", std::string(agents::gender_name(p.gender))},
          {"sociability", p.sociability},
          {"assertiveness", p.assertiveness},
          {"attention_span", p.attention_span},
          {"tablet_familiarity", tablet[static_cast<int>(p.tablet)]}};
}

}  // namespace

std::string SimWorld::mover_of(const nlohmann::json& data) const {
  if (data.value("holder", "") == "robot") return "robot";
  const int finger = data.value("finger", 0);
  for (const auto& c : children_) {
    if (c.owns_finger(finger)) return c.seat_name;
  }
  return "";
}

std::string SimWorld::zone_colour_at(const Vec2& p) const {
  const auto* zone = tray_.zones().at(p);
  return zone != nullptr ? zone->colour : "";
}

void SimWorld::drain_tray_events() {
  const double t = tray_.time() - freeplay_start_;
  for (auto& e : tray_.drain_events()) {
    if (e.type == "interaction_event") {
      const auto message = e.data.value("message", "");
      pending_interaction_events_.push_back(message);
      if (message.rfind("releasing_", 0) == 0) on_robot_release(message.substr(10));
    }
    if (e.type == "item_grabbed") on_grab(e.data, t);
    if (e.type == "item_released") on_release(e.data, t);
    log_.emit(std::move(e));
  }
}

void SimWorld::on_robot_release(const std::string& item) {
  const auto it = pending_placement_.find(item);
  if (it == pending_placement_.end() || models_.catalogue->find(item) == nullptr) return;
  const Vec2 at = tray_.item(item).pose.position();
  placement_errors_mm_.push_back((at - it->second).norm() * 1000.0);
  pending_placement_.erase(it);
}

void SimWorld::on_grab(const nlohmann::json& data, double t) {
  const auto item = data.value("item", "");
  const auto mover = mover_of(data);
  auto& h = history_[item];
  h.grabbed_at = tray_.item(item).pose.position();
  h.zone_at_grab = zone_colour_at(h.grabbed_at);
  const bool recently_other = !h.last_mover.empty() && h.last_mover != mover && t - h.last_move_t < kTakenWindowS;
  bool shared_with_robot = false;
  bool shared_with_child = false;
  for (const auto& other : data.value("shared_with", nlohmann::json::array())) {
    if (other == "robot") shared_with_robot = true; else shared_with_child = true;
  }
  if (mover == "robot" && (shared_with_child || (recently_other && h.last_mover != "robot"))) ++taken_by_robot_;
  if (mover != "robot" && (shared_with_robot || (recently_other && h.last_mover == "robot"))) ++taken_by_child_;
}

void SimWorld::on_release(const nlohmann::json& data, double t) {
  const auto item = data.value("item", "");
  const auto mover = mover_of(data);
  auto& h = history_[item];
  const Vec2 at = tray_.item(item).pose.position();
  if ((at - h.grabbed_at).norm() < kMinMoveM) return;
  h.last_mover = mover;
  h.last_move_t = t;
  if (zone_colour_at(at) != h.zone_at_grab) ++zone_transitions_;
  if (mover == "robot") {
    ++robot_item_moves_;
  } else {
    for (auto& c : children_) {
      if (c.seat_name == mover) ++c.item_moves;
    }
    awaiting_response_since_ = t;
  }
}

void SimWorld::update_gaze_metrics() {
  if (child_robot_) {
    const auto& c = children_[0];
    const bool child_looks = c.last.gaze.kind == agents::GazeKind::Robot || c.last.gaze.kind == agents::GazeKind::PartnerFace;
    const bool robot_looks = robot_gaze_.kind == RobotGaze::Kind::Child && robot_gaze_.target == c.seat_name;
    if (child_looks && robot_looks) mutual_gaze_s_ += kTickS;
    const bool joint = c.last.gaze.kind == agents::GazeKind::Item && c.last.gaze.item >= 0 &&
                       robot_gaze_.kind == RobotGaze::Kind::Item &&
                       agents::item_index(robot_gaze_.target) == c.last.gaze.item;
    if (joint && !joint_attention_) ++joint_attention_episodes_;
    joint_attention_ = joint;
    return;
  }
  const auto& a = children_[0].last.gaze;
  const auto& b = children_[1].last.gaze;
  if (a.kind == agents::GazeKind::PartnerFace && b.kind == agents::GazeKind::PartnerFace) mutual_gaze_s_ += kTickS;
  const bool joint = a.kind == agents::GazeKind::Item && b.kind == agents::GazeKind::Item && a.item >= 0 && a.item == b.item;
  if (joint && !joint_attention_) ++joint_attention_episodes_;
  joint_attention_ = joint;
}

nlohmann::json SimWorld::record(double duration, const std::string& ended_by,
                                const agents::SessionAnnotations& annotations,
                                const RobotSideMetrics& robot) const {
  const double minutes = std::max(duration / 60.0, 1e-9);
  nlohmann::json metrics;
  auto shares = [&](const std::string& seat, const agents::ChildTimeline& timeline) {
    for (const auto axis : agents::kAxes) {
      const auto s = agents::label_shares(timeline, axis);
      for (std::size_t i = 0; i < agents::label_count(axis); ++i) {
        metrics["label_share"][seat][std::string(agents::label_name(axis, i))] = s[i];
      }
    }
  };
  shares("purple", *annotations.purple);
  if (annotations.yellow) shares("yellow", *annotations.yellow);
  int child_touches = 0;
  int child_moves = 0;
  for (const auto& c : children_) {
    child_touches += c.touches;
    child_moves += c.item_moves;
    metrics["child"][c.seat_name]["touches_per_min"] = c.touches / minutes;
    metrics["child"][c.seat_name]["item_moves_per_min"] = c.item_moves / minutes;
  }
  metrics["child_touches_per_min"] = child_touches / minutes;
  metrics["child_item_moves_per_min"] = child_moves / minutes;
  metrics["zone_transitions"] = zone_transitions_;
  metrics["drawing_coverage"] = drawing_coverage_;
  metrics["mutual_gaze_s"] = mutual_gaze_s_;
  metrics["joint_attention_episodes"] = joint_attention_episodes_;
  if (child_robot_) {
    int actions = 0;
    for (const char* type : {"move", "look", "point", "say", "cancel"}) {
      const int n = robot_actions_.count(type) != 0 ? robot_actions_.at(type) : 0;
      metrics["robot_actions"][type] = n;
      actions += n;
    }
    metrics["robot_actions_per_min"] = actions / minutes;
    metrics["robot_item_moves_per_min"] = robot_item_moves_ / minutes;
    metrics["items_taken_by_robot_from_child"] = taken_by_robot_;
    metrics["items_taken_by_child_from_robot"] = taken_by_child_;
    metrics["robot_response_latency_s"] = freeplay::mean(response_latencies_);
    robot.write(metrics["planner"], metrics["executor"]);
    metrics["executor"]["placement_error_mm"] = freeplay::mean(placement_errors_mm_);
  }
  nlohmann::json children = nlohmann::json::object();
  for (const auto& c : children_) {
    children[c.seat_name] = profile_json(c.agent->profile());
    children[c.seat_name]["quit_time_s"] = c.agent->quit_time();
    // How often the coded social label equals the child's own state (the child's state is not in a bag).
    const auto& coded = c.seat_name == "purple" ? annotations.purple : annotations.yellow;
    if (coded) {
      children[c.seat_name]["coder_agreement"] =
          agents::timeline_agreement(*coded, c.agent->timeline(), agents::Axis::SocialEngagement, duration);
    }
  }
  auto out = provenance_fields(log_);
  out.update({{"duration_s", duration},
              {"ended_by", ended_by},
              {"children", children},
              {"robot_mode", child_robot_ ? scenario_.robot.mode : ""},
              {"planner", child_robot_ ? scenario_.planner.name : ""},
              {"metrics", metrics}});
  return out;
}

}  // namespace freeplay::runner::detail
