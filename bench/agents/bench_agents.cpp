// Cost of the child model's logic alone (no physics): whole child-child and child-robot sessions on the
// kinematic stand-in tray. Counters: simulated seconds per session, CPU µs per simulated second per child.

#include <benchmark/benchmark.h>

#include "freeplay/agents/session.hpp"

using namespace freeplay::agents;

namespace {

void run_sessions(benchmark::State& state, Condition condition) {
  const ChildModelParams params = default_child_model_params();
  SessionConfig config;
  config.condition = condition;
  const int children = condition == Condition::ChildChild ? 2 : 1;
  std::uint64_t seed = 0;
  double simulated_s = 0.0;
  for (auto _ : state) {
    const SessionResult result = simulate_session(params, config, seed++);
    simulated_s += result.duration_s;
    benchmark::DoNotOptimize(result.duration_s);
  }
  state.counters["sim_s_per_session"] = benchmark::Counter(simulated_s / static_cast<double>(state.iterations()));
  // CPU time per simulated second per child, in microseconds (the target is <= 10).
  state.counters["us_per_sim_s_per_child"] =
      benchmark::Counter(simulated_s * children / 1e6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_ChildChildSession(benchmark::State& state) { run_sessions(state, Condition::ChildChild); }
void BM_ChildRobotSession(benchmark::State& state) { run_sessions(state, Condition::ChildRobot); }

/// 1 000 child-child sessions of agent logic on one core (the budget: <= 30 s).
void BM_ThousandChildChildSessions(benchmark::State& state) {
  const ChildModelParams params = default_child_model_params();
  for (auto _ : state) {
    double total = 0.0;
    for (std::uint64_t seed = 0; seed < 1000; ++seed) total += simulate_session(params, SessionConfig{}, seed).duration_s;
    benchmark::DoNotOptimize(total);
  }
}

}  // namespace

BENCHMARK(BM_ChildChildSession)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ChildRobotSession)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ThousandChildChildSessions)->Unit(benchmark::kSecond)->Iterations(1);
