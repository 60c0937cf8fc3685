#pragma once
// The validity panel: robots that ignore the child (timetables, a yoked copy of the social policy, idle) must not
// earn joint play or keep children, and the social policy must beat its own yoked control (docs/validity.md).
// This file holds the gates and their reports; `freeplay validity` runs the panel's robots.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "freeplay/analysis/compare.hpp"
#include "freeplay/core/statistics.hpp"

namespace freeplay::analysis {

/// The bounds of the panel's gates (docs/validity.md says why each is where it is).
struct ValidityBounds {
  double max_cooperative = 0.05;           ///< a degenerate robot's cooperative share at most this
  double associative_margin = 0.05;        ///< … and its associative share at most the asocial robot's + this
  double duration_margin_s = 120.0;        ///< no degenerate robot keeps children longer than asocial + this
  double confidence = 0.95;                ///< level of the paired CIs of social − yoked
  int resamples = 2000;                    ///< bootstrap resamples of those CIs
  std::uint64_t bootstrap_seed = 1;        ///< bootstrap seed
};

/// The panel's runs: the references, the social policy's yoked control and the degenerate robots.
struct ValidityPanel {
  Sample asocial;                 ///< the asocial robot (the real `play` node): the reference of the bounds
  Sample social;                  ///< the social policy
  Sample yoked;                   ///< the yoked control of `social` (also one of `degenerate`, by name)
  std::vector<Sample> degenerate; ///< every robot that ignores the child (timetables, yoked, idle), in table order
};

/// The panel's per-robot numbers: episodes, mean free-play duration and the purple child's 14 label shares.
struct RobotRow {
  std::string robot;            ///< sample label
  int n = 0;                    ///< episodes
  double duration_s = 0.0;      ///< mean free-play duration
  std::vector<double> shares;   ///< per-child mean share of each label of `panel_labels()`
};

/// One gate of the panel: a measured value against its bound.
struct ValidityGate {
  std::string robot;     ///< whose value
  std::string name;      ///< e.g. "cooperative share", "joint play: social − yoked"
  double value = 0.0;    ///< the measured value (a mean, or the CI's low end for the paired gates)
  double bound = 0.0;    ///< the bound
  bool upper = true;     ///< true: passes when value ≤ bound; false: passes when value > bound
  bool passed = false;   ///< within the bound
  std::string verdict;   ///< one line: value, bound and by how much it misses
};

/// One paired difference social − yoked (episodes paired by seed: the same children).
struct PairedRow {
  std::string metric;          ///< dotted metric name (or "joint_play_share")
  int pairs = 0;               ///< paired episodes (0: the runs could not be paired)
  double difference = 0.0;     ///< mean of social − yoked
  Interval ci;                 ///< paired bootstrap CI of the mean difference
};

/// Everything the panel measured and decided.
struct ValidityReport {
  std::vector<RobotRow> robots;       ///< asocial, social, then the degenerate robots
  std::vector<ValidityGate> gates;    ///< in a fixed order: per degenerate robot, then social against yoked
  std::vector<PairedRow> paired;      ///< social − yoked: duration, joint play and the 14 shares
  ValidityBounds bounds;              ///< the bounds used

  /// Number of failed gates.
  int failures() const;
};

/// The metric name of the purple child's share of `label` (e.g. "metrics.label_share.purple.cooperative").
std::string share_metric(const std::string& label);
/// The derived per-episode metric: the purple child's associative + cooperative share.
inline constexpr const char* kJointPlayMetric = "joint_play_share";
/// The 14 labels of the coding scheme in the scheme's order (task, social engagement, social attitude).
std::vector<std::string> panel_labels();

/// Evaluates every gate of the panel; InputError when a sample has no episodes or lacks the label shares.
ValidityReport evaluate_panel(const ValidityPanel& panel, const ValidityBounds& bounds = {});

/// A readable report: the robots' table (duration and 14 shares), every gate with value, bound and ok/FAIL, and
/// social − yoked with paired CIs.
std::string validity_table(const ValidityReport& report);
/// Every number of the report as JSON (NaN becomes null).
nlohmann::json validity_json(const ValidityReport& report);
/// JUnit XML: one <testsuite> "validity", one <testcase> per gate, <failure> for failed gates.
std::string validity_junit(const ValidityReport& report);

}  // namespace freeplay::analysis
