#include <gtest/gtest.h>

#include <cmath>

#include "freeplay/core/rng.hpp"
#include "freeplay/core/statistics.hpp"

using namespace freeplay;

TEST(Statistics, TextbookValues) {
  const std::vector<double> v = {2, 4, 4, 4, 5, 5, 7, 9};
  EXPECT_DOUBLE_EQ(mean(v), 5.0);
  EXPECT_NEAR(sample_sd(v), 2.138089935, 1e-9);
  EXPECT_DOUBLE_EQ(median(v), 4.5);
  EXPECT_DOUBLE_EQ(quantile({1, 2, 3, 4}, 0.25), 1.75);  // R type 7
  EXPECT_DOUBLE_EQ(fraction_at_least(v, 5), 0.5);
  EXPECT_TRUE(std::isnan(mean({})));
}

TEST(Statistics, BootstrapCoverageOnSyntheticNormalData) {
  // 200 samples of n = 40 from N(10, 2²): the 95 % percentile-bootstrap CI should cover 10 about 93–96 % of
  // the time (percentile bootstrap under-covers slightly at this n); accept [0.88, 0.99].
  Rng rng(11);
  int covered = 0;
  const int trials = 200;
  for (int t = 0; t < trials; ++t) {
    std::vector<double> sample(40);
    for (auto& x : sample) x = rng.normal(10.0, 2.0);
    const auto ci = bootstrap_mean_ci(sample, 0.95, 1000, static_cast<std::uint64_t>(t));
    if (ci.low <= 10.0 && 10.0 <= ci.high) ++covered;
  }
  const double coverage = covered / static_cast<double>(trials);
  EXPECT_GE(coverage, 0.88);
  EXPECT_LE(coverage, 0.99);
}

// The interval's ends are exactly the quantiles (R type 7) of the sorted resample means: sizes with and without ties,
// integer data (many equal means), one value, and confidences whose positions fall on and between order statistics.
TEST(Statistics, BootstrapIntervalIsTheQuantilesOfTheSortedMeans) {
  Rng data(3);
  for (const std::size_t n : {1u, 2u, 7u, 40u, 105u}) {
    for (const int resamples : {1, 2, 2000, 2001}) {
      std::vector<double> values(n);
      for (auto& v : values) v = n == 7 ? static_cast<double>(data.uniform_int(0, 3)) : data.normal(0.0, 1.0);
      for (const double confidence : {0.95, 0.5, 0.0}) {
        const std::uint64_t seed = n * 31 + static_cast<std::uint64_t>(resamples);
        Rng rng(seed);
        const IndexDraw draw(n);
        std::vector<double> means;
        for (int r = 0; r < resamples; ++r) {
          double sum = 0.0;
          for (std::size_t i = 0; i < n; ++i) sum += values[draw(rng)];
          means.push_back(sum / static_cast<double>(n));
        }
        const double alpha = (1.0 - confidence) / 2.0;
        const auto ci = bootstrap_mean_ci(values, confidence, resamples, seed);
        EXPECT_EQ(ci.low, quantile(means, alpha)) << n << " values, " << resamples << " resamples, " << confidence;
        EXPECT_EQ(ci.high, quantile(means, 1.0 - alpha)) << n << " values, " << resamples << " resamples";
      }
    }
  }
}

TEST(Statistics, SummaryIgnoresNaNAndIsSeeded) {
  const std::vector<double> v = {1, 2, std::nan(""), 3};
  const auto a = summarize(v, 5);
  const auto b = summarize(v, 5);
  EXPECT_EQ(a.n, 3);
  EXPECT_DOUBLE_EQ(a.mean, 2.0);
  EXPECT_DOUBLE_EQ(a.ci95.low, b.ci95.low);
  EXPECT_LE(a.ci95.low, a.mean);
  EXPECT_GE(a.ci95.high, a.mean);
}
