#include <gtest/gtest.h>

#include "freeplay/core/error.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/policies/policy_names.hpp"

using namespace freeplay;
using namespace freeplay::policies;

TEST(PolicyRegistry, BuiltInPoliciesAreRegistered) {
  const auto names = policy_names();
  for (const char* expected : {"asocial", "idle", "scripted"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  }
  EXPECT_EQ(make_policy("asocial")->name(), "asocial");
}

TEST(PolicyRegistry, TheShippedNamesAreTheRegisteredOnes) {
  EXPECT_EQ(policy_names(), std::vector<std::string>(kPolicyNames.begin(), kPolicyNames.end()));
  for (const auto& name : policy_names()) EXPECT_TRUE(is_policy_name(name)) << name;
  EXPECT_FALSE(is_policy_name("telepathic"));
  EXPECT_FALSE(is_policy_name("python:module:Class"));
  static_assert(is_policy_name("yoked"));
}

TEST(PolicyRegistry, UnknownPolicyListsTheRegisteredOnes) {
  try {
    make_policy("telepathic");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("asocial"), std::string::npos);
  }
}

TEST(ScriptedPolicy, ReplaysActionsAtTheirTimes) {
  auto policy = make_policy("scripted", YAML::Load(R"(
actions:
  - {t: 2.0, say: {text: "Hello!", to: purple}}
  - {t: 1.0, move: {item: zebra, to: [0.2, -0.1]}}
  - {t: 2.0, point_at: [0.3, -0.2]}
)"));
  policy->reset({}, Rng(1));
  Observation obs;
  obs.t = 0.5;
  EXPECT_TRUE(policy->decide(obs).empty());
  obs.t = 1.0;
  auto due = policy->decide(obs);
  ASSERT_EQ(due.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<MoveItem>(due[0]));
  EXPECT_EQ(std::get<MoveItem>(due[0]).item, "zebra");
  obs.t = 2.05;
  due = policy->decide(obs);
  ASSERT_EQ(due.size(), 2u);
  EXPECT_EQ(std::get<Say>(due[0]).addressee, "purple");
}

TEST(ScriptedPolicy, RejectsAnActionWithTwoKinds) {
  EXPECT_THROW(make_policy("scripted", YAML::Load("actions: [{t: 1, wait: 1, cancel: true}]")), InputError);
  EXPECT_THROW(make_policy("scripted", YAML::Load("actions: [{t: 1, dance: true}]")), InputError);
  EXPECT_THROW(make_policy("scripted", YAML::Load("{}")), InputError);
}

TEST(PolicyRegistry, PythonPoliciesOutsidePythonSayWhereToRunThem) {
  try {
    check_policy_available("python:my_policies:Tidy");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("python3 -m freeplay"), std::string::npos) << e.what();
    EXPECT_EQ(e.key(), "robot.policy");
  }
  EXPECT_THROW(make_policy("python:my_policies:Tidy"), InputError);
  const auto patterns = policy_name_patterns();
  EXPECT_NE(std::find(patterns.begin(), patterns.end(), "python:*"), patterns.end());
}

TEST(PolicyRegistry, AFamilyBuildsEveryNameWithItsPrefix) {
  std::string built;
  register_policy_family("test-family:", [&](const std::string& name, const YAML::Node& params) {
    built = name;
    return make_policy("idle", params);
  });
  EXPECT_NO_THROW(check_policy_available("test-family:anything"));
  EXPECT_EQ(make_policy("test-family:anything")->name(), "idle");
  EXPECT_EQ(built, "test-family:anything");
  const auto patterns = policy_name_patterns();
  EXPECT_NE(std::find(patterns.begin(), patterns.end(), "test-family:*"), patterns.end());
}
