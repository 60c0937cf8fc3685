#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>

#include "freeplay/agents/params.hpp"
#include "freeplay/core/assets.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"

using namespace freeplay;
using namespace freeplay::agents;

namespace {
std::string shipped_text() { return read_file(asset_path("agents/child-model.yaml")); }

std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

/// The 1-based line of the first occurrence of `needle` in `text` (the shipped file changes with every refit).
int line_of(const std::string& text, const std::string& needle) {
  const auto pos = text.find(needle);
  EXPECT_NE(pos, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
}

/// `text` with the rest of the line after the first `key` replaced by `value`.
std::string replace_value(std::string text, const std::string& key, const std::string& value) {
  const auto pos = text.find(key);
  EXPECT_NE(pos, std::string::npos) << key;
  const auto from = pos + key.size();
  return text.replace(from, text.find('\n', from) - from, value);
}

/// The number written after `label` on the first line of `text` that contains `line_key`, as the file spells it.
double number_on_line(const std::string& text, const std::string& line_key, const std::string& label) {
  const auto line = text.find(line_key);
  EXPECT_NE(line, std::string::npos) << line_key;
  const auto at = text.find(label, line);
  EXPECT_LT(at, text.find('\n', line)) << label;
  return std::stod(text.substr(at + label.size(), 40));
}

/// The message of the InputError that parsing `text` throws.
std::string message_of(const std::string& text, const std::string& file = "child.yaml") {
  try {
    (void)parse_child_model_params(text, file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST(Params, ShippedFileLoads) {
  const ChildModelParams p = default_child_model_params();
  EXPECT_DOUBLE_EQ(p.session_cap_s, 2400.0);
  EXPECT_GT(p.axis(Axis::TaskEngagement).dwell_median_s[0], 0.0);
  EXPECT_GT(p.drives.quit_hazard_per_min, 0.0);
}

TEST(Params, YamlRoundTripIsExact) {
  const ChildModelParams p = default_child_model_params();
  const std::string text = child_model_params_to_yaml(p, "test header");
  EXPECT_EQ(text.rfind("# test header\n", 0), 0U);
  const ChildModelParams q = parse_child_model_params(text);
  EXPECT_EQ(child_model_params_to_yaml(q, "test header"), text);
  EXPECT_TRUE(q == p);  // every value
  EXPECT_EQ(q.drives.decay_per_min, p.drives.decay_per_min);
  EXPECT_EQ(q.axis(Axis::SocialEngagement).coupling, p.axis(Axis::SocialEngagement).coupling);
}

TEST(Params, OutOfRangeValueNamesFileLineColumnAndKey) {
  const std::string bad = replace_once(shipped_text(), "decay_per_min: ", "decay_per_min: -");
  try {
    (void)parse_child_model_params(bad, "child.yaml");
    FAIL() << "accepted a negative decay";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "drives.decay_per_min");
    EXPECT_EQ(e.where().file, "child.yaml");
    EXPECT_GT(e.where().line, 1);
    EXPECT_GT(e.where().column, 1);
    EXPECT_NE(std::string(e.what()).find("child.yaml:"), std::string::npos);
  }
}

TEST(Params, UnknownKeysAndLabelsAreRejectedWithTheAllowedValues) {
  const std::string unknown = replace_once(shipped_text(), "  decay_per_min:", "  decay_per_minute: 1\n  decay_per_min:");
  try {
    (void)parse_child_model_params(unknown, "child.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "drives.decay_per_minute");
    EXPECT_NE(e.allowed().find("decay_per_min"), std::string::npos);
  }
  const std::string bad_label = replace_once(shipped_text(), "dwell_median_s: {goaloriented: ", "dwell_median_s: {goal-oriented: ");
  // Both problems at once: the unknown label with the allowed ones, and the label that is now missing.
  const std::string line = std::to_string(line_of(shipped_text(), "dwell_median_s: {goaloriented: "));
  EXPECT_EQ(message_of(bad_label),
            "'axes.task_engagement.dwell_median_s.goal-oriented': "  // the first problem's key
            "child.yaml:" + line + ":22: 'axes.task_engagement.dwell_median_s.goal-oriented': unknown key 'goal-oriented' (allowed: "
            "goaloriented, aimless, adultseeking, noplay)\n"
            "child.yaml:" + line + ":21: 'axes.task_engagement.dwell_median_s.goaloriented': missing required key 'goaloriented' "
            "(allowed: a number in [0.5, 3600])\n"
            "(2 problems in all)");
  EXPECT_THROW((void)parse_child_model_params("version: 1\n", "x.yaml"), InputError);
  EXPECT_EQ(message_of("[unclosed", "x.yaml"), "x.yaml:1:1: YAML syntax error: end of sequence flow not found");
}

TEST(Params, EveryValueOfTheShippedFileIsReadExactly) {
  // Fitted values are compared with the number as the file spells it (they change with every refit), the others
  // with their value.
  const ChildModelParams p = default_child_model_params();
  const std::string text = shipped_text();
  const AxisModel& task = p.axis(Axis::TaskEngagement);
  const std::string dwell = "    dwell_median_s: {goaloriented: ";
  EXPECT_EQ(task.dwell_median_s,
            (std::array<double, kMaxLabels>{number_on_line(text, dwell, "goaloriented: "),
                                            number_on_line(text, dwell, "aimless: "),
                                            number_on_line(text, dwell, "adultseeking: "),
                                            number_on_line(text, dwell, "noplay: "), 0.0}));
  EXPECT_EQ(task.bias[3], number_on_line(text, "    bias: {goaloriented: ", "noplay: "));
  EXPECT_EQ(task.transition[0], (std::array<double, kMaxLabels>{0.0, 0.31, 0.19, 0.5, 0.0}));  // no own weight
  EXPECT_EQ(task.coupling[0][static_cast<std::size_t>(Feature::Tablet)], 0.2);
  EXPECT_EQ(task.coupling[3][static_cast<std::size_t>(Feature::Motivation)], -3.0);
  EXPECT_EQ(task.coupling[3][static_cast<std::size_t>(Feature::Age)], 0.0);  // absent features are zero
  EXPECT_EQ(p.axis(Axis::SocialAttitude).dwell_sigma[4], 1.395);
  EXPECT_EQ(p.drives.quit_hazard_per_min, number_on_line(text, "  quit_hazard_per_min: ", "quit_hazard_per_min: "));
  EXPECT_EQ(p.motor.action_gap_median_s, (std::array<double, 4>{3.0, 2.5, 12.0, 0.0}));
  EXPECT_EQ(p.expression.proposal_share,
            (std::array<double, 5>{0.3, 0.3, number_on_line(text, "proposal_share: {", "assertive: "), 0.1, 0.1}));
  EXPECT_EQ(p.partnership.answer_probability[4], number_on_line(text, "answer_probability: {", "cooperative: "));
  EXPECT_EQ(p.coder.assertive_hold_s, 6.0);
}

TEST(Params, AMissingKeyIsNamedWithTheLineOfItsSection) {
  const std::string text = replace_once(shipped_text(), "  grievance_tau_s: 60\n", "");
  EXPECT_EQ(message_of(text), "child.yaml:" + std::to_string(line_of(text, "\ndrives:\n") + 2) +
                                  ":3: 'drives.grievance_tau_s': missing required key 'grievance_tau_s' "
                                  "(allowed: a number in [0.1, 3600])");
  const std::string no_section = replace_once(shipped_text(), "traits:", "trait:");
  EXPECT_NE(message_of(no_section).find("'traits': missing required key 'traits'"), std::string::npos);
  const std::string no_row = replace_once(shipped_text(), "      noplay: {goaloriented: 0.48, aimless: 0.45, adultseeking: 0.07}\n", "");
  EXPECT_NE(message_of(no_row).find("'axes.task_engagement.transitions.noplay': missing required key 'noplay'"),
            std::string::npos);
}

TEST(Params, ANonNumberIsNamedWithItsLineAndColumn) {
  const std::string text = replace_value(shipped_text(), "  bid_floor: ", "low");
  EXPECT_EQ(message_of(text), "child.yaml:" + std::to_string(line_of(text, "  bid_floor: ")) +
                                  ":14: 'partnership.bid_floor': expected a finite number, found 'low' "
                                  "(allowed: a number in [0, 1])");
  const std::string map = replace_once(shipped_text(), "proposal_share: {", "proposal_share: [");
  EXPECT_NE(message_of(replace_once(map, "passive: 0.1}", "passive: 0.1]")).find("'expression.proposal_share': "
                                                                                 "expected a map"),
            std::string::npos);
}

TEST(Params, AnOutOfRangeValueStatesTheRange) {
  const std::string text = replace_value(shipped_text(), "  joint_distance_m: ", "2");
  EXPECT_EQ(message_of(text), "child.yaml:" + std::to_string(line_of(text, "  joint_distance_m: ")) +
                                  ":21: 'coder.joint_distance_m': 2 is out of range "
                                  "(allowed: a number in [0, 1])");
  const std::string label = replace_once(shipped_text(), "dwell_sigma: {goaloriented: 1.34", "dwell_sigma: {goaloriented: 4");
  EXPECT_NE(message_of(label).find("'axes.task_engagement.dwell_sigma.goaloriented': 4 is out of range (allowed: a "
                                   "number in [0.05, 3])"),
            std::string::npos);
}

TEST(Params, RulesAcrossKeysNameTheOffendingKey) {
  const std::string row = replace_once(shipped_text(), "noplay: {goaloriented: 0.48, aimless: 0.45, adultseeking: 0.07}",
                                       "noplay: {noplay: 1}");  // only its own label: no way out
  EXPECT_EQ(message_of(row), "child.yaml:" + std::to_string(line_of(row, "noplay: {noplay: 1}")) +
                                 ":15: 'axes.task_engagement.transitions.noplay': a row needs at least one "
                                 "positive weight to another label");
  const std::string taps = replace_once(shipped_text(), "tap_max_s: 0.2", "tap_max_s: 0.05");
  EXPECT_EQ(message_of(taps),
            "child.yaml:" + std::to_string(line_of(taps, "tap_max_s: 0.05")) + ":14: 'motor.tap_max_s': must be ≥ tap_min_s");
}
