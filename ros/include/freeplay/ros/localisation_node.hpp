#pragma once
// Fiducial localisation inside `freeplay serve`: the game's 5 s marker display on `sandtray/signals/robot_localising`
// and the simulated NAO's `sandtray_localisation` node, which looks for the field in its rendered head camera,
// then publishes the held `odom` → `sandtray` and `arm_reach` frames at every tick and speaks its two lines.

#include <memory>
#include <string>
#include <vector>

#include "freeplay/localisation/localiser.hpp"
#include "freeplay/ros/graph.hpp"
#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/stage/renderer.hpp"

namespace freeplay::ros_live {

/// The signal (under `sandtray/signals/`) that shows the markers and starts a search.
inline constexpr const char* kLocalisingSignal = "robot_localising";

/// The marker display and the simulated NAO's localisation node of one served child-robot episode.
class ServedLocalisation {
 public:
  /// A node with `settings`; the NAO's camera renders with `renderer` (the stage is built at the first signal).
  ServedLocalisation(localisation::LocaliserSettings settings, stage::RendererOptions renderer);
  ~ServedLocalisation();
  ServedLocalisation(const ServedLocalisation&) = delete;
  ServedLocalisation& operator=(const ServedLocalisation&) = delete;

  /// Handles `sandtray/signals/<name>` received at sandtray time `t`; true when it was `robot_localising`.
  bool on_signal(const std::string& name, double t);
  /// One tick: keeps the screen's markers for 5 s, searches the camera image while looking, and once localised
  /// appends `odom` → `sandtray` and `arm_reach` to `frames`. Returns the lines the robot says (`speech`).
  std::vector<std::string> observe(const runner::EpisodeSnapshot& snapshot, std::vector<ros_graph::Transform>& frames);
  /// True once this node publishes `arm_reach` (localised, shoulder within reach): nobody else should.
  bool publishes_arm_reach() const { return publishes_arm_reach_; }
  /// True while the game shows the marker field (the 5 s after a signal, seen at the last tick).
  bool markers_on_screen() const { return markers_on_screen_; }
  /// The simulated NAO's stage (built at the first signal; null before).
  const stage::Stage* stage() const;
  /// The node's state (for tests and logs).
  const localisation::Localiser& localiser() const { return localiser_; }

 private:
  struct Stage;
  localisation::Localiser localiser_;
  localisation::MarkerDisplay display_;
  stage::RendererOptions renderer_options_;
  std::unique_ptr<Stage> stage_;
  bool markers_on_screen_ = false;
  bool publishes_arm_reach_ = false;
};

}  // namespace freeplay::ros_live
