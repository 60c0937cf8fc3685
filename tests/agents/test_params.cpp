#include <gtest/gtest.h>

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
  try {
    (void)parse_child_model_params(bad_label, "child.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(e.allowed().find("goaloriented"), std::string::npos);
  }
  EXPECT_THROW((void)parse_child_model_params("version: 1\n", "x.yaml"), InputError);
  EXPECT_THROW((void)parse_child_model_params("[unclosed", "x.yaml"), InputError);
}
