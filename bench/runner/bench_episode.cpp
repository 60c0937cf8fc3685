// End-to-end speed of the episode loop: simulated seconds per wall second for each default scenario (no cameras),
// and the peak resident memory of the worker.

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>

#include "freeplay/runner/episode.hpp"

using namespace freeplay::runner;

namespace {

const SharedModels& models() {
  static const SharedModels m = SharedModels::load_default();
  return m;
}

void run_scenario(benchmark::State& state, const char* file) {
  const auto scenario = load_scenario(std::string(FREEPLAY_SCENARIOS_DIR) + "/" + file);
  const std::atomic<bool> stop{false};
  double simulated = 0.0;
  double freeplay = 0.0;
  double wall = 0.0;
  std::uint64_t seed = 1;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const auto result = run_episode(scenario, seed++, models(), stop);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    simulated += result.simulated_s;
    freeplay += result.duration_s;
    benchmark::DoNotOptimize(result.record);
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["sim_s_per_wall_s"] = simulated / wall;            // whole protocol
  state.counters["freeplay_s_per_wall_s"] = freeplay / wall;        // free play only
  state.counters["freeplay_min_per_episode"] = freeplay / 60.0 / static_cast<double>(state.iterations());
  state.counters["peak_rss_mb"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}

void BM_ChildChildEpisode(benchmark::State& state) { run_scenario(state, "child-child.yaml"); }
void BM_ChildRobotAsocialEpisode(benchmark::State& state) { run_scenario(state, "child-robot-asocial.yaml"); }
void BM_ChildRobotSocialEpisode(benchmark::State& state) { run_scenario(state, "child-robot-social.yaml"); }

}  // namespace

BENCHMARK(BM_ChildChildEpisode)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(BM_ChildRobotAsocialEpisode)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(BM_ChildRobotSocialEpisode)->Unit(benchmark::kMillisecond)->Iterations(10);
