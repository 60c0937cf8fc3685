// Robot policies' per-decision cost: the asocial play node's choice of a move over a drawn map's zones.

#include <benchmark/benchmark.h>

#include <cmath>

#include "freeplay/policies/asocial.hpp"

namespace {

using namespace freeplay;
using namespace freeplay::policies;

// 40 zones of 60-vertex polygons (a map with drawing on it) and the ten items; every item already home or not.
Observation crowded_tray(bool items_home) {
  Observation o;
  const char* colours[] = {"green", "blue", "yellow", "purple", "white"};
  for (int z = 0; z < 40; ++z) {
    ZoneObservation zone;
    zone.colour = colours[z % 5];
    const Vec2 centre(0.03 + 0.014 * z, -0.05 - 0.006 * (z % 7));
    for (int v = 0; v < 60; ++v) {
      const double a = 2.0 * 3.141592653589793 * v / 60.0;
      zone.polygon.push_back(centre + Vec2(0.02 * std::cos(a), 0.012 * std::sin(a)));
    }
    zone.centroid = vertex_mean(zone.polygon);
    o.zones.push_back(std::move(zone));
  }
  for (std::size_t i = 0; i < asocial_item_order().size(); ++i) {
    ItemObservation item;
    item.name = asocial_item_order()[i];
    item.pose = items_home ? Pose2{o.zones[i].centroid.x(), o.zones[i].centroid.y(), 0.0} : Pose2{0.3, -0.3, 0.0};
    o.items.push_back(item);
  }
  return o;
}

// One choose_move (the play node's place_random_item), zones as above.
void BM_AsocialChooseMove(benchmark::State& state) {
  AsocialPolicy policy({});
  policy.reset({}, Rng(1));
  const Observation observation = crowded_tray(state.range(0) != 0);
  for (auto _ : state) benchmark::DoNotOptimize(policy.choose_move(observation));
}
BENCHMARK(BM_AsocialChooseMove)->Arg(0)->Arg(1)->ArgName("items_home");

}  // namespace
