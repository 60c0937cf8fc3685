#pragma once
// `asocial`: a faithful port of the real `sandbox_play` node (core:nodes/play), the PInSoRo robot's policy.

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "freeplay/policies/play_policy.hpp"

namespace freeplay::policies {

/// The real play node's item order (`ITEMS`).
const std::vector<std::string>& asocial_item_order();
/// The real play node's habitat table (`HABITATS`): item → zone colours it belongs to.
const std::map<std::string, std::vector<std::string>>& asocial_habitats();

/// Moves one reachable item that is not in one of its habitats to the closest reachable centroid of a randomly
/// chosen habitat colour, then pauses U(1.2, 2.5) s (0.3 s when there was nothing to do). Never perceives the
/// children, never checks whether a child holds the item (as the original).
class AsocialPolicy final : public PlayPolicy {
 public:
  /// Accepts parameters `pause_min_s`, `pause_max_s`, `idle_pause_s` (defaults = the original 1.2, 2.5, 0.3).
  explicit AsocialPolicy(const YAML::Node& params);
  std::string name() const override { return "asocial"; }
  void reset(const PolicyContext& context, Rng rng) override;
  std::vector<Action> decide(const Observation& observation) override;
  void on_result(const ActionResult& result) override;

  /// One `place_random_item()` attempt of the original: the goal it would send, if any.
  std::optional<MoveItem> choose_move(const Observation& observation);

 private:
  std::vector<std::pair<Vec2, Vec2>> zone_boxes_;  // bounds() of the observation's zones, rebuilt by choose_move
  double pause_min_s_ = 1.2;
  double pause_max_s_ = 2.5;
  double idle_pause_s_ = 0.3;
  Rng rng_{0};
  double resume_at_ = 0.0;
  bool waiting_for_result_ = false;
  bool result_arrived_ = false;
};

}  // namespace freeplay::policies
