#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "freeplay/policies/play_policy.hpp"
#include "freeplay/scenario/suite.hpp"

using namespace freeplay::scenario;

namespace {
std::filesystem::path scenarios_dir() {
  const char* assets = std::getenv("FREEPLAY_ASSETS_DIR");
  return std::filesystem::path(assets != nullptr ? assets : "assets").parent_path() / "scenarios";
}
}  // namespace

TEST(ShippedScenarios, EveryFileValidates) {
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(scenarios_dir())) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    EXPECT_NO_THROW({
      if (is_suite_file(entry.path())) {
        load_suite(entry.path());
      } else {
        ScenarioVocabulary registered;  // every linked policy, `yoked` included
        registered.policies = freeplay::policies::policy_names();
        const auto scenario = load_scenario(entry.path(), {}, registered);
        // Timetables are checked by the policy itself (a yoked policy needs its source run: not shipped).
        if (scenario.robot.policy == "scripted") freeplay::policies::make_policy("scripted", scenario.robot.params);
      }
    }) << entry.path();
  }
  EXPECT_GE(files, 8);
}

TEST(ShippedScenarios, BaselinesAreLargeAndThePInSoRoVariantHasItsSessionCounts) {
  const auto check = [](const char* file, int cc, int cr) {
    const auto suite = load_suite(scenarios_dir() / file);
    ASSERT_EQ(suite.variants.size(), 3u) << file;
    EXPECT_EQ(suite.variants[0].scenario.condition, Condition::ChildChild);
    EXPECT_EQ(suite.variants[0].scenario.episodes, cc);
    EXPECT_EQ(suite.variants[1].scenario.robot.policy, "asocial");
    EXPECT_EQ(suite.variants[1].scenario.episodes, cr);
    EXPECT_EQ(suite.variants[2].scenario.robot.policy, "social");
    EXPECT_EQ(suite.variants[2].scenario.episodes, cr);
    // Common random numbers: both robot conditions share the seed, hence the same synthetic children.
    EXPECT_EQ(suite.variants[1].scenario.seed, suite.variants[2].scenario.seed);
  };
  check("baselines.yaml", 200, 200);
  check("baselines-pinsoro.yaml", 45, 30);
}
