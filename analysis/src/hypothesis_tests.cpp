#include "freeplay/analysis/hypothesis_tests.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <limits>
#include <numeric>

#include "freeplay/core/rng.hpp"
#include "report_values.hpp"

namespace freeplay::analysis {

namespace {

using detail::kNaN;

/// Two-sided p-value of a standard normal score.
double two_sided_normal_p(double z) {
  const boost::math::normal standard;
  const double lower = boost::math::cdf(standard, z);
  const double upper = boost::math::cdf(boost::math::complement(standard, z));
  return std::min(1.0, 2.0 * std::min(lower, upper));
}

/// Two-sided p-value from the counts of an integer statistic's exact null distribution (index = value).
double two_sided_exact_p(const std::vector<double>& counts, double statistic) {
  const double total = std::accumulate(counts.begin(), counts.end(), 0.0);
  const auto s = static_cast<std::size_t>(std::llround(statistic));
  double at_most = 0.0;
  double at_least = 0.0;
  for (std::size_t u = 0; u < counts.size(); ++u) {
    if (u <= s) at_most += counts[u];
    if (u >= s) at_least += counts[u];
  }
  return std::min(1.0, 2.0 * std::min(at_most, at_least) / total);
}

/// Counts of U = 0 … n₁n₂ over all arrangements of n₁ + n₂ distinct values (U = pairs with x > y).
std::vector<double> mann_whitney_null_counts(int n1, int n2) {
  // count(i, j, u) = count(i − 1, j, u − j) [the largest value is an x] + count(i, j − 1, u) [it is a y].
  std::vector<std::vector<double>> previous(static_cast<std::size_t>(n2) + 1, std::vector<double>{1.0});
  for (int i = 1; i <= n1; ++i) {
    std::vector<std::vector<double>> current(static_cast<std::size_t>(n2) + 1);
    current[0] = {1.0};
    for (int j = 1; j <= n2; ++j) {
      auto& row = current[static_cast<std::size_t>(j)];
      row.assign(static_cast<std::size_t>(i * j) + 1, 0.0);
      const auto& x_largest = previous[static_cast<std::size_t>(j)];
      const auto& y_largest = current[static_cast<std::size_t>(j - 1)];
      for (std::size_t u = 0; u < row.size(); ++u) {
        if (u >= static_cast<std::size_t>(j) && u - static_cast<std::size_t>(j) < x_largest.size()) {
          row[u] += x_largest[u - static_cast<std::size_t>(j)];
        }
        if (u < y_largest.size()) row[u] += y_largest[u];
      }
    }
    previous = std::move(current);
  }
  return previous[static_cast<std::size_t>(n2)];
}

/// Counts of W⁺ = 0 … n(n+1)/2 over the 2ⁿ sign patterns of ranks 1 … n.
std::vector<double> signed_rank_null_counts(int n) {
  std::vector<double> counts(static_cast<std::size_t>(n * (n + 1) / 2) + 1, 0.0);
  counts[0] = 1.0;
  for (int k = 1; k <= n; ++k) {
    for (std::size_t s = counts.size() - 1; s >= static_cast<std::size_t>(k); --s) {
      counts[s] += counts[s - static_cast<std::size_t>(k)];
    }
  }
  return counts;
}

double sign_of(double x) { return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0); }

}  // namespace

std::vector<double> average_ranks(const std::vector<double>& values, double* tie_term) {
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return values[i] < values[j]; });
  std::vector<double> ranks(values.size());
  double ties = 0.0;
  for (std::size_t start = 0; start < order.size();) {
    std::size_t end = start + 1;
    while (end < order.size() && values[order[end]] == values[order[start]]) ++end;
    const double rank = (static_cast<double>(start + 1) + static_cast<double>(end)) / 2.0;
    for (std::size_t k = start; k < end; ++k) ranks[order[k]] = rank;
    const auto t = static_cast<double>(end - start);
    ties += t * t * t - t;
    start = end;
  }
  if (tie_term != nullptr) *tie_term = ties;
  return ranks;
}

RankTest mann_whitney_u(const std::vector<double>& a, const std::vector<double>& b) {
  RankTest result;
  const auto n1 = static_cast<double>(a.size());
  const auto n2 = static_cast<double>(b.size());
  result.n = static_cast<int>(a.size() + b.size());
  if (a.empty() || b.empty()) {
    result.statistic = kNaN;
    result.p_value = kNaN;
    return result;
  }
  std::vector<double> combined(a);
  combined.insert(combined.end(), b.begin(), b.end());
  double tie_term = 0.0;
  const auto ranks = average_ranks(combined, &tie_term);
  const double rank_sum_a = std::accumulate(ranks.begin(), ranks.begin() + static_cast<std::ptrdiff_t>(a.size()), 0.0);
  result.statistic = rank_sum_a - n1 * (n1 + 1.0) / 2.0;
  const bool ties = tie_term > 0.0;
  if (!ties && a.size() < kExactRankTestLimit && b.size() < kExactRankTestLimit) {
    result.exact = true;
    result.p_value = two_sided_exact_p(
        mann_whitney_null_counts(static_cast<int>(a.size()), static_cast<int>(b.size())), result.statistic);
    return result;
  }
  const double n = n1 + n2;
  const double variance = n1 * n2 / 12.0 * ((n + 1.0) - tie_term / (n * (n - 1.0)));
  if (!(variance > 0.0)) return result;  // every value ties: no evidence either way
  const double deviation = result.statistic - n1 * n2 / 2.0;
  result.z = (deviation - 0.5 * sign_of(deviation)) / std::sqrt(variance);
  result.p_value = two_sided_normal_p(result.z);
  return result;
}

