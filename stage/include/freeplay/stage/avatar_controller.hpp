#pragma once
// Kinematic control of a child avatar: where the head looks and where a hand touches.

#include <Eigen/Core>

#include "freeplay/stage/nao_controller.hpp"
#include "freeplay/stage/stage.hpp"

namespace freeplay::stage {

/// Which hand.
enum class Hand { right = 0, left = 1 };

/// Outcome of a touch command.
struct TouchResult {
  bool reachable = false;  ///< the fingertip reaches the point (leaning forward if needed)
  double error_m = 0;      ///< fingertip–target distance after the move
  double lean = 0;         ///< forward lean used (rad)
};

/// Writes a child avatar's joint angles directly (avatars are always kinematic).
class AvatarController {
 public:
  /// Controls the `role` child of `stage`; throws InputError when that child is not in the scene.
  AvatarController(Stage& stage, ChildRole role);

  /// Sits upright, hands near the lap, looking at the screen centre.
  void rest();
  /// Turns the head (and eyes) towards `point` in the sandtray frame; clamps to the neck's range.
  GazeResult look_at(const Eigen::Vector3d& point);
  /// Puts the fingertip of `hand` on `screen_point` (z = 0), leaning forward when the arm alone is too short.
  TouchResult touch(const Eigen::Vector2d& screen_point, Hand hand = Hand::right);
  /// Brings `hand` back to rest on the table edge.
  void lower_hand(Hand hand);
  /// Puts the fingertip of `hand` on `target` (sandtray), leaning forward when needed.
  TouchResult reach(const Eigen::Vector3d& target, Hand hand);

 private:
  double qpos(int address) const;
  void set(int address, double value);

  Stage& stage_;
  const AvatarIndex& avatar_;
};

}  // namespace freeplay::stage
