#include "freeplay/web/state_frame.hpp"

#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/screen.hpp"
#include "freeplay/sim/zones.hpp"

namespace freeplay::web {

namespace {

nlohmann::json xy(const Vec2& p) { return {p.x(), p.y()}; }
nlohmann::json xyz(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

nlohmann::json polygon(const Polygon2& polygon) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : polygon) out.push_back(xy(p));
  return out;
}

std::string holder_name(sim::Holder::Kind kind) {
  switch (kind) {
    case sim::Holder::Kind::Finger: return "finger";
    case sim::Holder::Kind::Robot: return "robot";
    case sim::Holder::Kind::None: break;
  }
  return "none";
}

}  // namespace

nlohmann::json scene_json(const sim::ItemCatalogue& catalogue, const scenario::Scenario& scenario) {
  nlohmann::json items = nlohmann::json::array();
  for (const auto& item : catalogue.items()) {
    items.push_back({{"name", item.name},
                     {"label", item.label},
                     {"box_side_m", item.box_side_m},
                     {"polygon", polygon(item.polygon)},
                     {"colour", {item.colour[0], item.colour[1], item.colour[2]}}});
  }
  const bool robot = scenario.condition == scenario::Condition::ChildRobot;
  return {{"type", "scene"},
          {"screen", {{"width_m", sim::kScreenWidthM}, {"height_m", sim::kScreenHeightM},
                      {"width_px", sim::kScreenWidthPx}, {"height_px", sim::kScreenHeightPx},
                      {"stash_min_x", sim::kStashMinX}, {"frame", "sandtray"}}},
          {"items", items},
          {"scenario", scenario.name},
          {"condition", std::string(scenario::to_string(scenario.condition))},
          {"seats", robot ? nlohmann::json{"purple"} : nlohmann::json{"purple", "yellow"}},
          {"robot", robot},
          {"protocol", {{"greeting_s", scenario.protocol.greeting_s}, {"tutorial_s", scenario.protocol.tutorial_s},
                        {"freeplay_cap_s", scenario.protocol.freeplay_cap_s},
                        {"debriefing_s", scenario.protocol.debriefing_s}}}};
}

nlohmann::json tick_json(const runner::EpisodeSnapshot& s) {
  const auto& tray = *s.tray;
  nlohmann::json items = nlohmann::json::array();
  for (const auto& item : tray.items()) {
    items.push_back({{"name", item.name}, {"x", item.pose.x}, {"y", item.pose.y}, {"theta", item.pose.theta},
                     {"z", item.z}, {"visible", item.visible}, {"holder", holder_name(item.holder.kind)}});
  }
  nlohmann::json touches = nlohmann::json::array();
  for (const auto& touch : tray.touches()) {
    touches.push_back({{"finger", touch.finger}, {"x", touch.position.x()}, {"y", touch.position.y()}, {"item", touch.item}});
  }
  nlohmann::json children = nlohmann::json::array();
  for (const auto& c : s.children) {
    nlohmann::json fingers = nlohmann::json::array();
    for (const auto& [finger, p] : c.touches) fingers.push_back(finger);
    nlohmann::json coded = nullptr;  // simulation only: the coder's current labels, once free play started
    if (!c.coded[0].empty()) {
      coded = {{"task", std::string(c.coded[0])}, {"social", std::string(c.coded[1])}, {"attitude", std::string(c.coded[2])}};
    }
    children.push_back({{"seat", c.seat}, {"age", c.age_years}, {"gender", c.gender}, {"gaze", c.gaze},
                        {"gaze_point", xyz(c.gaze_point)}, {"speaking", c.speaking}, {"fingers", fingers},
                        {"coded", coded}});
  }
  nlohmann::json robot = nullptr;
  if (s.robot != nullptr) {
    robot = {{"finger", s.robot->finger ? xy(*s.robot->finger) : nlohmann::json()},
             {"gaze_point", xyz(s.robot->gaze_point)},
             {"speaking", s.robot->speaking}};
    const auto hand = tray.robot_hand();
    robot["hand"] = hand ? xy(*hand) : nlohmann::json();
    const auto held = tray.robot_item();
    robot["holding"] = held ? nlohmann::json(*held) : nlohmann::json();
  }
  return {{"type", "state"},
          {"t", s.t},
          {"freeplay_t", s.freeplay_t},
          {"stage", std::string(s.stage)},
          {"game_state", std::string(sim::game_state_name(tray.state()))},
          {"items", items},
          {"touches", touches},
          {"children", children},
          {"robot", robot},
          {"background_version", tray.background_version()}};
}

nlohmann::json zones_json(const sim::Sandtray& tray) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& zone : tray.zones().zones()) {
    out.push_back({{"colour", zone.colour}, {"id", zone.id}, {"centroid", xy(zone.centroid)}, {"polygon", polygon(zone.polygon)}});
  }
  return out;
}

}  // namespace freeplay::web
