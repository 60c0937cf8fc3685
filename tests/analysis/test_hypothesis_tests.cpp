// Rank tests, effect sizes and Holm against published textbook values and hand computations.

#include <gtest/gtest.h>

#include <cmath>

#include "freeplay/analysis/hypothesis_tests.hpp"

namespace freeplay::analysis {
namespace {

// Hollander & Wolfe (1973, p. 69f), permeability constants of the human chorioamnion (the two-sample example of
// R's wilcox.test help): W = 35, one-sided exact p = 0.1272, so two-sided 0.2544.
TEST(MannWhitney, HollanderWolfeExactExample) {
  const std::vector<double> at_term = {0.80, 0.83, 1.89, 1.04, 1.45, 1.38, 1.91, 1.64, 0.73, 1.46};
  const std::vector<double> early = {1.15, 0.88, 0.90, 0.74, 1.21};
  const auto t = mann_whitney_u(at_term, early);
  EXPECT_TRUE(t.exact);
  EXPECT_DOUBLE_EQ(t.statistic, 35.0);
  EXPECT_NEAR(t.p_value, 0.2544, 0.0005);
  // Swapping the samples gives U' = n1 n2 − U and the same two-sided p.
  const auto swapped = mann_whitney_u(early, at_term);
  EXPECT_DOUBLE_EQ(swapped.statistic, 50.0 - 35.0);
  EXPECT_NEAR(swapped.p_value, t.p_value, 1e-12);
}

// With ties: normal approximation with tie and continuity correction (as R's wilcox.test(exact = FALSE)).
// Ranks of a = {1, 2, 2, 3, 4} in a ∪ b: 1, 3, 3, 5.5, 8 → R = 20.5, U = 5.5; Σ(t³ − t) = 24 + 6 + 24 = 54;
// σ² = 30/12 · (12 − 54/110) = 28.7727; z = (5.5 − 15 + 0.5)/σ = −1.67785; p = 0.09338.
TEST(MannWhitney, TiesUseCorrectedNormalApproximation) {
  const auto t = mann_whitney_u({1, 2, 2, 3, 4}, {2, 3, 4, 4, 5, 6});
  EXPECT_FALSE(t.exact);
  EXPECT_DOUBLE_EQ(t.statistic, 5.5);
  EXPECT_NEAR(t.z, -1.67785, 1e-4);
  EXPECT_NEAR(t.p_value, 0.09338, 1e-4);
}

TEST(MannWhitney, DegenerateSamples) {
  EXPECT_TRUE(std::isnan(mann_whitney_u({}, {1.0, 2.0}).p_value));
  EXPECT_DOUBLE_EQ(mann_whitney_u({3, 3, 3}, {3, 3}).p_value, 1.0);
  // Complete separation of 5 vs 5: two-sided exact p = 2 / C(10, 5) = 2/252.
  EXPECT_NEAR(mann_whitney_u({1, 2, 3, 4, 5}, {6, 7, 8, 9, 10}).p_value, 2.0 / 252.0, 1e-12);
}

// The exact distribution and the normal approximation agree for moderately large samples.
TEST(MannWhitney, ExactAndApproximateAgreeForLargerSamples) {
  std::vector<double> a;
  std::vector<double> b;
  for (int i = 0; i < 40; ++i) a.push_back(i * 1.0);
  for (int i = 0; i < 45; ++i) b.push_back(i * 1.0 + 10.25);
  const auto exact = mann_whitney_u(a, b);
  ASSERT_TRUE(exact.exact);
  b.push_back(b.back());  // one tie forces the approximation (and barely moves the statistic)
  const auto approx = mann_whitney_u(a, b);
  ASSERT_FALSE(approx.exact);
  EXPECT_NEAR(exact.p_value, approx.p_value, 0.01);
}

// Hollander & Wolfe (1973, p. 29f), depression scale before/after (the paired example of R's wilcox.test
// help): V = 40, one-sided exact p = 0.01953 (10/512), two-sided 20/512 = 0.0390625.
TEST(Wilcoxon, HollanderWolfeExactExample) {
  const std::vector<double> x = {1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30};
  const std::vector<double> y = {0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29};
  std::vector<double> d;
  for (std::size_t i = 0; i < x.size(); ++i) d.push_back(x[i] - y[i]);
  const auto t = wilcoxon_signed_rank(d);
  EXPECT_TRUE(t.exact);
  EXPECT_DOUBLE_EQ(t.statistic, 40.0);
  EXPECT_NEAR(t.p_value, 20.0 / 512.0, 1e-12);
  EXPECT_NEAR(t.p_value, 0.0391, 0.0001);
}

// Zeros dropped, tied magnitudes averaged: non-zero d = 1, −1, 2, 2, 3, −4, 5, 6 (n = 8); ranks of |d|: 1.5, 1.5,
// 3.5, 3.5, 5, 6, 7, 8 → V = 28.5; σ² = 8·9·17/24 − 12/48 = 50.75; z = (28.5 − 18 − 0.5)/σ = 1.40372; p = 0.1604.
TEST(Wilcoxon, ZerosAndTiesUseCorrectedNormalApproximation) {
  const auto t = wilcoxon_signed_rank({0, 1, -1, 2, 2, 3, -4, 5, 0, 6});
  EXPECT_FALSE(t.exact);
  EXPECT_EQ(t.n, 8);
  EXPECT_DOUBLE_EQ(t.statistic, 28.5);
  EXPECT_NEAR(t.z, 1.40372, 1e-4);
  EXPECT_NEAR(t.p_value, 0.16040, 1e-4);
}

TEST(Wilcoxon, AllZeroDifferencesGiveNoEvidence) {
  EXPECT_DOUBLE_EQ(wilcoxon_signed_rank({0, 0, 0}).p_value, 1.0);
  EXPECT_TRUE(std::isnan(wilcoxon_signed_rank({}).p_value));
}

TEST(EffectSizes, CohensDAndCliffsDelta) {
  const std::vector<double> a = {1, 2, 3, 4, 5};
  const std::vector<double> b = {3, 4, 5, 6, 7};
  // Both SDs are √2.5, so d = 2 / √2.5.
  EXPECT_NEAR(cohens_d(a, b), 2.0 / std::sqrt(2.5), 1e-12);
  EXPECT_NEAR(cohens_d(b, a), -2.0 / std::sqrt(2.5), 1e-12);
  // b over a: 3 → 0, 4 → +2, 5 → +4, 6 → +5, 7 → +5; 16 / 25.
  EXPECT_NEAR(cliffs_delta(a, b), 0.64, 1e-12);
  EXPECT_NEAR(cliffs_delta(b, a), -0.64, 1e-12);
  EXPECT_DOUBLE_EQ(cliffs_delta({1, 2}, {5, 6}), 1.0);
  EXPECT_TRUE(std::isnan(cohens_d({1.0}, {2.0, 3.0})));
  EXPECT_TRUE(std::isnan(cohens_d({1, 1}, {1, 1})));
}

// R: p.adjust(c(0.01, 0.04, 0.03, 0.005), "holm") = 0.03 0.06 0.06 0.02.
TEST(Holm, KnownVector) {
  const auto adjusted = holm_adjust({0.01, 0.04, 0.03, 0.005});
  ASSERT_EQ(adjusted.size(), 4u);
  EXPECT_NEAR(adjusted[0], 0.03, 1e-12);
  EXPECT_NEAR(adjusted[1], 0.06, 1e-12);
  EXPECT_NEAR(adjusted[2], 0.06, 1e-12);
  EXPECT_NEAR(adjusted[3], 0.02, 1e-12);
}

TEST(Holm, CapsAtOneAndSkipsNaN) {
  const auto adjusted = holm_adjust({0.5, std::nan(""), 0.2});
  EXPECT_NEAR(adjusted[0], 0.5, 1e-12);  // m = 2: 2·0.2 = 0.4, then max(0.4, 1·0.5)
  EXPECT_TRUE(std::isnan(adjusted[1]));
  EXPECT_NEAR(adjusted[2], 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(holm_adjust({0.7, 0.9})[0], 1.0);
}

TEST(AverageRanks, TiesShareTheMeanRank) {
  double ties = 0.0;
  const auto r = average_ranks({10, 20, 10, 30, 10}, &ties);
  EXPECT_EQ(r, (std::vector<double>{2, 4, 2, 5, 2}));
  EXPECT_DOUBLE_EQ(ties, 24.0);
}

TEST(BootstrapDifference, DeterministicAndAroundTheDifference) {
  const std::vector<double> a = {1, 2, 3, 4, 5, 6};
  const std::vector<double> b = {4, 5, 6, 7, 8, 9};
  const auto ci = bootstrap_difference_ci(a, b, 0.95, 2000, 7);
  const auto again = bootstrap_difference_ci(a, b, 0.95, 2000, 7);
  EXPECT_EQ(ci.low, again.low);
  EXPECT_EQ(ci.high, again.high);
  EXPECT_LT(ci.low, 3.0);
  EXPECT_GT(ci.high, 3.0);
  EXPECT_GT(ci.low, 0.0);
}

}  // namespace
}  // namespace freeplay::analysis
