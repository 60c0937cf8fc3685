#pragma once
// Descriptive statistics shared by calibration, summaries and comparisons (deterministic, seeded bootstrap).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace freeplay {

/// Arithmetic mean (NaN for an empty sample).
double mean(const std::vector<double>& values);
/// Sample standard deviation with n − 1 (NaN for fewer than two values).
double sample_sd(const std::vector<double>& values);
/// Quantile with linear interpolation between order statistics (R type 7); q in [0, 1].
double quantile(std::vector<double> values, double q);
/// Median (quantile 0.5).
double median(const std::vector<double>& values);
/// Fraction of values ≥ `threshold` (e.g. survival of session durations).
double fraction_at_least(const std::vector<double>& values, double threshold);

/// A confidence interval.
struct Interval {
  double low = 0.0;   ///< lower bound
  double high = 0.0;  ///< upper bound
};

/// Percentile bootstrap CI of the mean, with `resamples` resamples drawn from a generator seeded by `seed`.
Interval bootstrap_mean_ci(const std::vector<double>& values, double confidence = 0.95, int resamples = 2000,
                           std::uint64_t seed = 1);

/// Mean, SD, median and a bootstrap CI of one metric over episodes.
struct Summary {
  int n = 0;              ///< number of values
  double mean = 0.0;      ///< arithmetic mean
  double sd = 0.0;        ///< sample SD (0 when n < 2)
  double median = 0.0;    ///< median
  Interval ci95;          ///< 95 % bootstrap CI of the mean
};

/// Samples larger than this get the normal-approximation CI of the mean (mean ± 1.96 SD/√n) instead of the
/// bootstrap, whose cost grows with n (at this size the two agree to well under 1 % of the interval).
inline constexpr std::size_t kBootstrapMaxValues = 5000;

/// Summarises a sample (NaN values are ignored).
Summary summarize(const std::vector<double>& values, std::uint64_t seed = 1);

}  // namespace freeplay
