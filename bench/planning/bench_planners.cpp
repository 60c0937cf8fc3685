// Time per plan of every planner on the same random tray layouts (0, 5, 10 items).

#include <benchmark/benchmark.h>

#include "cases.hpp"

namespace freeplay::planning::bench {
namespace {

constexpr int kCasesPerSize = 32;

void plan_round_robin(benchmark::State& state, const std::string& name) {
  const int n_items = static_cast<int>(state.range(0));
  auto cases = make_cases(n_items, kCasesPerSize, 1000 + static_cast<std::uint64_t>(n_items));
  for (auto& request : cases) apply_budget(name, request);
  const auto planner = make_planner(name);
  Rng rng(7);
  std::size_t next = 0;
  std::int64_t successes = 0;
  double length = 0.0;
  for (auto _ : state) {
    const PlanResult result = planner->plan(cases[next], rng);
    benchmark::DoNotOptimize(result.path.data());
    next = (next + 1) % cases.size();
    if (result.ok) {
      ++successes;
      length += result.metrics.path_length_m;
    }
  }
  state.counters["success_rate"] =
      benchmark::Counter(static_cast<double>(successes) / static_cast<double>(state.iterations()));
  state.counters["path_length_m"] =
      benchmark::Counter(successes > 0 ? length / static_cast<double>(successes) : 0.0);
}

void BM_AStar(benchmark::State& state) { plan_round_robin(state, "astar"); }
void BM_RRTConnect(benchmark::State& state) { plan_round_robin(state, "rrtconnect"); }
void BM_PRMstar(benchmark::State& state) { plan_round_robin(state, "prmstar"); }
void BM_RRTstar1000(benchmark::State& state) { plan_round_robin(state, "rrtstar"); }
void BM_BITstar50ms(benchmark::State& state) { plan_round_robin(state, "bitstar"); }

BENCHMARK(BM_AStar)->Arg(0)->Arg(5)->Arg(10)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RRTConnect)->Arg(0)->Arg(5)->Arg(10)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PRMstar)->Arg(0)->Arg(5)->Arg(10)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RRTstar1000)->Arg(0)->Arg(5)->Arg(10)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BITstar50ms)->Arg(0)->Arg(5)->Arg(10)->Unit(benchmark::kMicrosecond)->Iterations(64);

}  // namespace
}  // namespace freeplay::planning::bench
