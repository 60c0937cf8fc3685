// Controller regression episodes: metrics on constructed cases, golden traces, trace-diff, check gates, schema errors.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>

#include "freeplay/analysis/baseline.hpp"
#include "freeplay/analysis/run_data.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/runner/controller_episode.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/scenario/scenario.hpp"

namespace freeplay::runner {
using namespace freeplay::scenario;

namespace {

const SharedModels& models() { return SharedModels::shipped(); }

Scenario controller_scenario(const std::string& targets, const std::string& extra = "") {
  const std::string text = "name: test-controller\nkind: controller\nseed: 3\ncontroller:\n  mode: dynamic\n" + extra +
                           "  targets:\n" + targets;
  return scenario_from_document(parse_yaml(text, "test.yaml"));
}

ControllerEpisodeResult run(const Scenario& s, std::uint64_t seed = 1) {
  const std::atomic<bool> stop{false};
  return run_controller_episode(s, seed, models(), stop);
}

double metric(const nlohmann::json& record, const std::string& dotted) {
  const nlohmann::json* node = &record["metrics"];
  std::size_t start = 0;
  while (true) {
    const auto dot = dotted.find('.', start);
    node = &(*node)[dotted.substr(start, dot - start)];
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return node->is_number() ? node->get<double>() : std::nan("");
}

TEST(ControllerEpisode, PointInsideReachSettlesWithinFiveMillimetres) {
  const auto r = run(controller_scenario("    - point: [0.20, -0.05]\n"));
  const auto& target = r.record["targets"][0];
  EXPECT_TRUE(target["reachable"].get<bool>());
  EXPECT_TRUE(target["settled"].get<bool>());
  EXPECT_LT(target["error_mm"].get<double>(), 5.0);
  EXPECT_GT(target["settle_s"].get<double>(), 0.0);
  EXPECT_LT(target["settle_s"].get<double>(), 5.0);
  EXPECT_EQ(metric(r.record, "self_collisions.count"), 0.0);
  EXPECT_EQ(metric(r.record, "unsettled_targets"), 0.0);
  EXPECT_GT(metric(r.record, "joint_limit_margin_rad"), 0.0);
  EXPECT_GT(metric(r.record, "tracking_error_rad.max"), 0.0);
  EXPECT_GE(metric(r.record, "tracking_error_rad.max"), metric(r.record, "tracking_error_rad.rms"));
}

TEST(ControllerEpisode, UnreachableTargetIsReportedWithALargeError) {
  const auto r = run(controller_scenario("    - point: [0.50, -0.30]\n    - point: [0.20, -0.05]\n"));
  const auto& far = r.record["targets"][0];
  EXPECT_FALSE(far["reachable"].get<bool>());
  EXPECT_GT(far["error_mm"].get<double>(), 50.0);
  EXPECT_GT(metric(r.record, "fingertip_error_mm.max"), 50.0);
  EXPECT_LT(metric(r.record, "fingertip_error_mm.reachable_max"), 5.0);  // the reachable one is still fine
}

TEST(ControllerEpisode, PosturesHaveNoSelfCollisions) {
  const auto r = run(controller_scenario(
      "    - posture: Stand\n    - posture: StandZero\n    - posture: StandInit\n"));
  EXPECT_EQ(metric(r.record, "self_collisions.count"), 0.0);
  EXPECT_EQ(metric(r.record, "self_collisions.time_s"), 0.0);
  EXPECT_EQ(metric(r.record, "unsettled_targets"), 0.0);
  EXPECT_GT(r.record["controller"]["self_collision_pairs"].get<int>(), 50);
}

TEST(ControllerEpisode, DefaultGainsStayWithinTheNaoLimits) {
  const auto r = run(controller_scenario(
      "    - point: [0.10, -0.02]\n    - point: [0.31, -0.10]\n    - look: [0.55, -0.30, 0.0]\n"
      "    - look: [0.30, -0.60, 0.25]\n    - posture: StandInit\n"));
  EXPECT_GT(metric(r.record, "peak_velocity_fraction"), 0.05);
  EXPECT_LE(metric(r.record, "peak_velocity_fraction"), 1.0);
  EXPECT_GT(metric(r.record, "peak_torque_fraction"), 0.0);
  EXPECT_LE(metric(r.record, "peak_torque_fraction"), 1.0) << r.record["peak_torque_at"];
  EXPECT_LT(metric(r.record, "gaze_error_deg.unclamped_max"), 5.0);
}

analysis::RunData as_run(const nlohmann::json& record, const std::string& dir) {
  nlohmann::json r = record;
  r["variant"] = "controller";
  r["episode"] = 0;
  r["seed"] = 1;
  return analysis::run_from_records({r}, dir);
}

TEST(ControllerEpisode, TooAggressiveGainDegradesTheMetricsAndFailsCheck) {
  const std::string targets = "    - point: [0.10, -0.02]\n    - point: [0.31, -0.10]\n    - look: [0.55, -0.30, 0.0]\n";
  const auto good = run(controller_scenario(targets));
  const auto bad = run(controller_scenario(targets, "  speed_fraction: 3\n  torque_fraction: 10\n"));
  // The servos saturate (±5 N·m, far above the motors' efforts) before the joints reach their speed limits.
  EXPECT_GT(metric(bad.record, "peak_velocity_fraction"), metric(good.record, "peak_velocity_fraction"));
  EXPECT_GT(metric(bad.record, "peak_torque_fraction"), 1.0);
  EXPECT_GT(metric(bad.record, "tracking_error_rad.max"), metric(good.record, "tracking_error_rad.max"));

  analysis::BaselineOptions options;
  options.kind = analysis::BandKind::Absolute;
  options.width = 0.05;
  options.metrics = {"metrics.peak_*", "metrics.trace_hash"};
  const auto baseline = analysis::make_baseline(as_run(good.record, "good"), options);
  ASSERT_EQ(baseline.gates.size(), 3u);
  EXPECT_EQ(analysis::check_run(as_run(good.record, "good"), baseline).failures(), 0);
  const auto report = analysis::check_run(as_run(bad.record, "bad"), baseline);
  EXPECT_EQ(report.failures(), 3);  // both peaks and the trace hash
  // The baseline round-trips through its YAML, the trace hash as an `equals` gate.
  const auto yaml = analysis::baseline_yaml(baseline);
  EXPECT_NE(yaml.find("\"metrics.trace_hash\": {equals: \""), std::string::npos);
  const auto reparsed = analysis::parse_baseline(parse_yaml(yaml, "b.yaml"));
  EXPECT_EQ(analysis::check_run(as_run(good.record, "good"), reparsed).failures(), 0);
  EXPECT_EQ(analysis::check_run(as_run(bad.record, "bad"), reparsed).failures(), 3);
}

TEST(ControllerEpisode, ItemMoveGoesThroughThePlannerAndExecutor) {
  const auto r = run(controller_scenario("    - move: {item: zebra, from: [0.12, -0.05], to: [0.26, -0.05]}\n"));
  const auto& target = r.record["targets"][0];
  EXPECT_EQ(target["status"], "succeeded");
  EXPECT_EQ(metric(r.record, "moves.succeeded"), 1.0);
  EXPECT_LT(target["error_mm"].get<double>(), 5.0);
  EXPECT_GT(metric(r.record, "sync.error_mm_mean"), 0.0);
  EXPECT_LT(metric(r.record, "sync.error_mm_mean"), 30.0);
  EXPECT_GE(metric(r.record, "sync.lag_ms"), 0.0);
  EXPECT_LT(metric(r.record, "placement_error_mm"), 10.0);
}

TEST(ControllerTrace, IdenticalBetweenRunsAndChangesWithTheGain) {
  const std::string targets = "    - point: [0.20, -0.05]\n    - look: [0.3, -0.3, 0.0]\n";
  const auto a = run(controller_scenario(targets));
  const auto b = run(controller_scenario(targets));
  const auto c = run(controller_scenario(targets, "  torque_fraction: 0.52\n"));
  EXPECT_EQ(a.record["trace_hash"], b.record["trace_hash"]);
  EXPECT_EQ(a.record["metrics"]["trace_hash"], a.record["trace_hash"]);
  EXPECT_NE(a.record["trace_hash"], c.record["trace_hash"]);
  EXPECT_GT(a.trace.checkpoints.size(), 10u);
  const auto same = diff_traces(a.trace, b.trace, 0.0);
  EXPECT_TRUE(same.bit_identical);
  EXPECT_TRUE(same.within_tolerance);
  const auto other = diff_traces(a.trace, c.trace, 1e-6);
  EXPECT_FALSE(other.bit_identical);
  EXPECT_FALSE(other.within_tolerance);
  ASSERT_TRUE(other.first_beyond.has_value());
  ASSERT_TRUE(other.first_hash_mismatch.has_value());
  EXPECT_LE(*other.first_hash_mismatch, *other.first_beyond);
}

TEST(ControllerTrace, RoundTripsAndDiffsWithTolerance) {
  const auto a = run(controller_scenario("    - point: [0.20, -0.05]\n    - wait: 1\n"), 5);
  ASSERT_GT(a.trace.checkpoints.size(), 10u);
  const auto parsed = parse_trace(trace_jsonl(a.trace), "a.jsonl");
  ASSERT_EQ(parsed.checkpoints.size(), a.trace.checkpoints.size());
  EXPECT_EQ(parsed.hash(), a.trace.hash());
  EXPECT_EQ(parsed.checkpoints[3].qpos, a.trace.checkpoints[3].qpos);  // round-trip precision
  EXPECT_TRUE(diff_traces(a.trace, parsed, 0.0).bit_identical);

  auto perturbed = a.trace;
  perturbed.checkpoints[7].qpos[0] += 1e-9;  // another machine's rounding, as it were
  perturbed.checkpoints[7].hash ^= 1;
  const auto loose = diff_traces(a.trace, perturbed, 1e-6);
  EXPECT_FALSE(loose.bit_identical);
  EXPECT_TRUE(loose.within_tolerance);
  EXPECT_EQ(loose.first_hash_mismatch, 7u);
  EXPECT_NEAR(loose.max_abs_diff, 1e-9, 1e-12);
  const auto tight = diff_traces(a.trace, perturbed, 1e-12);
  EXPECT_FALSE(tight.within_tolerance);
  EXPECT_EQ(tight.first_beyond, 7u);
  EXPECT_NE(trace_diff_text(tight, 1e-12).find("checkpoint 7"), std::string::npos);

  auto shorter = a.trace;
  shorter.checkpoints.pop_back();
  EXPECT_FALSE(diff_traces(a.trace, shorter, 1.0).within_tolerance);
  EXPECT_THROW(parse_trace("{\"format\":\"something-else\"}\n", "x.jsonl"), InputError);
}

TEST(ControllerTrace, RandomPointsFollowTheSeed) {
  const auto s = controller_scenario("    - random_points: {count: 3, region: reach}\n");
  const auto a = run(s, 11);
  const auto b = run(s, 11);
  const auto c = run(s, 12);
  EXPECT_EQ(a.record["targets"].size(), 3u);
  EXPECT_EQ(a.record["targets"][0]["point"], b.record["targets"][0]["point"]);
  EXPECT_NE(a.record["targets"][0]["point"], c.record["targets"][0]["point"]);
  EXPECT_EQ(a.record["trace_hash"], b.record["trace_hash"]);
  EXPECT_LT(metric(a.record, "fingertip_error_mm.max"), 5.0);
}

std::string error_of(const std::string& text) {
  try {
    scenario_from_document(parse_yaml(text, "bad.yaml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ControllerScenario, ParsesTheSequence) {
  const auto s = controller_scenario(
      "    - point: [0.2, -0.05]\n    - look: [0.3, -0.2, 0.1]\n    - move: {item: ball, to: [0.2, -0.1]}\n"
      "    - posture: Stand\n    - wait: 1.5\n    - random_points: {count: 4}\n");
  EXPECT_EQ(s.kind, ScenarioKind::controller);
  EXPECT_EQ(s.condition, Condition::Controller);
  EXPECT_EQ(s.controller.mode, stage::StageMode::dynamic);
  EXPECT_DOUBLE_EQ(s.controller.speed_fraction, 0.3);
  EXPECT_EQ(s.controller.trace_interval_steps, 50);
  ASSERT_EQ(s.controller.targets.size(), 6u);
  EXPECT_EQ(s.controller.targets[2].kind, ControllerTarget::Kind::Move);
  EXPECT_EQ(s.controller.targets[2].item, "ball");
  EXPECT_FALSE(s.controller.targets[2].from.has_value());
  EXPECT_EQ(s.controller.targets[3].posture, "Stand");
  EXPECT_DOUBLE_EQ(s.controller.targets[4].seconds, 1.5);
  EXPECT_EQ(s.controller.targets[5].region, "reach");
  // Episodes are unchanged: kind defaults to episode.
  const auto episode = scenario_from_document(parse_yaml("name: e\ncondition: child-child\n", "e.yaml"));
  EXPECT_EQ(episode.kind, ScenarioKind::episode);
}

TEST(ControllerScenario, ErrorsNameTheLocationKeyAndAllowedValues) {
  const std::string head = "name: c\nkind: controller\ncontroller:\n  targets:\n";
  auto e = error_of(head + "    - move: {item: unicorn, to: [0.2, -0.1]}\n");
  EXPECT_NE(e.find("bad.yaml:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("item"), std::string::npos) << e;
  EXPECT_NE(e.find("zebra"), std::string::npos) << e;
  e = error_of(head + "    - point: [0.2, -0.1]\n      wait: 2\n");
  EXPECT_NE(e.find("exactly one key"), std::string::npos) << e;
  EXPECT_NE(e.find("controller.targets[0]"), std::string::npos) << e;
  e = error_of(head + "    - posture: Dance\n");
  EXPECT_NE(e.find("StandInit"), std::string::npos) << e;
  e = error_of(head + "    - point: [0.2]\n");
  EXPECT_NE(e.find("bad.yaml:5:"), std::string::npos) << e;
  e = error_of(head + "    - fly: 3\n");
  EXPECT_NE(e.find("random_points"), std::string::npos) << e;
  e = error_of("name: c\nkind: controller\n");
  EXPECT_NE(e.find("'controller' section"), std::string::npos) << e;
  e = error_of(head + "    - wait: 1\nchildren: {population: pinsoro}\n");
  EXPECT_NE(e.find("'children' belongs to episodes"), std::string::npos) << e;
  EXPECT_NE(e.find("bad.yaml:6:"), std::string::npos) << e;
  e = error_of("name: e\ncondition: child-robot\ncontroller:\n  targets:\n    - wait: 1\n");
  EXPECT_NE(e.find("needs kind: controller"), std::string::npos) << e;
  e = error_of("name: e\n");
  EXPECT_NE(e.find("condition"), std::string::npos) << e;
  e = error_of("name: c\nkind: robot\n");
  EXPECT_NE(e.find("controller"), std::string::npos) << e;
  e = error_of(head + "    - wait: 1\n  speed_fraction: 0\n");
  EXPECT_NE(e.find("speed_fraction"), std::string::npos) << e;
}

}  // namespace
}  // namespace freeplay::runner
