// Speed of the simulated sandtray: idle 10 Hz tick, one active drag per physics step, shuffle-and-settle.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/zones.hpp"

namespace freeplay::sim {
namespace {

std::shared_ptr<const ItemCatalogue> catalogue() {
  static const auto shared = std::make_shared<const ItemCatalogue>(ItemCatalogue::load_default());
  return shared;
}

std::unique_ptr<Sandtray> settled_freeplay_tray() {
  SandtrayConfig config;
  config.raster_width_px = 240;
  auto tray = std::make_unique<Sandtray>(catalogue(), config, Rng(1));
  tray->signal(Signal::StartFreeplay);
  tray->signal(Signal::ShuffleItems);
  for (int i = 0; i < 3000 && !tray->asleep(); ++i) tray->step(kPhysicsStepS);
  return tray;
}

/// One 10 Hz game tick of a tray where nothing moves (target <= 1 us).
void BM_IdleGameTick(benchmark::State& state) {
  auto tray = settled_freeplay_tray();
  if (!tray->asleep()) state.SkipWithError("tray did not settle");
  const auto steps = tray->physics_steps();
  for (auto _ : state) {
    tray->step(0.1);
    benchmark::DoNotOptimize(tray->time());
  }
  if (tray->physics_steps() != steps) state.SkipWithError("the idle tray was stepped");
}
BENCHMARK(BM_IdleGameTick);

/// One 1/60 s physics step while a finger drags an item in circles through the other items (target <= 20 us).
void BM_ActiveDragPhysicsStep(benchmark::State& state) {
  auto tray = settled_freeplay_tray();
  bool grabbed = false;
  for (const auto& item : tray->items()) {
    if (tray->item_at(item.pose.position()) == item.name) {
      grabbed = tray->touch_down(1, item.pose.position()) == TouchOutcome::GrabbedItem;
      break;
    }
  }
  if (!grabbed) state.SkipWithError("no item to grab");
  const Vec2 centre(0.3, -0.17);
  double angle = 0.0;
  for (auto _ : state) {
    angle += 0.25 * kPhysicsStepS / 0.1;  // 25 cm/s on a 10 cm circle
    tray->touch_move(1, centre + 0.1 * Vec2(std::cos(angle), std::sin(angle)));
    tray->step(kPhysicsStepS);
  }
  state.counters["physics_steps"] = static_cast<double>(tray->physics_steps());
}
BENCHMARK(BM_ActiveDragPhysicsStep);

/// Shuffle the 10 items and run the physics until every body sleeps (items pushed apart, damped to rest).
void BM_ShuffleSettle(benchmark::State& state) {
  auto tray = settled_freeplay_tray();
  double steps_per_settle = 0.0;
  std::int64_t rounds = 0;
  for (auto _ : state) {
    const auto before = tray->physics_steps();
    tray->signal(Signal::ShuffleItems);
    for (int i = 0; i < 6000 && !tray->asleep(); ++i) tray->step(kPhysicsStepS);
    steps_per_settle += static_cast<double>(tray->physics_steps() - before);
    ++rounds;
  }
  state.counters["steps_per_settle"] = steps_per_settle / static_cast<double>(std::max<std::int64_t>(1, rounds));
}
BENCHMARK(BM_ShuffleSettle)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace freeplay::sim

namespace freeplay::sim {
namespace {

/// The item snapshot every 10 Hz tick reads (what the children perceive and the robot observes).
void BM_ItemsSnapshot(benchmark::State& state) {
  auto tray = settled_freeplay_tray();
  for (auto _ : state) benchmark::DoNotOptimize(tray->items().size());
}
BENCHMARK(BM_ItemsSnapshot);

/// The same into a reused vector (no allocation).
void BM_ItemsSnapshotReused(benchmark::State& state) {
  auto tray = settled_freeplay_tray();
  std::vector<ItemState> snapshot;
  for (auto _ : state) {
    tray->items(snapshot);
    benchmark::DoNotOptimize(snapshot.data());
  }
}
BENCHMARK(BM_ItemsSnapshotReused);

/// One 10 Hz tick with a child's finger drawing (stroke extension on the 960 px episode raster, then the game step;
/// the background is republished and segmented at the next 4 Hz poll after the stroke ends).
void BM_DrawingTick(benchmark::State& state) {
  SandtrayConfig config;
  config.raster_width_px = 960;
  Sandtray tray(catalogue(), config, Rng(2));
  tray.signal(Signal::StartFreeplay);
  tray.select_colour(PaletteColour::Blue);
  int k = 0;
  for (auto _ : state) {
    if (k % 20 == 0) tray.touch_down(1, {0.05 + 0.004 * (k % 100), -0.1});
    const double t = 0.1 * k;
    tray.touch_move(1, {0.05 + 0.004 * (k % 100) + 0.02 * std::sin(t), -0.1 - 0.05 * std::cos(0.7 * t)});
    if (k % 20 == 19) tray.touch_up(1);
    tray.step(0.1);
    ++k;
  }
  state.counters["segmentations_per_tick"] = static_cast<double>(tray.zone_counters().images) / k;
}
BENCHMARK(BM_DrawingTick)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace freeplay::sim
