// The validity panel's gates on synthetic numbers: a panel that passes, and each gate failing on its own.

#include <gtest/gtest.h>

#include "freeplay/analysis/validity.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"

using namespace freeplay;
using namespace freeplay::analysis;

namespace {

/// The mean numbers of one synthetic robot.
struct RobotMeans {
  double duration_s = 1100.0;
  double associative = 0.02;
  double cooperative = 0.0;
};

/// 40 episodes with seeds 1 … 40 (the same children for every robot): a per-child effect plus robot-specific noise.
Sample robot(const std::string& name, const RobotMeans& m) {
  Sample s{name, {}};
  for (int i = 0; i < 40; ++i) {
    const auto seed = static_cast<std::uint64_t>(i + 1);
    Rng child(seed);
    Rng noise(seed ^ fnv1a64(name));
    const double engagement = child.normal(0.0, 1.0);
    EpisodeValues e;
    e.variant = name;
    e.episode = i;
    e.seed = seed;
    e.metrics["duration_s"] = m.duration_s + 200.0 * engagement + 20.0 * noise.normal(0.0, 1.0);
    for (const auto& label : panel_labels()) e.metrics[share_metric(label)] = 0.1;
    e.metrics[share_metric("associative")] = std::max(0.0, m.associative + 0.01 * noise.normal(0.0, 1.0));
    e.metrics[share_metric("cooperative")] = std::max(0.0, m.cooperative + 0.005 * noise.normal(0.0, 1.0));
    s.episodes.push_back(std::move(e));
  }
  return s;
}

/// A panel that passes every gate; `edit` changes one robot's means first.
ValidityPanel panel(const std::function<void(std::map<std::string, RobotMeans>&)>& edit = {}) {
  std::map<std::string, RobotMeans> means = {
      {"asocial", {1100.0, 0.02, 0.0}},   {"social", {1600.0, 0.35, 0.30}},   {"chatterer", {1120.0, 0.04, 0.0}},
      {"mover", {1150.0, 0.05, 0.02}},     {"yoked-social", {1200.0, 0.05, 0.01}}, {"idle", {1000.0, 0.0, 0.0}}};
  if (edit) edit(means);
  ValidityPanel p;
  p.asocial = robot("asocial", means["asocial"]);
  p.social = robot("social", means["social"]);
  p.yoked = robot("yoked-social", means["yoked-social"]);
  for (const char* name : {"chatterer", "mover", "yoked-social", "idle"}) p.degenerate.push_back(robot(name, means[name]));
  return p;
}

/// The failed gates as "robot: gate name".
std::vector<std::string> failed(const ValidityReport& report) {
  std::vector<std::string> out;
  for (const auto& g : report.gates) {
    if (!g.passed) out.push_back(g.robot + ": " + g.name);
  }
  return out;
}

}  // namespace

TEST(ValidityPanel, AGoodPanelPassesEveryGate) {
  const auto report = evaluate_panel(panel());
  EXPECT_EQ(report.gates.size(), 4u * 3u + 2u);
  EXPECT_EQ(report.failures(), 0) << validity_table(report);
  ASSERT_EQ(report.robots.size(), 6u);
  EXPECT_EQ(report.robots[0].shares.size(), 14u);
  for (const auto& row : report.paired) EXPECT_EQ(row.pairs, 40) << row.metric;
  EXPECT_NEAR(report.paired[1].difference, (0.35 + 0.30) - (0.05 + 0.01), 0.01);  // joint play
}

TEST(ValidityPanel, ACooperativeTimetableFails) {
  const auto report = evaluate_panel(panel([](auto& m) { m["mover"].cooperative = 0.08; }));
  EXPECT_EQ(failed(report), std::vector<std::string>{"mover: cooperative share"}) << validity_table(report);
  for (const auto& g : report.gates) {
    if (g.passed) continue;
    EXPECT_NEAR(g.value - g.bound, 0.03, 0.005);
    EXPECT_NE(g.verdict.find("misses by 0.0"), std::string::npos) << g.verdict;
  }
}

TEST(ValidityPanel, AssociativeIsBoundedByTheAsocialRobotPlusAMargin) {
  // The asocial robot's 0.02 + 0.05: a chatterer at 0.10 fails, at 0.06 it passes.
  EXPECT_EQ(failed(evaluate_panel(panel([](auto& m) { m["chatterer"].associative = 0.10; }))),
            std::vector<std::string>{"chatterer: associative share"});
  EXPECT_EQ(evaluate_panel(panel([](auto& m) { m["chatterer"].associative = 0.06; })).failures(), 0);
  // The bound moves with the asocial robot.
  EXPECT_EQ(evaluate_panel(panel([](auto& m) {
              m["chatterer"].associative = 0.10;
              m["asocial"].associative = 0.08;
            })).failures(),
            0);
}

TEST(ValidityPanel, KeepingChildrenTooLongFails) {
  const auto report = evaluate_panel(panel([](auto& m) { m["idle"].duration_s = 1100.0 + 200.0; }));
  EXPECT_EQ(failed(report), std::vector<std::string>{"idle: mean duration (min)"}) << validity_table(report);
}

TEST(ValidityPanel, SocialMustBeatItsYokedControlOnJointPlayAndDuration) {
  // Less joint play than its yoked control: the paired CI lies below zero.
  const auto joint = evaluate_panel(panel([](auto& m) {
    m["social"].associative = 0.03;
    m["social"].cooperative = 0.0;
  }));
  EXPECT_EQ(failed(joint), std::vector<std::string>{"social: joint play: social − yoked, CI low"})
      << validity_table(joint);
  const auto duration = evaluate_panel(panel([](auto& m) { m["social"].duration_s = 1200.0; }));
  EXPECT_EQ(failed(duration), std::vector<std::string>{"social: duration (s): social − yoked, CI low"})
      << validity_table(duration);
}

TEST(ValidityPanel, UnpairedRunsFailThePairedGates) {
  auto p = panel();
  for (auto& e : p.yoked.episodes) e.seed += 1000;  // other children: nothing to pair
  const auto report = evaluate_panel(p);
  EXPECT_EQ(failed(report).size(), 2u);
  EXPECT_NE(report.gates.back().verdict.find("could not be paired"), std::string::npos);
}

TEST(ValidityPanel, ReportsNameEveryGate) {
  const auto report = evaluate_panel(panel([](auto& m) { m["mover"].cooperative = 0.08; }));
  const auto table = validity_table(report);
  EXPECT_NE(table.find("FAIL"), std::string::npos);
  EXPECT_NE(table.find("1 of 14 gates failed"), std::string::npos) << table;
  const auto junit = validity_junit(report);
  EXPECT_NE(junit.find("failures=\"1\""), std::string::npos);
  EXPECT_NE(junit.find("<failure message=\"mover: cooperative share breaks its bound\""), std::string::npos) << junit;
  const auto json = validity_json(report);
  EXPECT_EQ(json["failures"], 1);
  EXPECT_EQ(json["robots"][0]["shares"].size(), 14u);
}

TEST(ValidityPanel, ARunWithoutLabelSharesIsBadInput) {
  auto p = panel();
  for (auto& e : p.asocial.episodes) e.metrics.erase(share_metric("cooperative"));
  EXPECT_THROW(evaluate_panel(p), InputError);
  p = panel();
  p.degenerate[0].episodes.clear();
  EXPECT_THROW(evaluate_panel(p), InputError);
}
