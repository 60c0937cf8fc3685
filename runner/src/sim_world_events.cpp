// The world side's events and record: the game's events into the log and on to the episode's metrics unit
// (EpisodeMetrics, which replay feeds the same way), and the episode record.

#include "freeplay/agents/labels.hpp"
#include "freeplay/runner/versions.hpp"
#include "freeplay/results/run_folder.hpp"
#include "sim_world.hpp"

namespace freeplay::runner::detail {

namespace {

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

void SimWorld::drain_tray_events() {
  for (auto& e : tray_.drain_events()) {
    if (const auto* message = e.get<events::InteractionEvent>()) {
      pending_interaction_events_.push_back(message->message);
    }
    log_.emit(std::move(e));
  }
  metrics_.observe_new(log_, tray_.time(), SandtrayMetricsWorld(tray_));
}

nlohmann::json SimWorld::record(double duration, const std::string& ended_by,
                                const agents::SessionAnnotations& annotations) const {
  const auto metrics = metrics_.to_json(duration, annotations, drawing_coverage_);
  nlohmann::json children = nlohmann::json::object();
  for (const auto& c : children_) {
    children[c.seat_name] = profile_json(c.agent->profile());
    children[c.seat_name]["quit_time_s"] = c.agent->quit_time();
    // How often each coded label equals the child's own state (the child's state is not in a bag).
    const auto& coded = c.seat_name == "purple" ? annotations.purple : annotations.yellow;
    if (coded) {
      for (const agents::Axis axis : agents::kAxes) {
        const double agreement = agents::timeline_agreement(*coded, c.agent->timeline(), axis, duration);
        children[c.seat_name]["coder_agreement_by_axis"][std::string(agents::axis_name(axis))] = agreement;
        if (axis == agents::Axis::SocialEngagement) children[c.seat_name]["coder_agreement"] = agreement;
      }
    }
  }
  auto out = provenance_fields(log_);
  out.update({{"duration_s", duration},
              {"ended_by", ended_by},
              {"children", children},
              {"robot_mode", child_robot_ ? std::string(stage::to_string(scenario_.robot.mode)) : ""},
              {"planner", child_robot_ ? scenario_.planner.name : ""},
              {"metrics", metrics}});
  return out;
}

}  // namespace freeplay::runner::detail
