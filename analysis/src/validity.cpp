#include "freeplay/analysis/validity.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "freeplay/agents/labels.hpp"
#include "freeplay/analysis/baseline.hpp"
#include "freeplay/core/error.hpp"
#include "report_values.hpp"

namespace freeplay::analysis {

namespace {

using detail::kNaN;
using detail::values_of;
using detail::json_number;

/// The mean of `metric` over `sample`; InputError when no episode has it.
double mean_of(const Sample& sample, const std::string& metric) {
  const auto values = values_of(sample.episodes, metric);
  if (values.empty()) {
    throw InputError(fmt::format("the run '{}' has no value of {}", sample.label, metric), "RUN",
                     "a child-robot run whose episodes.jsonl records hold the coded label shares");
  }
  return mean(values);
}

/// `sample` with the derived joint-play share (the shares of agents::kJointPlay) added to each episode that has them.
Sample with_joint_play(Sample sample) {
  std::vector<std::string> metrics;
  for (const auto label : agents::kJointPlay) metrics.push_back(share_metric(std::string(agents::name(label))));
  for (auto& e : sample.episodes) {
    double joint = 0.0;
    bool complete = true;
    for (const auto& metric : metrics) {
      const auto found = e.metrics.find(metric);
      complete = complete && found != e.metrics.end();
      if (found != e.metrics.end()) joint += found->second;
    }
    if (complete) e.metrics[kJointPlayMetric] = joint;
  }
  return sample;
}

RobotRow row_of(const Sample& sample) {
  if (sample.episodes.empty()) {
    throw InputError(fmt::format("the run '{}' holds no episode", sample.label), "RUN", "a finished run");
  }
  RobotRow row;
  row.robot = sample.label;
  row.n = static_cast<int>(sample.episodes.size());
  row.duration_s = mean_of(sample, "duration_s");
  for (const auto& label : panel_labels()) row.shares.push_back(mean_of(sample, share_metric(label)));
  return row;
}

std::string decimal_text(double v, int decimals = 3) {
  return std::isfinite(v) ? fmt::format("{:.{}f}", v, decimals) : std::string("–");
}

/// A gate `value` ≤ `bound` (upper) or `value` > `bound` (lower), with its verdict line.
ValidityGate make_gate(std::string robot, std::string name, double value, double bound, bool upper,
                       const std::string& bound_text, int decimals = 3) {
  ValidityGate g{std::move(robot), std::move(name), value, bound, upper, false, {}};
  g.passed = std::isfinite(value) && (upper ? value <= bound + 1e-12 : value > bound);
  const auto relation = upper ? "≤" : ">";
  g.verdict = fmt::format("{} = {} (must be {} {}: {})", g.name, decimal_text(value, decimals), relation,
                          decimal_text(bound, decimals), bound_text);
  if (!g.passed && std::isfinite(value)) {
    g.verdict += fmt::format("; misses by {}", decimal_text(std::abs(value - bound), decimals));
  }
  if (!std::isfinite(value)) g.verdict += "; not measured (the runs could not be paired by seed)";
  return g;
}


}  // namespace

int ValidityReport::failures() const {
  return static_cast<int>(std::count_if(gates.begin(), gates.end(), [](const ValidityGate& g) { return !g.passed; }));
}

std::string share_metric(const std::string& label) { return "metrics.label_share.purple." + label; }

std::vector<std::string> panel_labels() {
  std::vector<std::string> out;
  for (const auto axis : agents::kAxes) {
    for (std::size_t i = 0; i < agents::label_count(axis); ++i) out.emplace_back(agents::label_name(axis, i));
  }
  return out;
}

ValidityReport evaluate_panel(const ValidityPanel& panel, const ValidityBounds& bounds) {
  ValidityReport report;
  report.bounds = bounds;
  report.robots.push_back(row_of(panel.asocial));
  report.robots.push_back(row_of(panel.social));
  for (const auto& robot : panel.degenerate) report.robots.push_back(row_of(robot));

  const auto labels = panel_labels();
  const auto share_of = [&](const RobotRow& row, const std::string& label) {
    return row.shares[static_cast<std::size_t>(std::find(labels.begin(), labels.end(), label) - labels.begin())];
  };
  const auto& asocial = report.robots[0];
  const double associative_bound = share_of(asocial, "associative") + bounds.associative_margin;
  const double duration_bound_min = (asocial.duration_s + bounds.duration_margin_s) / 60.0;
  for (std::size_t i = 2; i < report.robots.size(); ++i) {
    const auto& row = report.robots[i];
    report.gates.push_back(make_gate(row.robot, "cooperative share", share_of(row, "cooperative"),
                                     bounds.max_cooperative, true, "a robot that ignores the child"));
    report.gates.push_back(make_gate(row.robot, "associative share", share_of(row, "associative"), associative_bound,
                                     true,
                                     fmt::format("asocial's {} + {}", decimal_text(share_of(asocial, "associative")),
                                                 decimal_text(bounds.associative_margin, 2))));
    report.gates.push_back(make_gate(row.robot, "mean duration (min)", row.duration_s / 60.0, duration_bound_min, true,
                                     fmt::format("asocial's {} min + {} min",
                                                 decimal_text(asocial.duration_s / 60.0, 2),
                                                 decimal_text(bounds.duration_margin_s / 60.0, 1)),
                                     2));
  }

  // Social against its yoked control, paired by seed (the same children): yoked is A, social is B.
  CompareOptions options;
  options.confidence = bounds.confidence;
  options.resamples = bounds.resamples;
  options.seed = bounds.bootstrap_seed;
  options.metrics = {"duration_s", kJointPlayMetric};
  for (const auto& label : labels) options.metrics.push_back(share_metric(label));
  const Sample yoked = with_joint_play(panel.yoked);
  const Sample social = with_joint_play(panel.social);
  const auto comparison = compare_samples(yoked, social, options);
  for (const auto& name : options.metrics) {
    PairedRow row{name, 0, kNaN, {kNaN, kNaN}};
    for (const auto& m : comparison.metrics) {
      if (m.metric != name) continue;
      row.difference = m.difference;
      if (m.paired) row = {name, m.paired->pairs, m.paired->mean_difference, m.paired->ci};
    }
    report.paired.push_back(row);
  }
  const auto ci_low = [&](const std::string& metric) {
    for (const auto& row : report.paired) {
      if (row.metric == metric && row.pairs > 0) return row.ci.low;
    }
    return kNaN;
  };
  const auto confidence = fmt::format("{:g} %", bounds.confidence * 100);
  report.gates.push_back(make_gate(social.label, "joint play: social − yoked, CI low", ci_low(kJointPlayMetric), 0.0,
                                   false, fmt::format("the paired {} CI excludes zero", confidence)));
  report.gates.push_back(make_gate(social.label, "duration (s): social − yoked, CI low", ci_low("duration_s"), 0.0,
                                   false, fmt::format("the paired {} CI excludes zero", confidence), 1));
  return report;
}

std::string validity_table(const ValidityReport& report) {
  const auto labels = panel_labels();
  std::size_t width = 5;
  for (const auto& row : report.robots) width = std::max(width, row.robot.size());
  std::string out = fmt::format("{:<{}} {:>5} {:>8}", "robot", width, "n", "min");
  for (const auto& label : labels) out += fmt::format(" {:>7.7}", label);
  out += "\n";
  for (const auto& row : report.robots) {
    out += fmt::format("{:<{}} {:>5} {:>8.2f}", row.robot, width, row.n, row.duration_s / 60.0);
    for (const double s : row.shares) out += fmt::format(" {:>7.3f}", s);
    out += "\n";
  }
  out += "\ngates\n";
  for (const auto& g : report.gates) {
    out += fmt::format("  {:<4} {:<{}}  {}\n", g.passed ? "ok" : "FAIL", g.robot, width, g.verdict);
  }
  out += fmt::format("\nsocial − yoked, paired by seed (the same children), {:g} % bootstrap CIs\n",
                     report.bounds.confidence * 100);
  for (const auto& row : report.paired) {
    out += fmt::format("  {:<44} {:>9} [{}, {}]  ({} pairs)\n", row.metric, decimal_text(row.difference, 4),
                       decimal_text(row.ci.low, 4), decimal_text(row.ci.high, 4), row.pairs);
  }
  out += fmt::format("\n{} of {} gates failed\n", report.failures(), report.gates.size());
  return out;
}

nlohmann::json validity_json(const ValidityReport& report) {
  const auto labels = panel_labels();
  nlohmann::json robots = nlohmann::json::array();
  for (const auto& row : report.robots) {
    nlohmann::json shares = nlohmann::json::object();
    for (std::size_t i = 0; i < labels.size(); ++i) shares[labels[i]] = json_number(row.shares[i]);
    robots.push_back(
        {{"robot", row.robot}, {"n", row.n}, {"duration_s", json_number(row.duration_s)}, {"shares", shares}});
  }
  nlohmann::json gates = nlohmann::json::array();
  for (const auto& g : report.gates) {
    gates.push_back({{"robot", g.robot}, {"gate", g.name}, {"value", json_number(g.value)},
                     {"bound", json_number(g.bound)}, {"relation", g.upper ? "<=" : ">"}, {"passed", g.passed},
                     {"verdict", g.verdict}});
  }
  nlohmann::json paired = nlohmann::json::array();
  for (const auto& row : report.paired) {
    paired.push_back({{"metric", row.metric}, {"pairs", row.pairs}, {"difference", json_number(row.difference)},
                      {"ci", {json_number(row.ci.low), json_number(row.ci.high)}}});
  }
  return {{"robots", robots},
          {"gates", gates},
          {"social_minus_yoked", paired},
          {"confidence", report.bounds.confidence},
          {"failures", report.failures()}};
}

std::string validity_junit(const ValidityReport& report) {
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += fmt::format("<testsuites name=\"freeplay validity\" tests=\"{}\" failures=\"{}\">\n", report.gates.size(),
                     report.failures());
  out += fmt::format("  <testsuite name=\"validity\" tests=\"{}\" failures=\"{}\">\n", report.gates.size(),
                     report.failures());
  for (const auto& g : report.gates) {
    out += fmt::format("    <testcase classname=\"{}\" name=\"{}\" time=\"0\">\n",
                       xml_escape("freeplay.validity." + g.robot), xml_escape(g.name));
    if (!g.passed) {
      out += fmt::format("      <failure message=\"{}\" type=\"ValidityGate\">{}</failure>\n",
                         xml_escape(g.robot + ": " + g.name + " breaks its bound"), xml_escape(g.verdict));
    }
    out += fmt::format("      <system-out>{}</system-out>\n    </testcase>\n", xml_escape(g.verdict));
  }
  out += "  </testsuite>\n</testsuites>\n";
  return out;
}

}  // namespace freeplay::analysis