RankTest wilcoxon_signed_rank(const std::vector<double>& differences) {
  RankTest result;
  std::vector<double> nonzero;
  std::vector<double> magnitudes;
  for (const double d : differences) {
    if (d == 0.0 || std::isnan(d)) continue;
    nonzero.push_back(d);
    magnitudes.push_back(std::fabs(d));
  }
  result.n = static_cast<int>(nonzero.size());
  if (nonzero.empty()) {
    result.statistic = 0.0;
    result.p_value = differences.empty() ? kNaN : 1.0;
    return result;
  }
  double tie_term = 0.0;
  const auto ranks = average_ranks(magnitudes, &tie_term);
  for (std::size_t i = 0; i < nonzero.size(); ++i) {
    if (nonzero[i] > 0) result.statistic += ranks[i];
  }
  const auto n = static_cast<double>(nonzero.size());
  const bool zeros = nonzero.size() != differences.size();
  if (!zeros && tie_term == 0.0 && nonzero.size() < kExactRankTestLimit) {
    result.exact = true;
    result.p_value = two_sided_exact_p(signed_rank_null_counts(static_cast<int>(nonzero.size())), result.statistic);
    return result;
  }
  const double variance = n * (n + 1.0) * (2.0 * n + 1.0) / 24.0 - tie_term / 48.0;
  if (!(variance > 0.0)) return result;
  const double deviation = result.statistic - n * (n + 1.0) / 4.0;
  result.z = (deviation - 0.5 * sign_of(deviation)) / std::sqrt(variance);
  result.p_value = two_sided_normal_p(result.z);
  return result;
}

double cohens_d(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() < 2 || b.size() < 2) return kNaN;
  const auto n1 = static_cast<double>(a.size());
  const auto n2 = static_cast<double>(b.size());
  const double sd_a = sample_sd(a);
  const double sd_b = sample_sd(b);
  const double pooled = std::sqrt(((n1 - 1.0) * sd_a * sd_a + (n2 - 1.0) * sd_b * sd_b) / (n1 + n2 - 2.0));
  if (!(pooled > 0.0)) return kNaN;
  return (mean(b) - mean(a)) / pooled;
}

double cliffs_delta(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.empty() || b.empty()) return kNaN;
  std::vector<double> sorted_a(a);
  std::sort(sorted_a.begin(), sorted_a.end());
  double dominance = 0.0;
  for (const double value : b) {
    const auto below = std::lower_bound(sorted_a.begin(), sorted_a.end(), value) - sorted_a.begin();
    const auto above = sorted_a.end() - std::upper_bound(sorted_a.begin(), sorted_a.end(), value);
    dominance += static_cast<double>(below) - static_cast<double>(above);
  }
  return dominance / (static_cast<double>(a.size()) * static_cast<double>(b.size()));
}

std::vector<double> holm_adjust(const std::vector<double>& p_values) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < p_values.size(); ++i) {
    if (!std::isnan(p_values[i])) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return p_values[i] < p_values[j]; });
  std::vector<double> adjusted(p_values.size(), kNaN);
  const auto m = static_cast<double>(order.size());
  double running_max = 0.0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    running_max = std::max(running_max, std::min(1.0, (m - static_cast<double>(k)) * p_values[order[k]]));
    adjusted[order[k]] = running_max;
  }
  return adjusted;
}

Interval bootstrap_difference_ci(const std::vector<double>& a, const std::vector<double>& b, double confidence,
                                 int resamples, std::uint64_t seed) {
  if (a.empty() || b.empty()) return {kNaN, kNaN};
  Rng rng(seed);
  auto resampled_mean = [&rng](const std::vector<double>& values) {
    const auto n = static_cast<std::int64_t>(values.size());
    double sum = 0.0;
    for (std::int64_t i = 0; i < n; ++i) sum += values[static_cast<std::size_t>(rng.uniform_int(0, n - 1))];
    return sum / static_cast<double>(n);
  };
  std::vector<double> differences;
  differences.reserve(static_cast<std::size_t>(resamples));
  for (int r = 0; r < resamples; ++r) {
    const double mean_a = resampled_mean(a);
    differences.push_back(resampled_mean(b) - mean_a);
  }
  const double alpha = (1.0 - confidence) / 2.0;
  return {quantile(differences, alpha), quantile(differences, 1.0 - alpha)};
}

}  // namespace freeplay::analysis
