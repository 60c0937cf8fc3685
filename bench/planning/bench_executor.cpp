// Speed of the move executor: the per-tick cost of streaming, the sync metrics, a whole move in the physics.

#include <benchmark/benchmark.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/planning/layout.hpp"
#include "freeplay/planning/move_executor.hpp"
#include "freeplay/runner/sandtray_world.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"

namespace {

using namespace freeplay;
using namespace freeplay::planning;

// A world of one item and nothing else (the path is a 0.55 m diagonal-then-straight A* path of ~110 poses).
MoveWorld empty_world() {
  MoveWorld world;
  world.item_centre = [](const std::string&) -> std::optional<Vec2> { return Vec2(0.02, -0.02); };
  world.footprints = [] {
    return std::vector<Obstacle>{{"hippo", {{0.0, -0.04}, {0.04, -0.04}, {0.04, 0.0}, {0.0, 0.0}}}};
  };
  world.held_by_child = [](const std::string&) { return false; };
  return world;
}

/// An arm that points exactly at the finger (the follower call and the report bookkeeping are what is measured).
class PerfectArm : public ArmFollower {
 public:
  FollowReport follow(const Vec2& finger, double /*t*/) override { return {finger, true}; }
};

void stream_ticks(benchmark::State& state, ArmFollower* arm) {
  MoveExecutor executor(std::shared_ptr<const MotionPlanner>(make_planner("astar")), MoveExecutorConfig{});
  const MoveWorld world = empty_world();
  Vec2 sink_sum = Vec2::Zero();
  MoveOutputs outputs;
  outputs.finger = [&sink_sum](const TimedPose& pose) { sink_sum += pose.position; };
  outputs.feedback = [](int percentage) { benchmark::DoNotOptimize(percentage); };
  outputs.arm = arm;
  Rng rng(1);
  const MoveGoal goal{"hippo", {0.57, -0.31}};
  for (auto _ : state) {
    if (executor.status() != MoveStatus::Running) {
      state.PauseTiming();
      executor.start(goal, world, rng);
      state.ResumeTiming();
    }
    executor.step(0.1, world, outputs);  // one 10 Hz tick: one pose, feedback, steal check (sync at the last)
  }
  benchmark::DoNotOptimize(sink_sum);
  state.counters["poses_per_move"] = static_cast<double>(executor.current().poses.size());
}

void BM_ExecutorTick(benchmark::State& state) { stream_ticks(state, nullptr); }
BENCHMARK(BM_ExecutorTick);

void BM_ExecutorTickWithArm(benchmark::State& state) {
  PerfectArm arm;
  stream_ticks(state, &arm);
}
BENCHMARK(BM_ExecutorTickWithArm);

void BM_SyncMetrics(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::vector<TimedPose> finger;
  std::vector<FollowReport> tips;
  for (std::size_t i = 0; i < n; ++i) {
    finger.push_back({0.1 * static_cast<double>(i), {0.005 * static_cast<double>(i), -0.1}});
    tips.push_back({finger[i >= 3 ? i - 3 : 0].position, true});
  }
  for (auto _ : state) benchmark::DoNotOptimize(sync_metrics(finger, tips));
}
BENCHMARK(BM_SyncMetrics)->Arg(20)->Arg(100)->Arg(250);

// One whole move in the physics on a 10-item layout: plan, 10 Hz poses into the sandtray, step it, release.
void BM_WholeMoveInPhysics(benchmark::State& state) {
  const auto catalogue = std::make_shared<const sim::ItemCatalogue>(sim::ItemCatalogue::load_default());
  std::vector<ItemShape> shapes;
  for (const auto& spec : catalogue->items()) shapes.push_back({spec.name, spec.polygon});
  sim::SandtrayConfig config;
  config.raster_width_px = 240;
  sim::Sandtray tray(catalogue, config, Rng(1));
  tray.signal(sim::Signal::StartFreeplay);
  Rng layout_rng(1);
  const Layout layout = random_layout(shapes, 10, layout_rng);
  const auto planner = std::shared_ptr<const MotionPlanner>(make_planner("astar"));
  const MoveWorld world = runner::sandtray_move_world(tray);
  MoveOutputs outputs;
  outputs.finger = [&tray](const TimedPose& pose) { tray.robot_pose(pose.position); };
  Rng rng(2);
  std::size_t ticks = 0;
  std::size_t moves = 0;
  const std::string item = layout.items.front().name;
  for (auto _ : state) {
    state.PauseTiming();
    for (const auto& placed : layout.items) tray.place_item(placed.name, placed.pose);
    tray.step(0.1);
    tray.drain_events();
    state.ResumeTiming();
    MoveExecutor executor(planner, MoveExecutorConfig{});
    executor.start({item, moves % 2 == 0 ? Vec2(0.45, -0.05) : Vec2(0.10, -0.30)}, world, rng);
    bool released = false;
    while (!released && ticks < 100000000) {
      executor.step(0.1, world, outputs);
      tray.step(0.1);
      ++ticks;
      for (const auto& event : tray.drain_events()) {
        released = released || event.get<events::InteractionEvent>() != nullptr;
      }
    }
    ++moves;
  }
  state.counters["ticks_per_move"] = static_cast<double>(ticks) / static_cast<double>(moves);
}
BENCHMARK(BM_WholeMoveInPhysics)->Unit(benchmark::kMicrosecond);

}  // namespace
