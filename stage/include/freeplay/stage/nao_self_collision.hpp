#pragma once
// Self-collision checks of the NAO: which pairs of its geoms may touch, and which of them penetrate now.

#include <cstddef>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "freeplay/stage/stage.hpp"
#include "freeplay/stage/stage_model.hpp"

namespace freeplay::stage {

/// Pairs of NAO geoms that may collide: different bodies, not adjacent (through geom-less bodies), and apart in
/// StandZero (pairs that overlap there are part of the primitive shell, as MoveIt's "default" collision pairs).
class NaoSelfCollision {
 public:
  /// The pairs of `model`'s NAO; a pair collides when its geoms penetrate deeper than `penetration_m` (m).
  NaoSelfCollision(const StageModel& model, double penetration_m);

  /// Names ("geom/geom") of every pair that collided so far.
  const std::set<std::string>& hit() const { return hit_; }
  /// Number of pairs checked.
  std::size_t pairs() const { return pairs_.size(); }

  /// Checks every pair in `stage`'s current poses; returns how many pairs newly started colliding and sets `any`.
  int update(const Stage& stage, bool& any);

 private:
  const StageModel* model_;
  double penetration_m_;
  std::vector<std::pair<int, int>> pairs_;
  std::vector<bool> colliding_;
  std::set<std::string> hit_;
};

}  // namespace freeplay::stage
