#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/scenario/suite.hpp"
#include "../scratch_dir.hpp"

using namespace freeplay;
using namespace freeplay::scenario;

namespace {

/// A scratch folder for this file's test `name`.
std::filesystem::path fresh_dir(const std::string& name) { return test_support::fresh_dir("suite-" + name); }

}  // namespace

TEST(Suite, ExpandsSweepsAndAppliesEntryOverrides) {
  const auto dir = fresh_dir("suite");
  write_file_atomically(dir / "cc.yaml", "name: cc\ncondition: child-child\nepisodes: 3\n");
  write_file_atomically(dir / "cr.yaml", "name: cr\ncondition: child-robot\n");
  write_file_atomically(dir / "suite.yaml",
                        "suite: s\nscenarios:\n"
                        "  - scenario: cc.yaml\n    episodes: 5\n"
                        "  - scenario: cr.yaml\n    set: {planner.name: rrtconnect}\n"
                        "    sweep: {perception.latency_s: [0.1, 0.3], robot.arm_reach_m: [0.4, 0.5]}\n");
  const auto suite = load_suite(dir / "suite.yaml");
  ASSERT_EQ(suite.variants.size(), 5u);
  EXPECT_EQ(suite.variants[0].id, "cc");
  EXPECT_EQ(suite.variants[0].scenario.episodes, 5);
  EXPECT_EQ(suite.variants[1].id, "cr[perception.latency_s=0.1,robot.arm_reach_m=0.4]");
  EXPECT_EQ(suite.variants[4].scenario.planner.name, "rrtconnect");
  EXPECT_DOUBLE_EQ(suite.variants[4].scenario.perception.latency_s, 0.3);
  EXPECT_EQ(suite.total_episodes(), 5 + 4);
  EXPECT_TRUE(is_suite_file(dir / "suite.yaml"));
  EXPECT_FALSE(is_suite_file(dir / "cc.yaml"));
}

TEST(Suite, BadEntriesAreReportedWithTheSuiteLocation) {
  const auto dir = fresh_dir("suite_bad");
  write_file_atomically(dir / "suite.yaml", "suite: s\nscenarios:\n  - scenario: missing.yaml\n");
  try {
    load_suite(dir / "suite.yaml");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("suite.yaml:3:15"), std::string::npos) << msg;
    EXPECT_NE(msg.find("does not exist"), std::string::npos) << msg;
  }
}
