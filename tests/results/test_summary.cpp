#include <gtest/gtest.h>

#include <cmath>

#include "freeplay/results/summary.hpp"

using namespace freeplay::results;

TEST(Summary, GroupsByVariantAndFlattensMetrics) {
  std::vector<nlohmann::json> records;
  for (int i = 0; i < 4; ++i) {
    records.push_back({{"variant", "cc"}, {"condition", "child-child"}, {"episode", i}, {"duration_s", 600.0 * (i + 1)},
                       {"metrics", {{"label_share", {{"purple", {{"cooperative", 0.25 * i}}}}}}}});
  }
  records.push_back({{"variant", "cr"}, {"condition", "child-robot"}, {"policy", "asocial"}, {"episode", 0},
                     {"duration_s", 60.0}, {"metrics", nlohmann::json::object()}});
  const auto s = summarize_run(records, {"cc", "cr"});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].episodes, 4);
  const auto it = std::find_if(s[0].metrics.begin(), s[0].metrics.end(),
                               [](const auto& m) { return m.metric == "metrics.label_share.purple.cooperative"; });
  ASSERT_NE(it, s[0].metrics.end());
  EXPECT_DOUBLE_EQ(it->stats.mean, 0.375);
  const auto csv = summary_csv(s);
  EXPECT_NE(csv.find("\"cc\",child-child,,duration_s,4,1500"), std::string::npos) << csv;
  const auto md = summary_markdown(s, "test");
  EXPECT_NE(md.find("24.15 (11.25)"), std::string::npos) << md;  // PInSoRo child-child beside ours
  EXPECT_NE(md.find("19.18 (10.00)"), std::string::npos) << md;  // asocial robot reference
  EXPECT_NE(md.find("purple cooperative share"), std::string::npos) << md;
}

TEST(Summary, SmallSamplesAreSummarisedExactlyAsBefore) {
  std::vector<double> values;
  MetricSample sample;
  for (int i = 0; i < 3000; ++i) {
    const double v = std::sin(i * 0.37) * 100.0 + (i % 3 == 0 ? std::nan("") : 0.0);
    values.push_back(v);
    sample.add(v);
  }
  const auto a = sample.summary(5, 60.0);
  std::vector<double> minutes;
  for (const double v : values) minutes.push_back(v / 60.0);
  const auto b = freeplay::summarize(minutes, 5);
  EXPECT_EQ(a.n, b.n);
  EXPECT_EQ(a.mean, b.mean);
  EXPECT_EQ(a.sd, b.sd);
  EXPECT_EQ(a.median, b.median);
  EXPECT_EQ(a.ci95.low, b.ci95.low);
  EXPECT_EQ(a.ci95.high, b.ci95.high);
}

TEST(Summary, LargeSamplesKeepExactMomentsAndABoundedSampleForTheMedian) {
  // 10^5 values 0 … 99 999 in a scrambled order: mean, SD and n exact; the median from the 5 000-value sample.
  MetricSample sample;
  std::vector<double> values;
  constexpr int kN = 100000;
  for (int i = 0; i < kN; ++i) values.push_back(static_cast<double>((static_cast<long>(i) * 7919) % kN));
  for (const double v : values) sample.add(v);
  const auto s = sample.summary(1);
  EXPECT_EQ(s.n, kN);
  EXPECT_NEAR(s.mean, freeplay::mean(values), 1e-6);
  EXPECT_NEAR(s.sd, freeplay::sample_sd(values), 1e-6);
  EXPECT_NEAR(s.median, 49999.5, 0.02 * kN);  // a 5 000-value sample: rank error ≈ 0.7 % of n (1 SD)
  EXPECT_NEAR(s.ci95.high - s.mean, 1.959963984540054 * s.sd / std::sqrt(kN), 1e-9);
  // The same values in the same order give the same summary (the reservoir is seeded).
  MetricSample again;
  for (const double v : values) again.add(v);
  EXPECT_EQ(again.summary(1).median, s.median);
}

TEST(Summary, BootstrapsOnSeveralThreadsGiveTheSameSummaries) {
  RunSummarizer summarizer({"cc", "cr"});
  for (int i = 0; i < 60; ++i) {
    summarizer.add({{"variant", i % 3 == 0 ? "cr" : "cc"}, {"condition", "child-child"}, {"duration_s", 30.0 * i},
                    {"metrics", {{"a", std::sin(i)}, {"b", {{"c", i * i}, {"d", i % 7}}}}}});
  }
  const std::string one = summary_csv(summarizer.finish(1));
  for (const int threads : {2, 5}) {
    const auto summaries = summarizer.finish(threads);
    EXPECT_EQ(summary_csv(summaries), one) << threads;
    EXPECT_EQ(summary_markdown(summaries, "t"), summary_markdown(summarizer.finish(1), "t")) << threads;
  }
}
