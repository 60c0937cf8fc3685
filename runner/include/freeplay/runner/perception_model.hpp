#pragma once
// The robot's perception of a child (face detection, head-pose gaze, voice activity) with noise, latency and
// dropout — what gazr, a VAD and the touch frames would report in the real setup, never the child's state.

#include <deque>
#include <optional>
#include <string>

#include "freeplay/agents/perception.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/runner/episode_settings.hpp"

namespace freeplay::runner {

/// What is observable about a child at one instant (input of the perception model).
struct ChildTruth {
  std::string seat;                                   ///< "purple" / "yellow"
  agents::GazeKind gaze = agents::GazeKind::Away;      ///< where the child looks
  Vec2 gaze_point = Vec2::Zero();                     ///< looked-at screen point (tray/item)
  bool speaking = false;                              ///< voice active
  bool speech_to_partner = false;                     ///< the utterance is addressed to the partner (the robot)
  double seconds_since_touch = 1e9;                   ///< since the child's last touch began (touch frames)
  std::optional<std::string> moving_item;             ///< item under the child's finger (touch frames + TF)
};

/// Turns observable child behaviour into a noisy, delayed `PerceivedChild` (one instance per child and episode).
class PerceptionModel {
 public:
  /// A model with its own random stream.
  PerceptionModel(PerceptionSettings settings, Rng rng);
  /// The perception the policy gets at time `t` for the truth observed at `t` (delayed by the latency).
  policies::PerceivedChild perceive(const ChildTruth& truth, double t);

 private:
  policies::PerceivedChild sense(const ChildTruth& truth);
  PerceptionSettings settings_;
  Rng rng_;
  std::deque<std::pair<double, policies::PerceivedChild>> pipeline_;
  std::optional<policies::PerceivedChild> latest_;
};

}  // namespace freeplay::runner
