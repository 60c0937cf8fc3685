#pragma once
// Two-sample and paired statistics for comparing runs: rank tests (Mann–Whitney U, Wilcoxon signed-rank), effect
// sizes (Cohen's d, Cliff's delta), Holm–Bonferroni adjustment and bootstrap CIs of differences of means.

#include <cstdint>
#include <vector>

#include "freeplay/core/statistics.hpp"

namespace freeplay::analysis {

/// The result of a two-sided rank test.
struct RankTest {
  double statistic = 0.0;  ///< U of the first sample (Mann–Whitney) or V = W⁺ (Wilcoxon signed-rank)
  double z = 0.0;          ///< normal score with tie and continuity correction (0 when exact or degenerate)
  double p_value = 1.0;    ///< two-sided p-value (NaN when a sample is empty, 1 when every value ties)
  bool exact = false;      ///< true when p comes from the exact null distribution (small samples without ties)
  int n = 0;               ///< values used: n₁ + n₂ (Mann–Whitney) or non-zero differences (Wilcoxon)
};

/// Sample sizes below which, when there are no ties (and, for Wilcoxon, no zero differences), p is exact (as R).
inline constexpr int kExactRankTestLimit = 50;

/// Mann–Whitney U test of `a` against `b` (U counts pairs with a > b plus half the ties); two-sided p, exact for
/// small samples without ties, otherwise normal approximation with tie and continuity correction.
RankTest mann_whitney_u(const std::vector<double>& a, const std::vector<double>& b);

/// Wilcoxon signed-rank test of paired differences `differences` against 0 (zeros dropped, tied |d| get average
/// ranks); two-sided p, exact for small n without ties or zeros, otherwise normal approximation with tie and
/// continuity correction.
RankTest wilcoxon_signed_rank(const std::vector<double>& differences);

/// Cohen's d of b − a with the pooled SD (NaN when either sample has fewer than two values or the SD is 0).
double cohens_d(const std::vector<double>& a, const std::vector<double>& b);

/// Cliff's delta: P(b > a) − P(b < a) over all pairs, in [−1, 1] (NaN for an empty sample).
double cliffs_delta(const std::vector<double>& a, const std::vector<double>& b);

/// Holm–Bonferroni step-down adjusted p-values, in the order given (NaN entries stay NaN and are not counted).
std::vector<double> holm_adjust(const std::vector<double>& p_values);

/// Percentile bootstrap CI of mean(b) − mean(a), resampling each sample independently (seeded).
Interval bootstrap_difference_ci(const std::vector<double>& a, const std::vector<double>& b,
                                 double confidence = 0.95, int resamples = 2000, std::uint64_t seed = 1);

/// Ranks of `values` (1-based, ties get the average rank); `tie_term` receives Σ(t³ − t) over tie groups.
std::vector<double> average_ranks(const std::vector<double>& values, double* tie_term = nullptr);

}  // namespace freeplay::analysis
