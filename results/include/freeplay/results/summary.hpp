#pragma once
// Per-condition summaries of a run: mean, SD, median and 95 % bootstrap CI of every metric, with the session
// durations beside the PInSoRo values.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "freeplay/core/statistics.hpp"

namespace freeplay::results {

/// What the real PInSoRo sessions measured for one condition (pinsoro-targets.md §2).
struct PinsoroDurations {
  int sessions = 0;              ///< number of sessions
  double mean_min = 0.0;         ///< mean duration (min)
  double sd_min = 0.0;           ///< SD (min)
  double median_min = 0.0;       ///< median (min)
  double survival_10 = 0.0;      ///< fraction still playing at 10 min
  double survival_20 = 0.0;      ///< … at 20 min
  double survival_30 = 0.0;      ///< … at 30 min
};

/// The PInSoRo reference for "child-child" or "child-robot" (asocial robot); nullptr for other conditions.
const PinsoroDurations* pinsoro_durations(const std::string& condition);

/// What flatten_numbers does with a null leaf (nlohmann writes NaN as null).
enum class NullLeaves { skip, as_nan };

/// Numeric (and boolean, as 0/1) leaves of a JSON object as dotted keys (e.g. "label_share.purple.cooperative").
std::map<std::string, double> flatten_numbers(const nlohmann::json& value, const std::string& prefix = {},
                                              NullLeaves nulls = NullLeaves::skip);

/// One metric summarised over the episodes of one variant.
struct MetricSummary {
  std::string metric;  ///< dotted name ("duration_s", "metrics.robot_moves_per_min", …)
  Summary stats;       ///< n, mean, SD, median, CI
};

/// Every metric of one variant.
struct VariantSummary {
  std::string variant;                 ///< suite variant id
  std::string condition;               ///< "child-child" / "child-robot"
  std::string policy;                  ///< robot policy ("" for child-child)
  int episodes = 0;                    ///< finished episodes
  Summary duration_min;                ///< free-play durations (minutes)
  std::array<double, 3> still_playing{};  ///< share of sessions lasting ≥ 10, ≥ 20 and ≥ 30 minutes
  std::vector<MetricSummary> metrics;  ///< sorted by name
};

/// One metric's values as a summary needs them, in memory that stops growing at kBootstrapMaxValues values: every
/// value up to that many (summarised exactly as `summarize` does), then running moments (mean, SD, normal CI) and a
/// uniform sample of kBootstrapMaxValues values (reservoir sampling, seeded: deterministic for a given record order)
/// whose median stands for the median.
class MetricSample {
 public:
  /// Takes one value (NaN is ignored, as `summarize` does).
  void add(double value);
  /// Values taken (NaN excluded).
  std::uint64_t count() const { return n_; }
  /// The summary of the values divided by `divisor`; `seed` drives the bootstrap of small samples.
  Summary summary(std::uint64_t seed, double divisor = 1.0) const;

 private:
  std::vector<double> kept_;  // every value while n ≤ kBootstrapMaxValues, then a uniform sample of that many
  std::uint64_t n_ = 0;
  double mean_ = 0.0;  // Welford's running mean and sum of squared deviations
  double m2_ = 0.0;
  std::uint64_t rng_ = 0x9e3779b97f4a7c15ULL;  // SplitMix64 state of the reservoir
};

/// Builds the variant summaries one record at a time (for episodes.jsonl streamed from disk): it keeps the numbers
/// it summarises, at most kBootstrapMaxValues per metric and variant (MetricSample), never the records, so its
/// memory does not grow with the number of episodes past that.
class RunSummarizer {
 public:
  /// Summaries of the variants in `variant_order` (others are ignored).
  explicit RunSummarizer(const std::vector<std::string>& variant_order);
  /// Takes one episode record.
  void add(const nlohmann::json& record);
  /// The summaries of the variants with at least one episode, in `variant_order`; the metrics' bootstraps run on
  /// `threads` threads (each metric has its own seed, so the result does not depend on them).
  std::vector<VariantSummary> finish(int threads = 1) const;

 private:
  struct Variant {
    VariantSummary summary;
    std::map<std::string, MetricSample> values;
    std::array<std::uint64_t, 3> still_playing{};  // durations ≥ 10, 20, 30 min
  };
  std::vector<Variant> variants_;
  std::map<std::string, std::size_t> index_;
};

/// Groups records by variant (in `variant_order`) and summarises `duration_s` and every numeric `metrics.*`.
std::vector<VariantSummary> summarize_run(const std::vector<nlohmann::json>& records,
                                          const std::vector<std::string>& variant_order);
/// `summary.csv`: variant, condition, metric, n, mean, sd, median, ci_low, ci_high.
std::string summary_csv(const std::vector<VariantSummary>& summaries);
/// `summary.md`: the durations beside PInSoRo, then the main metrics per condition, readable in a terminal.
std::string summary_markdown(const std::vector<VariantSummary>& summaries, const std::string& title);

/// Writes summary.csv and summary.md of the run folder `dir`'s finished episodes for the variants in
/// `variant_order` (bootstraps on `threads` threads); returns the Markdown.
std::string write_summaries(const std::filesystem::path& dir, const std::vector<std::string>& variant_order,
                            const std::string& title, int threads = 1);

}  // namespace freeplay::results
