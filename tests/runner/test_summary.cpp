#include <gtest/gtest.h>

#include "freeplay/runner/progress.hpp"
#include "freeplay/runner/summary.hpp"

using namespace freeplay::runner;

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

TEST(Progress, LineCountsEpisodesAndSimulatedHours) {
  ProgressReporter progress(4, false);
  progress.episode_done(1800.0);
  progress.episode_done(1800.0);
  const auto line = progress.line();
  EXPECT_NE(line.find("2/4 episodes"), std::string::npos) << line;
  EXPECT_NE(line.find("1.0 simulated h"), std::string::npos) << line;
}
