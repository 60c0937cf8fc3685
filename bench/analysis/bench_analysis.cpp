// Speed of the comparison statistics: rank tests (exact and approximate) and a whole compare of two variants.

#include <benchmark/benchmark.h>

#include "freeplay/analysis/compare.hpp"
#include "freeplay/core/rng.hpp"

namespace {

using namespace freeplay;

std::vector<double> draw(std::uint64_t seed, int n) {
  Rng rng(seed);
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(rng.normal(0.0, 1.0));
  return v;
}

void BM_MannWhitneyExact40(benchmark::State& state) {
  const auto a = draw(1, 40);
  const auto b = draw(2, 45);
  for (auto _ : state) benchmark::DoNotOptimize(analysis::mann_whitney_u(a, b));
}
BENCHMARK(BM_MannWhitneyExact40);

void BM_MannWhitneyNormal1000(benchmark::State& state) {
  const auto a = draw(1, 1000);
  const auto b = draw(2, 1000);
  for (auto _ : state) benchmark::DoNotOptimize(analysis::mann_whitney_u(a, b));
}
BENCHMARK(BM_MannWhitneyNormal1000);

// The baselines suite's shape: 30 paired episodes per condition, 20 metrics, 2000 bootstrap resamples.
void BM_CompareTwoVariants30Episodes20Metrics(benchmark::State& state) {
  analysis::Sample a{"a", {}};
  analysis::Sample b{"b", {}};
  Rng rng(3);
  for (int i = 0; i < 30; ++i) {
    analysis::EpisodeValues ea{"a", i, static_cast<std::uint64_t>(i), {}};
    analysis::EpisodeValues eb{"b", i, static_cast<std::uint64_t>(i), {}};
    for (int m = 0; m < 20; ++m) {
      const auto name = "metrics.m" + std::to_string(m);
      const double child = rng.normal(0.0, 1.0);
      ea.metrics[name] = child + rng.normal(0.0, 0.3);
      eb.metrics[name] = child + 0.2 + rng.normal(0.0, 0.3);
    }
    a.episodes.push_back(ea);
    b.episodes.push_back(eb);
  }
  for (auto _ : state) benchmark::DoNotOptimize(analysis::compare_samples(a, b));
}
BENCHMARK(BM_CompareTwoVariants30Episodes20Metrics)->Unit(benchmark::kMillisecond);

}  // namespace
