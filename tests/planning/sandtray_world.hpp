#pragma once
// Test adapter: a real `freeplay::sim::Sandtray` seen through the executor's callbacks, and a 10 Hz episode loop.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/planning/layout.hpp"
#include "freeplay/planning/move_executor.hpp"
#include "freeplay/runner/sandtray_world.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"

namespace freeplay::planning::testing {

/// The shared default catalogue.
inline std::shared_ptr<const sim::ItemCatalogue> default_catalogue() {
  static const auto catalogue = std::make_shared<const sim::ItemCatalogue>(sim::ItemCatalogue::load_default());
  return catalogue;
}

/// A sandtray in the free-play state with a small raster (physics does not depend on it).
inline std::unique_ptr<sim::Sandtray> free_play_tray(std::uint64_t seed = 5) {
  sim::SandtrayConfig config;
  config.raster_width_px = 240;
  auto tray = std::make_unique<sim::Sandtray>(default_catalogue(), config, Rng(seed));
  tray->signal(sim::Signal::StartFreeplay);
  return tray;
}

/// The catalogue's polygons as layout shapes.
inline std::vector<ItemShape> catalogue_shapes() {
  std::vector<ItemShape> shapes;
  for (const auto& spec : default_catalogue()->items()) shapes.push_back({spec.name, spec.polygon});
  return shapes;
}

/// Teleports the layout's items onto the tray (the others stay in the stash).
inline void place_layout(sim::Sandtray& tray, const Layout& layout) {
  for (const auto& item : layout.items) tray.place_item(item.name, item.pose);
}

/// The tray as the real planner sees it (the one adapter the episode loop and `freeplay plan` use too).
inline MoveWorld sandtray_world(const sim::Sandtray& tray) { return runner::sandtray_move_world(tray); }

/// What happened during one move run in the physics.
struct PhysicsRun {
  MoveOutcome outcome;                   ///< the executor's outcome (placement error filled on release)
  std::vector<TimedPose> sent;           ///< poses as delivered
  std::vector<double> sent_at;           ///< tray time of each delivered pose
  std::vector<int> feedback;             ///< feedback percentages in order
  std::optional<double> release_time;    ///< tray time of `releasing_<item>`
};

/// Runs the 10 Hz loop (executor step, then tray step) until the move ended and the robot released the item, or
/// `max_s` passed; `each_tick(tick)` runs before every executor step (e.g. a child's finger, a cancel).
template <typename TickHook>
PhysicsRun run_in_physics(sim::Sandtray& tray, MoveExecutor& executor, const MoveGoal& goal, Rng& rng,
                          TickHook each_tick, ArmFollower* arm = nullptr, double max_s = 40.0) {
  PhysicsRun run;
  const MoveWorld world = sandtray_world(tray);
  MoveOutputs outputs;
  outputs.finger = [&](const TimedPose& pose) {
    tray.robot_pose(pose.position);
    run.sent.push_back(pose);
    run.sent_at.push_back(tray.time());
  };
  outputs.feedback = [&](int percentage) { run.feedback.push_back(percentage); };
  outputs.arm = arm;
  executor.start(goal, world, rng);
  const std::string releasing = "releasing_" + goal.item;
  for (int tick = 0; tick < static_cast<int>(max_s * 10.0); ++tick) {
    each_tick(tick);
    executor.step(0.1, world, outputs);
    tray.step(0.1);
    for (const Event& event : tray.drain_events()) {
      if (event.type() == "interaction_event" && event.data().value("message", "") == releasing) {
        run.release_time = event.t;
        executor.observe_release(tray.item(goal.item).pose.position());
      }
    }
    if (executor.status() != MoveStatus::Running && (run.release_time || run.sent.empty())) break;
  }
  run.outcome = executor.current();
  return run;
}

/// `run_in_physics` without a per-tick hook.
inline PhysicsRun run_in_physics(sim::Sandtray& tray, MoveExecutor& executor, const MoveGoal& goal, Rng& rng,
                                 ArmFollower* arm = nullptr) {
  return run_in_physics(tray, executor, goal, rng, [](int) {}, arm);
}

}  // namespace freeplay::planning::testing
