// Comparing runs: pairing by seed, effect detection, Holm, metric filters, table and JSON.

#include <gtest/gtest.h>

#include "freeplay/analysis/compare.hpp"
#include "freeplay/core/error.hpp"
#include "synthetic_runs.hpp"

namespace freeplay::analysis {
namespace {

using testing::SyntheticVariant;

Sample sample_of(const std::string& label, const SyntheticVariant& v) {
  std::vector<nlohmann::json> records;
  for (int i = 0; i < v.episodes; ++i) records.push_back(testing::synthetic_record(v, i));
  return {label, run_from_records(records, label).episodes};
}

const MetricComparison& find(const Comparison& c, const std::string& metric) {
  for (const auto& m : c.metrics) {
    if (m.metric == metric) return m;
  }
  throw std::runtime_error("no metric " + metric);
}

TEST(Compare, SameSeedsArePairedAndTheShiftIsFound) {
  const SyntheticVariant asocial{"child-robot-asocial", "asocial", 30, 2017, 2.0, 0.30, 1};
  const SyntheticVariant social{"child-robot-social", "social", 30, 2017, 2.6, 0.30, 2};
  const auto c = compare_samples(sample_of("A", asocial), sample_of("B", social));
  EXPECT_TRUE(c.paired());
  const auto& moves = find(c, "metrics.robot_item_moves_per_min");
  ASSERT_TRUE(moves.paired.has_value());
  EXPECT_EQ(moves.paired->pairs, 30);
  EXPECT_NEAR(moves.difference, 0.6, 0.15);
  EXPECT_NEAR(moves.paired->mean_difference, moves.difference, 1e-9);  // same episodes: same mean difference
  // Pairing removes the per-child variation: a narrower CI and a smaller p than the unpaired analysis.
  EXPECT_LT(moves.paired->ci.high - moves.paired->ci.low, moves.difference_ci.high - moves.difference_ci.low);
  EXPECT_LT(moves.paired->wilcoxon.p_value, moves.mann_whitney.p_value);
  EXPECT_TRUE(moves.significant);
  EXPECT_GT(moves.cohens_d, 0.5);
  EXPECT_GT(moves.cliffs_delta, 0.3);
  EXPECT_GE(moves.p_holm, moves.mann_whitney.p_value);
  EXPECT_GE(moves.paired->p_holm, moves.paired->wilcoxon.p_value);
  // The constant metric: no difference, no evidence.
  const auto& zero = find(c, "metrics.constant_zero");
  EXPECT_DOUBLE_EQ(zero.difference, 0.0);
  EXPECT_DOUBLE_EQ(zero.mann_whitney.p_value, 1.0);
  EXPECT_FALSE(zero.significant);
}

TEST(Compare, DifferentSeedsAreIndependentSamples) {
  const SyntheticVariant a{"x", "asocial", 25, 1, 2.0, 0.3, 1};
  const SyntheticVariant b{"y", "social", 25, 99, 2.0, 0.3, 1};
  const auto c = compare_samples(sample_of("A", a), sample_of("B", b));
  EXPECT_FALSE(c.paired());
  for (const auto& m : c.metrics) EXPECT_FALSE(m.paired.has_value());
  const auto& moves = find(c, "metrics.robot_item_moves_per_min");
  EXPECT_FALSE(moves.significant);
  EXPECT_LT(moves.difference_ci.low, 0.0);
  EXPECT_GT(moves.difference_ci.high, 0.0);
}

TEST(Compare, PairingCanBeTurnedOff) {
  const SyntheticVariant a{"x", "asocial", 20, 5, 2.0, 0.3, 1};
  CompareOptions options;
  options.allow_paired = false;
  EXPECT_FALSE(compare_samples(sample_of("A", a), sample_of("B", a), options).paired());
}

TEST(Compare, MetricGlobsSelectAndUnknownPatternsAreErrors) {
  const SyntheticVariant a{"x", "asocial", 10, 5, 2.0, 0.3, 1};
  CompareOptions options;
  options.metrics = {"metrics.label_share.*", "duration_s"};
  const auto c = compare_samples(sample_of("A", a), sample_of("B", a), options);
  ASSERT_EQ(c.metrics.size(), 2u);
  EXPECT_EQ(c.metrics[0].metric, "duration_s");
  EXPECT_EQ(c.metrics[1].metric, "metrics.label_share.purple.cooperative");
  options.metrics = {"metrics.no_such_*"};
  try {
    compare_samples(sample_of("A", a), sample_of("B", a), options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "--metric");
    EXPECT_NE(std::string(e.what()).find("metrics.robot_item_moves_per_min"), std::string::npos);  // lists them
  }
}

TEST(Compare, ResultsDoNotDependOnWhichOtherMetricsAreCompared) {
  const SyntheticVariant a{"x", "asocial", 15, 5, 2.0, 0.3, 1};
  const SyntheticVariant b{"y", "social", 15, 5, 2.4, 0.3, 1};
  CompareOptions only;
  only.metrics = {"duration_s"};
  const auto alone = compare_samples(sample_of("A", a), sample_of("B", b), only);
  const auto all = compare_samples(sample_of("A", a), sample_of("B", b));
  EXPECT_EQ(find(alone, "duration_s").a.ci.low, find(all, "duration_s").a.ci.low);
  EXPECT_EQ(find(alone, "duration_s").difference_ci.high, find(all, "duration_s").difference_ci.high);
}

TEST(Compare, MetricsPresentInOneSampleOnlyAreListed) {
  const SyntheticVariant a{"x", "asocial", 10, 5, 2.0, 0.3, 1};
  auto sa = sample_of("A", a);
  auto sb = sample_of("B", a);
  for (auto& e : sb.episodes) e.metrics["metrics.only_b"] = 1.0;
  const auto c = compare_samples(sa, sb);
  EXPECT_EQ(c.only_in_b, std::vector<std::string>{"metrics.only_b"});
  EXPECT_TRUE(c.only_in_a.empty());
  EXPECT_NE(comparison_table(c).find("only in B (not compared): metrics.only_b"), std::string::npos);
}

TEST(Compare, TableAndJsonCarryEveryNumber) {
  const SyntheticVariant asocial{"child-robot-asocial", "asocial", 12, 2017, 2.0, 0.30, 1};
  const SyntheticVariant social{"child-robot-social", "social", 12, 2017, 2.6, 0.35, 2};
  const auto c = compare_samples(sample_of("runs/x:asocial", asocial), sample_of("runs/x:social", social));
  const auto table = comparison_table(c);
  EXPECT_NE(table.find("A: runs/x:asocial"), std::string::npos);
  EXPECT_NE(table.find("metrics.robot_item_moves_per_min"), std::string::npos);
  EXPECT_NE(table.find("p Holm W"), std::string::npos);
  EXPECT_NE(table.find("paired by seed"), std::string::npos);
  const auto json = nlohmann::json::parse(comparison_json(c).dump());  // valid JSON text
  EXPECT_EQ(json["a"], "runs/x:asocial");
  EXPECT_TRUE(json["paired"].get<bool>());
  ASSERT_EQ(json["metrics"].size(), c.metrics.size());
  const auto& row = json["metrics"][1];
  for (const char* key : {"metric", "a", "b", "difference", "difference_ci", "cohens_d", "cliffs_delta",
                          "mann_whitney", "p_holm", "paired", "significant"}) {
    EXPECT_TRUE(row.contains(key)) << key;
  }
  EXPECT_TRUE(row["paired"].contains("wilcoxon"));
  // NaN (Cohen's d of a constant metric) is written as null, not as invalid JSON.
  for (const auto& m : json["metrics"]) {
    if (m["metric"] == "metrics.constant_zero") {
      EXPECT_TRUE(m["cohens_d"].is_null());
    }
  }
}

}  // namespace
}  // namespace freeplay::analysis
