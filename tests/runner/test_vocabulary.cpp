// The scenario vocabulary's default names (what a parser without the registries accepts) are the owners' lists:
// items of the catalogue, the planners make_planner builds, the stage's real cameras, registered policies.

#include <gtest/gtest.h>

#include <algorithm>

#include "freeplay/agents/item_names.hpp"
#include "freeplay/planning/plan.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/scenario/settings.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/stage/camera_names.hpp"

using namespace freeplay;

namespace {

std::vector<std::string> sorted(std::vector<std::string> names) {
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST(ScenarioVocabulary, ItemsAreTheCataloguesInThePolicyOrder) {
  const scenario::ScenarioVocabulary vocabulary;
  EXPECT_EQ(vocabulary.items, std::vector<std::string>(agents::kItemNames.begin(), agents::kItemNames.end()));
  std::vector<std::string> catalogue;
  const auto loaded = sim::ItemCatalogue::load_default();
  for (const auto& item : loaded.items()) catalogue.push_back(item.name);
  EXPECT_EQ(sorted(vocabulary.items), sorted(catalogue));
}

TEST(ScenarioVocabulary, PlannersCamerasAndPoliciesComeFromTheirOwners) {
  const scenario::ScenarioVocabulary vocabulary;
  EXPECT_EQ(sorted(vocabulary.planners), planning::planner_names());
  EXPECT_EQ(vocabulary.cameras, stage::real_camera_names());
  EXPECT_EQ(vocabulary.policies, policies::policy_names());  // policies::kPolicyNames: every registered one
}
