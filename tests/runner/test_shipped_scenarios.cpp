#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "freeplay/runner/suite.hpp"

using namespace freeplay::runner;

namespace {
std::filesystem::path scenarios_dir() {
  const char* assets = std::getenv("FREEPLAY_ASSETS_DIR");
  return std::filesystem::path(assets != nullptr ? assets : "assets").parent_path() / "scenarios";
}
}  // namespace

TEST(ShippedScenarios, EveryFileValidates) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(scenarios_dir())) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    EXPECT_NO_THROW({
      if (is_suite_file(entry.path())) {
        load_suite(entry.path());
      } else {
        load_scenario(entry.path());
      }
    }) << entry.path();
  }
  EXPECT_GE(files, 4);
}

TEST(ShippedScenarios, BaselinesHavePInSoRoSessionCounts) {
  const auto suite = load_suite(scenarios_dir() / "baselines.yaml");
  ASSERT_EQ(suite.variants.size(), 3u);
  EXPECT_EQ(suite.variants[0].scenario.condition, "child-child");
  EXPECT_EQ(suite.variants[0].scenario.episodes, 45);
  EXPECT_EQ(suite.variants[1].scenario.robot.policy, "asocial");
  EXPECT_EQ(suite.variants[1].scenario.episodes, 30);
  EXPECT_EQ(suite.variants[2].scenario.robot.policy, "social");
  EXPECT_EQ(suite.variants[2].scenario.episodes, 30);
  // Common random numbers: both robot conditions share the seed, hence the same synthetic children.
  EXPECT_EQ(suite.variants[1].scenario.seed, suite.variants[2].scenario.seed);
}
