// The run folder (resume, torn last lines, configuration hashes, file ids) and the summaries written into it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "freeplay/core/error.hpp"
#include "freeplay/results/run_folder.hpp"
#include "freeplay/results/summary.hpp"
#include "../scratch_dir.hpp"

using namespace freeplay;
using namespace freeplay::results;

namespace {

/// A scratch folder for this file's test `name`.
std::filesystem::path fresh_dir(const std::string& name) { return test_support::fresh_dir("results-" + name); }

}  // namespace

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

TEST(RunFolder, WriteSummariesSummarisesTheFinishedEpisodesInVariantOrder) {
  const auto dir = fresh_dir("run_folder_summaries");
  {
    RunFolder run(dir);
    for (int i = 0; i < 3; ++i) {
      run.append({{"variant", "cr"}, {"condition", "child-robot"}, {"episode", i}, {"duration_s", 600.0 * (i + 1)},
                  {"config_hash", 1}});
      run.append({{"variant", "cc"}, {"condition", "child-child"}, {"episode", i}, {"duration_s", 1200.0},
                  {"config_hash", 2}});
    }
  }
  const std::string markdown = write_summaries(dir, {"cc", "cr"}, "two variants");
  ASSERT_TRUE(std::filesystem::is_regular_file(dir / "summary.csv"));
  std::ifstream md_file(dir / "summary.md");
  const std::string written((std::istreambuf_iterator<char>(md_file)), std::istreambuf_iterator<char>());
  EXPECT_EQ(written, markdown);
  EXPECT_NE(markdown.find("two variants"), std::string::npos) << markdown;
  EXPECT_LT(markdown.find("cc"), markdown.find("cr")) << markdown;  // the given order, not the records'
}
