#pragma once
// Comparing two samples of episodes metric by metric: means with bootstrap CIs, the difference, effect sizes,
// Mann–Whitney U with Holm–Bonferroni correction across metrics, and the paired analysis (Wilcoxon signed-rank,
// paired bootstrap CI) when both samples ran the same seeds (common random numbers: the same synthetic children).

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/analysis/hypothesis_tests.hpp"
#include "freeplay/analysis/run_data.hpp"

namespace freeplay::analysis {

/// Settings of a comparison.
struct CompareOptions {
  std::vector<std::string> metrics;  ///< glob patterns of the metrics to compare (empty: all)
  double confidence = 0.95;          ///< level of every CI
  int resamples = 2000;              ///< bootstrap resamples
  std::uint64_t seed = 1;            ///< bootstrap seed (each metric derives its own stream from it and its name)
  double alpha = 0.05;               ///< significance level applied to Holm-adjusted p-values
  bool allow_paired = true;          ///< pair by seed when both samples ran the same seeds
};

/// One side of a comparison for one metric.
struct SideSummary {
  int n = 0;            ///< episodes with a value
  double mean = 0.0;    ///< mean
  double sd = 0.0;      ///< sample SD (NaN for n < 2)
  Interval ci;          ///< bootstrap CI of the mean
};

/// The paired analysis of one metric (episodes matched by seed).
struct PairedComparison {
  int pairs = 0;                ///< matched episodes
  double mean_difference = 0.0; ///< mean of B − A over pairs
  Interval ci;                  ///< paired bootstrap CI of the mean difference
  RankTest wilcoxon;            ///< Wilcoxon signed-rank test of the differences
  double p_holm = 1.0;          ///< Holm-adjusted across the compared metrics
};

/// Everything measured for one metric.
struct MetricComparison {
  std::string metric;                     ///< dotted name
  SideSummary a;                          ///< sample A
  SideSummary b;                          ///< sample B
  double difference = 0.0;                ///< mean(B) − mean(A)
  Interval difference_ci;                 ///< bootstrap CI of the difference (independent resampling)
  double cohens_d = 0.0;                  ///< (B − A) / pooled SD
  double cliffs_delta = 0.0;              ///< P(B > A) − P(B < A)
  RankTest mann_whitney;                  ///< Mann–Whitney U of A against B
  double p_holm = 1.0;                    ///< Mann–Whitney p, Holm-adjusted across the compared metrics
  std::optional<PairedComparison> paired; ///< present when both samples ran the same seeds
  bool significant = false;               ///< adjusted p < α (the paired test when paired)
};

/// A labelled sample of episodes (one variant of one run).
struct Sample {
  std::string label;                    ///< e.g. "runs/a:child-robot-social"
  std::vector<EpisodeValues> episodes;  ///< its episodes
};

/// The result of comparing sample B against sample A.
struct Comparison {
  std::string label_a;                    ///< sample A
  std::string label_b;                    ///< sample B
  CompareOptions options;                 ///< the settings used
  std::vector<MetricComparison> metrics;  ///< compared metrics, sorted by name
  std::vector<std::string> only_in_a;     ///< selected metrics that only A has (not compared)
  std::vector<std::string> only_in_b;     ///< selected metrics that only B has (not compared)

  /// True when every compared metric was paired.
  bool paired() const;
};

/// Compares `b` against `a`; InputError when a pattern of `options.metrics` matches no metric of either sample.
Comparison compare_samples(const Sample& a, const Sample& b, const CompareOptions& options = {});

/// An aligned, readable table of one comparison (with a legend line).
std::string comparison_table(const Comparison& comparison);

/// Every number of one comparison as JSON (NaN becomes null).
nlohmann::json comparison_json(const Comparison& comparison);

}  // namespace freeplay::analysis
