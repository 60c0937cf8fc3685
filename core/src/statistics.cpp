#include "freeplay/core/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "freeplay/core/rng.hpp"

namespace freeplay {

double mean(const std::vector<double>& values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (const double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

double sample_sd(const std::vector<double>& values) {
  if (values.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  const double m = mean(values);
  double ss = 0.0;
  for (const double v : values) ss += (v - m) * (v - m);
  return std::sqrt(ss / static_cast<double>(values.size() - 1));
}

namespace {

// Where quantile `q` (R type 7) of `n` sorted values lies: the index at or below it and the fraction of the way to the
// next value.
struct QuantilePosition {
  std::size_t below;
  double fraction;
};

QuantilePosition quantile_position(std::size_t n, double q) {
  const double h = (static_cast<double>(n) - 1.0) * std::clamp(q, 0.0, 1.0);
  const auto below = static_cast<std::size_t>(std::floor(h));
  return {below, h - static_cast<double>(below)};
}

// The quantile between the sorted values at the position and after it (the same value at the last one).
double interpolate(const QuantilePosition& p, double at, double after) { return at + p.fraction * (after - at); }

}  // namespace

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const QuantilePosition p = quantile_position(values.size(), q);
  return interpolate(p, values[p.below], values[std::min(p.below + 1, values.size() - 1)]);
}

double median(const std::vector<double>& values) { return quantile(values, 0.5); }

double fraction_at_least(const std::vector<double>& values, double threshold) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto count = std::count_if(values.begin(), values.end(), [&](double v) { return v >= threshold; });
  return static_cast<double>(count) / static_cast<double>(values.size());
}

Interval bootstrap_mean_ci(const std::vector<double>& values, double confidence, int resamples,
                           std::uint64_t seed) {
  if (values.empty()) return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  Rng rng(seed);
  std::vector<double> means;
  means.reserve(static_cast<std::size_t>(resamples));
  const std::size_t n = values.size();
  const IndexDraw draw(n);  // rng.uniform_int(0, n − 1)
  for (int r = 0; r < resamples; ++r) {
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) sum += values[draw(rng)];
    means.push_back(sum / static_cast<double>(n));
  }
  // The two quantiles of the sorted means without sorting them: the order statistics at and after each quantile's
  // position, selected (the same values; a mean is never −0, so no tie between zeros of two signs can differ).
  const auto sorted_quantile = [&means](double q) {
    const QuantilePosition p = quantile_position(means.size(), q);
    const auto at = [&means](std::size_t k) { return means.begin() + static_cast<std::ptrdiff_t>(k); };
    std::nth_element(means.begin(), at(p.below), means.end());
    const double below = means[p.below];
    return interpolate(p, below, p.below + 1 < means.size() ? *std::min_element(at(p.below + 1), means.end()) : below);
  };
  const double alpha = (1.0 - confidence) / 2.0;
  const double low = sorted_quantile(alpha);
  return {low, sorted_quantile(1.0 - alpha)};
}

Summary summarize(const std::vector<double>& values, std::uint64_t seed) {
  std::vector<double> clean;
  clean.reserve(values.size());
  for (const double v : values) {
    if (!std::isnan(v)) clean.push_back(v);
  }
  Summary s;
  s.n = static_cast<int>(clean.size());
  if (clean.empty()) return s;
  s.mean = mean(clean);
  s.sd = clean.size() > 1 ? sample_sd(clean) : 0.0;
  s.median = median(clean);
  if (clean.size() > kBootstrapMaxValues) {
    const double half = 1.959963984540054 * s.sd / std::sqrt(static_cast<double>(clean.size()));
    s.ci95 = {s.mean - half, s.mean + half};
  } else {
    s.ci95 = bootstrap_mean_ci(clean, 0.95, 2000, seed);
  }
  return s;
}

}  // namespace freeplay
