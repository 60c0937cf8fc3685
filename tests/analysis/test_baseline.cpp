// Baselines and gates: round trip through YAML, pass on an unchanged run, fail on a degraded policy, bad baseline
// files and mismatched runs, JUnit XML.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "freeplay/analysis/baseline.hpp"
#include "synthetic_runs.hpp"

namespace freeplay::analysis {
namespace {

using testing::SyntheticVariant;

const SyntheticVariant kAsocial{"child-robot-asocial", "asocial", 30, 2017, 2.0, 0.30, 1};
const SyntheticVariant kSocial{"child-robot-social", "social", 30, 2017, 2.6, 0.35, 2};

RunData synthetic_run(const std::vector<SyntheticVariant>& variants, const std::string& name = "runs/test") {
  std::vector<nlohmann::json> records;
  for (const auto& v : variants) {
    for (int i = 0; i < v.episodes; ++i) records.push_back(testing::synthetic_record(v, i));
  }
  return run_from_records(records, name);
}

const GateResult& result_of(const CheckReport& report, const std::string& variant, const std::string& metric) {
  for (const auto& r : report.results) {
    if (r.gate.variant == variant && r.gate.metric == metric) return r;
  }
  throw std::runtime_error("no gate " + variant + "/" + metric);
}

std::string error_of(const std::string& yaml) {
  try {
    parse_baseline(parse_yaml(yaml, "baseline.yaml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Baseline, RoundTripsThroughYamlAndPassesOnTheSameRun) {
  const auto run = synthetic_run({kAsocial, kSocial});
  const auto made = make_baseline(run, {}, "v1");
  const auto text = baseline_yaml(made);
  const auto loaded = parse_baseline(parse_yaml(text, "b.yaml"));
  ASSERT_EQ(loaded.gates.size(), made.gates.size());
  EXPECT_EQ(loaded.source, "runs/test");
  EXPECT_EQ(loaded.program_version, "v1");
  for (std::size_t i = 0; i < made.gates.size(); ++i) {
    EXPECT_EQ(loaded.gates[i].variant, made.gates[i].variant);
    EXPECT_EQ(loaded.gates[i].metric, made.gates[i].metric);
    EXPECT_EQ(loaded.gates[i].expected, made.gates[i].expected);  // round-trip precision
    EXPECT_EQ(loaded.gates[i].kind, made.gates[i].kind);
    EXPECT_EQ(loaded.gates[i].width, made.gates[i].width);
  }
  const auto report = check_run(run, loaded);
  EXPECT_EQ(report.failures(), 0);
  EXPECT_EQ(report.results.size(), loaded.gates.size());
  EXPECT_NE(check_table(report).find("gates passed"), std::string::npos);
}

TEST(Baseline, DefaultBandsAreRelativeAndZeroMetricsGetAnAbsoluteFloor) {
  const auto b = make_baseline(synthetic_run({kAsocial}), {});
  for (const auto& g : b.gates) {
    if (g.metric == "metrics.constant_zero") {
      EXPECT_EQ(g.kind, BandKind::Absolute);
      EXPECT_DOUBLE_EQ(g.width, 1e-6);
    } else {
      EXPECT_EQ(g.kind, BandKind::Relative);
      EXPECT_DOUBLE_EQ(g.width, 0.25);
    }
  }
}

TEST(Baseline, DegradedPolicyFailsTheRightGateByTheRightAmount) {
  const auto baseline = make_baseline(synthetic_run({kAsocial, kSocial}), {});
  auto degraded = kSocial;
  degraded.moves_per_min = 1.2;  // the social robot barely plays any more
  const auto report = check_run(synthetic_run({kAsocial, degraded}), baseline);
  EXPECT_EQ(report.failures(), 1);
  const auto& moves = result_of(report, "child-robot-social", "metrics.robot_item_moves_per_min");
  EXPECT_FALSE(moves.passed);
  const double allowed = 0.25 * moves.gate.expected;
  EXPECT_NEAR(moves.miss, std::fabs(moves.mean - moves.gate.expected) - allowed, 1e-12);
  EXPECT_NEAR(moves.mean - moves.gate.expected, -1.4, 1e-9);  // the same children, 1.4 fewer moves per minute
  EXPECT_NE(moves.verdict.find("beyond the band"), std::string::npos);
  EXPECT_TRUE(result_of(report, "child-robot-asocial", "metrics.robot_item_moves_per_min").passed);
  const auto table = check_table(report);
  EXPECT_NE(table.find("FAIL  child-robot-social"), std::string::npos);
  EXPECT_NE(table.find("1 of "), std::string::npos);
}

TEST(Baseline, AbsoluteBand) {
  Gate gate{"v", "m", 10.0, BandKind::Absolute, 0.5, Direction::HigherIsBetter, 0.95, {}};
  Baseline baseline{"b.yaml", "", "", {gate}};
  auto run_with = [](double value) {
    RunData run;
    run.dir = "r";
    run.variants = {"v"};
    for (int i = 0; i < 3; ++i) run.episodes.push_back({"v", i, static_cast<std::uint64_t>(i), {{"m", value}}});
    return run;
  };
  EXPECT_TRUE(check_run(run_with(10.4), baseline).results[0].passed);
  EXPECT_TRUE(check_run(run_with(9.5), baseline).results[0].passed);
  const auto failed = check_run(run_with(10.8), baseline).results[0];
  EXPECT_FALSE(failed.passed);
  EXPECT_NEAR(failed.miss, 0.3, 1e-12);
}

TEST(Baseline, NotWorseThanFailsOnlyWhenTheWholeCiIsWorse) {
  BaselineOptions options;
  options.kind = BandKind::NotWorseThan;
  options.direction = Direction::HigherIsBetter;
  options.metrics = {"metrics.label_share.*"};
  const auto baseline = make_baseline(synthetic_run({kSocial}), options);
  ASSERT_EQ(baseline.gates.size(), 1u);
  auto slightly_worse = kSocial;
  slightly_worse.cooperative -= 0.005;  // within the run's CI: not evidence of a regression
  EXPECT_EQ(check_run(synthetic_run({slightly_worse}), baseline).failures(), 0);
  auto better = kSocial;
  better.cooperative += 0.2;
  EXPECT_EQ(check_run(synthetic_run({better}), baseline).failures(), 0);
  auto worse = kSocial;
  worse.cooperative -= 0.1;
  const auto report = check_run(synthetic_run({worse}), baseline);
  ASSERT_EQ(report.failures(), 1);
  const auto& r = report.results[0];
  EXPECT_LT(r.ci.high, r.gate.expected);
  EXPECT_NEAR(r.miss, r.gate.expected - r.ci.high, 1e-12);
  // lower_is_better: the same worse run now passes (lower is fine).
  auto lower_is_better = baseline;
  lower_is_better.gates[0].direction = Direction::LowerIsBetter;
  EXPECT_EQ(check_run(synthetic_run({worse}), lower_is_better).failures(), 0);
}

TEST(Baseline, FiltersSelectVariantsAndMetrics) {
  BaselineOptions options;
  options.variants = {"child-robot-social"};
  options.metrics = {"duration_s"};
  const auto b = make_baseline(synthetic_run({kAsocial, kSocial}), options);
  ASSERT_EQ(b.gates.size(), 1u);
  EXPECT_EQ(b.gates[0].variant, "child-robot-social");
  options.variants = {"nope"};
  EXPECT_THROW(make_baseline(synthetic_run({kAsocial}), options), InputError);
  options.variants = {};
  options.metrics = {"nothing.*"};
  EXPECT_THROW(make_baseline(synthetic_run({kAsocial}), options), InputError);
}

TEST(BaselineFile, BadFilesNameFileLineColumn) {
  EXPECT_NE(error_of("variants:\n  v:\n    m: {expected: 1, rel: 0.1, abs: 2}\n").find("baseline.yaml:3:8"),
            std::string::npos)
      << error_of("variants:\n  v:\n    m: {expected: 1, rel: 0.1, abs: 2}\n");
  EXPECT_NE(error_of("variants:\n  v:\n    m: {expected: 1, rel: 0.1, abs: 2}\n").find("exactly one band"),
            std::string::npos);
  EXPECT_NE(error_of("variants:\n  v:\n    m: {rel: 0.1}\n").find("expected"), std::string::npos);
  const auto unknown_key = error_of("variants:\n  v:\n    m: {expected: 1, relative: 0.1}\n");
  EXPECT_NE(unknown_key.find("baseline.yaml:3:"), std::string::npos) << unknown_key;
  EXPECT_NE(unknown_key.find("unknown key 'relative'"), std::string::npos) << unknown_key;
  const auto direction =
      error_of("variants:\n  v:\n    m:\n      expected: 1\n      not_worse_than: {direction: up}\n");
  EXPECT_NE(direction.find("higher_is_better"), std::string::npos) << direction;
  EXPECT_NE(direction.find("baseline.yaml:5:"), std::string::npos) << direction;
  EXPECT_NE(error_of("variants:\n  v:\n    m: {expected: lots, rel: 0.1}\n").find("finite number"), std::string::npos);
  EXPECT_NE(error_of("variants:\n  v:\n    m: {expected: 1, rel: -0.1}\n").find("out of range"), std::string::npos);
  EXPECT_NE(error_of("gates: []\n").find("variants"), std::string::npos);
  EXPECT_NE(error_of("variants: {}\n").find("no gate"), std::string::npos);
  EXPECT_NE(error_of("").find("empty"), std::string::npos);
  EXPECT_NE(error_of("variants: [\n").find("baseline.yaml:"), std::string::npos);  // YAML syntax error
}

TEST(BaselineFile, MismatchedRunIsBadInputNamingTheGate) {
  const auto text =
      "variants:\n"
      "  child-robot-social:\n"
      "    metrics.robot_item_moves_per_min: {expected: 2.6, rel: 0.25}\n"
      "    metrics.no_such_metric: {expected: 1, abs: 1}\n"
      "  child-child:\n"
      "    duration_s: {expected: 1400, rel: 0.25}\n";
  const auto baseline = parse_baseline(parse_yaml(text, "baseline.yaml"));
  try {
    check_run(synthetic_run({kSocial}), baseline);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("baseline.yaml:4:5"), std::string::npos) << message;
    EXPECT_NE(message.find("no metric 'metrics.no_such_metric'"), std::string::npos) << message;
    EXPECT_NE(message.find("baseline.yaml:6:5"), std::string::npos) << message;
    EXPECT_NE(message.find("no episodes of variant 'child-child'"), std::string::npos) << message;
  }
}

TEST(Junit, EscapesText) {
  EXPECT_EQ(xml_escape("a<b & \"c\" 'd'>\n\x01"), "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;&#10;?");
}

TEST(Junit, OneSuitePerVariantOneCasePerGateAndFailures) {
  auto degraded = kSocial;
  degraded.moves_per_min = 1.2;
  const auto baseline = make_baseline(synthetic_run({kAsocial, kSocial}), {});
  auto report = check_run(synthetic_run({kAsocial, degraded}, "runs/<weird & \"name\">"), baseline);
  const auto xml = junit_xml(report);
  EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>", 0), 0u);
  EXPECT_NE(xml.find("<testsuite name=\"child-robot-asocial\""), std::string::npos);
  EXPECT_NE(xml.find("<testsuite name=\"child-robot-social\" tests=\"4\" failures=\"1\""), std::string::npos);
  EXPECT_NE(xml.find("<failure message=\"metrics.robot_item_moves_per_min misses its band by"), std::string::npos);
  EXPECT_NE(xml.find("runs/&lt;weird &amp; &quot;name&quot;&gt;"), std::string::npos);
  std::size_t cases = 0;
  for (auto at = xml.find("<testcase "); at != std::string::npos; at = xml.find("<testcase ", at + 1)) ++cases;
  EXPECT_EQ(cases, report.results.size());

  // A real XML parser (python3's xml.etree) reads it back with the same counts.
  if (std::system("python3 -c 'pass' > /dev/null 2>&1") != 0) GTEST_SKIP() << "python3 is not installed";
  const auto dir = testing::fresh_dir("junit");
  std::ofstream(dir / "report.xml") << xml;
  const auto command =
      "python3 -c 'import sys, xml.etree.ElementTree as E\n"
      "root = E.parse(sys.argv[1]).getroot()\n"
      "assert root.tag == \"testsuites\", root.tag\n"
      "cases = root.findall(\"testsuite/testcase\")\n"
      "failures = root.findall(\"testsuite/testcase/failure\")\n"
      "assert len(root.findall(\"testsuite\")) == 2\n"
      "assert len(cases) == int(root.get(\"tests\")) == " + std::to_string(report.results.size()) + "\n"
      "assert len(failures) == int(root.get(\"failures\")) == 1\n"
      "assert failures[0].get(\"message\").startswith(\"metrics.robot_item_moves_per_min\")\n"
      "' " + (dir / "report.xml").string();
  EXPECT_EQ(std::system(command.c_str()), 0);
}

}  // namespace
}  // namespace freeplay::analysis
