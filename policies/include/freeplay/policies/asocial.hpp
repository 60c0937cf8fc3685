#pragma once
// `asocial`: a faithful port of the real `sandbox_play` node (core:nodes/play), the PInSoRo robot's policy.

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "freeplay/core/settings_archive.hpp"
#include "freeplay/policies/play_policy.hpp"

namespace freeplay::policies {

/// The real play node's item order (`ITEMS`).
const std::vector<std::string>& asocial_item_order();
/// The real play node's habitat table (`HABITATS`): item → zone colours it belongs to.
const std::map<std::string, std::vector<std::string>>& asocial_habitats();

/// The asocial policy's `robot.params` (defaults = the original's pauses).
struct AsocialParams {
  double pause_min_s = 1.2;   ///< pause after a move: lower bound (s)
  double pause_max_s = 2.5;   ///< pause after a move: upper bound (s)
  double idle_pause_s = 0.3;  ///< pause when nothing was moved (s)

  /// The keys of the asocial policy's `robot.params`.
  template <typename Archive>
  void visit(Archive& a) {
    a.field("pause_min_s", pause_min_s, Schema::number(0, 60), "pause after a move: lower bound");
    a.field("pause_max_s", pause_max_s, Schema::number(0, 60), "pause after a move: upper bound");
    a.field("idle_pause_s", idle_pause_s, Schema::number(0, 60), "pause when nothing was moved");
  }
};

/// Moves one reachable item that is not in one of its habitats to the closest reachable centroid of a randomly
/// chosen habitat colour, then pauses U(1.2, 2.5) s (0.3 s when there was nothing to do). Never perceives the
/// children, never checks whether a child holds the item (as the original).
class AsocialPolicy final : public PlayPolicy {
 public:
  /// Reads `params` as AsocialParams (absent keys: the original's pauses); InputError naming `robot.params.KEY`.
  explicit AsocialPolicy(const YAML::Node& params);
  std::string name() const override { return "asocial"; }
  void reset(const PolicyContext& context, Rng rng) override;
  std::vector<Action> decide(const Observation& observation) override;
  void on_result(const ActionResult& result) override;

  /// One `place_random_item()` attempt of the original: the goal it would send, if any.
  std::optional<MoveItem> choose_move(const Observation& observation);

 private:
  std::vector<std::pair<Vec2, Vec2>> zone_boxes_;  // bounds() of the observation's zones, rebuilt by choose_move
  AsocialParams params_;
  Rng rng_{0};
  double resume_at_ = 0.0;
  bool waiting_for_result_ = false;
  bool result_arrived_ = false;
};

}  // namespace freeplay::policies
