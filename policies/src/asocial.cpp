#include "freeplay/policies/asocial.hpp"

#include <array>
#include <limits>
#include <stdexcept>

#include "freeplay/core/error.hpp"
#include "freeplay/core/settings_archive.hpp"

namespace freeplay::policies {

const std::vector<std::string>& asocial_item_order() {
  static const std::vector<std::string> items = {"zebra",   "elephant",  "ball",  "lion", "giraffe",
                                                 "caravan", "crocodile", "hippo", "boy",  "girl"};
  return items;
}

const std::map<std::string, std::vector<std::string>>& asocial_habitats() {
  static const std::map<std::string, std::vector<std::string>> habitats = {
      {"zebra", {"yellow", "green"}},
      {"elephant", {"green"}},
      {"lion", {"yellow"}},
      {"giraffe", {"yellow", "green"}},
      {"crocodile", {"blue"}},
      {"hippo", {"blue"}},
      {"ball", {"yellow", "green", "purple", "white"}},
      {"caravan", {"yellow", "green", "purple", "white"}},
      {"boy", {"yellow", "green", "purple", "white"}},
      {"girl", {"yellow", "green", "purple", "white"}},
  };
  return habitats;
}

namespace {

bool reachable(const RobotSelf& self, const Vec2& p) {
  if (!self.arm_reach_known) return true;  // the original plays everywhere until localised
  return (p - self.arm_reach_centre).norm() < self.arm_reach_radius;
}

// Farther than this outside a polygon's bounding box, `point_in_polygon` is false: no edge crosses the point's row
// to its right an odd number of times, and the boundary is farther than its 1e-12 tolerance (rounding is ~1e-16).
constexpr double kOutsideBoxMargin = 1e-9;

bool outside_box(const std::pair<Vec2, Vec2>& box, const Vec2& p) {
  const auto& [lo, hi] = box;
  return p.x() < lo.x() - kOutsideBoxMargin || p.x() > hi.x() + kOutsideBoxMargin ||
         p.y() < lo.y() - kOutsideBoxMargin || p.y() > hi.y() + kOutsideBoxMargin;
}

}  // namespace

AsocialPolicy::AsocialPolicy(const YAML::Node& params)
    : params_(read_unvalidated_settings<AsocialParams>(params, "robot.params")) {
  if (params_.pause_max_s < params_.pause_min_s) {
    throw InputError("pause_max_s is below pause_min_s", "robot.params.pause_max_s", ">= pause_min_s");
  }
}

void AsocialPolicy::reset(const PolicyContext& /*context*/, Rng rng) {
  rng_ = rng;
  resume_at_ = 0.0;
  waiting_for_result_ = false;
  result_arrived_ = false;
}

std::optional<MoveItem> AsocialPolicy::choose_move(const Observation& observation) {
  // The shuffle draws depend only on the length: shuffling indices gives the original's order of names.
  const auto& names = asocial_item_order();
  std::array<std::size_t, 10> order{};
  if (names.size() != order.size()) throw std::logic_error("asocial_item_order() must list 10 items");
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  rng_.shuffle(order);
  zone_boxes_.resize(observation.zones.size());
  for (std::size_t z = 0; z < observation.zones.size(); ++z) zone_boxes_[z] = bounds(observation.zones[z].polygon);
  for (const std::size_t index : order) {
    const auto& name = names[index];
    const auto* item = observation.item(name);
    if (item == nullptr) continue;  // TF not yet published
    const Vec2 position = item->pose.position();
    if (!reachable(observation.self, position)) continue;
    const auto habitat = asocial_habitats().find(name);
    if (habitat == asocial_habitats().end() || habitat->second.empty()) continue;
    bool already_home = false;
    for (std::size_t z = 0; z < observation.zones.size(); ++z) {
      const auto& zone = observation.zones[z];
      if (outside_box(zone_boxes_[z], position)) continue;  // point_in_polygon would say false
      for (const auto& colour : habitat->second) {
        if (zone.colour == colour && point_in_polygon(zone.polygon, position)) already_home = true;
      }
    }
    if (already_home) continue;
    const auto& colour =
        habitat->second[static_cast<std::size_t>(rng_.uniform_int(0, static_cast<std::int64_t>(habitat->second.size()) - 1))];
    const ZoneObservation* best = nullptr;
    double best_distance = std::numeric_limits<double>::infinity();
    for (const auto& zone : observation.zones) {
      if (zone.colour != colour || !reachable(observation.self, zone.centroid)) continue;
      const double d = (zone.centroid - position).norm();
      if (d < best_distance) {
        best_distance = d;
        best = &zone;
      }
    }
    if (best == nullptr) continue;
    return MoveItem{name, best->centroid};
  }
  return std::nullopt;
}

std::vector<Action> AsocialPolicy::decide(const Observation& observation) {
  if (waiting_for_result_) {
    if (!result_arrived_) return {};
    waiting_for_result_ = false;
    resume_at_ = observation.t + rng_.uniform(params_.pause_min_s, params_.pause_max_s);
    return {};
  }
  if (observation.t < resume_at_) return {};
  if (auto move = choose_move(observation)) {
    waiting_for_result_ = true;
    result_arrived_ = false;
    return {*move};
  }
  resume_at_ = observation.t + params_.idle_pause_s;
  return {};
}

void AsocialPolicy::on_result(const ActionResult& result) {
  if (result.kind != ActionResult::Kind::SpeechFinished) result_arrived_ = true;
}

FREEPLAY_REGISTER_POLICY(AsocialPolicy, "asocial",
                         "faithful port of the real play node: habitats, random order, closest reachable zone");

}  // namespace freeplay::policies
