#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/runner/run_folder.hpp"
#include "freeplay/runner/suite.hpp"

using namespace freeplay;
using namespace freeplay::runner;

namespace {

std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("freeplay_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

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

TEST(RunFolder, ResumesAndDropsATornLastLine) {
  const auto dir = fresh_dir("run_folder");
  {
    RunFolder run(dir);
    run.append({{"variant", "cc"}, {"episode", 1}, {"config_hash", 42}});
    run.append({{"variant", "cc"}, {"episode", 0}, {"config_hash", 42}});
  }
  {  // a crash in the middle of the third append
    std::ofstream out(dir / "episodes.jsonl", std::ios::app);
    out << "{\"variant\": \"cc\", \"epis";
  }
  RunFolder resumed(dir);
  EXPECT_TRUE(resumed.dropped_partial_line());
  EXPECT_EQ(resumed.records().size(), 2u);
  EXPECT_TRUE(resumed.finished("cc", 0, 42));
  EXPECT_FALSE(resumed.finished("cc", 2, 42));
  EXPECT_THROW(resumed.finished("cc", 1, 43), InputError);  // same episode, other configuration
  resumed.finalize({"cc"});
  RunFolder reread(dir);
  ASSERT_EQ(reread.records().size(), 2u);
  EXPECT_EQ(reread.records()[0]["episode"], 0);
  EXPECT_FALSE(reread.dropped_partial_line());
}

TEST(RunFolder, RemembersAnEpisodeRecordedWithAnotherConfiguration) {
  // The index keeps one hash per variant and the episodes that differ from it.
  const auto dir = fresh_dir("run_folder_hashes");
  {
    RunFolder run(dir);
    run.append({{"variant", "cc"}, {"episode", 0}, {"config_hash", 42}});
    run.append({{"variant", "cc"}, {"episode", 5}, {"config_hash", 7}});
    run.append({{"variant", "cr"}, {"episode", 2}, {"config_hash", 9}});
  }
  RunFolder resumed(dir);
  EXPECT_TRUE(resumed.finished("cc", 0, 42));
  EXPECT_TRUE(resumed.finished("cc", 5, 7));
  EXPECT_THROW(resumed.finished("cc", 5, 42), InputError);
  EXPECT_THROW(resumed.finished("cc", 0, 7), InputError);
  EXPECT_FALSE(resumed.finished("cc", 3, 42));
  EXPECT_FALSE(resumed.finished("cc", 100, 42));
  EXPECT_TRUE(resumed.finished("cr", 2, 9));
  EXPECT_FALSE(resumed.finished("cr", 1, 9));
  EXPECT_FALSE(resumed.finished("other", 0, 42));
}

TEST(RunFolder, EpisodeFileIdsAreSafe) {
  EXPECT_EQ(RunFolder::episode_file_id("cr[a.b=0.1]", 7), "cr_a.b=0.1_-0007");
}
