// Shard + merge equals the whole run (real runner, fake episodes); duplicates, missing episodes, different
// suites and configuration mismatches are refused without writing anything.

#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "freeplay/analysis/merge.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "synthetic_runs.hpp"

namespace freeplay::analysis {
namespace {

namespace fs = std::filesystem;

scenario::Suite tiny_suite() {
  scenario::Suite suite;
  suite.name = "tiny";
  const std::vector<std::pair<std::string, int>> variants = {
      {"child-child", 7}, {"child-robot-asocial", 5}, {"child-robot-social[robot.params.x=1]", 6}};
  for (const auto& [id, episodes] : variants) {
    scenario::SuiteVariant v;
    v.id = id;
    v.scenario.name = id.substr(0, id.find('['));
    v.scenario.condition = id == "child-child" ? scenario::Condition::ChildChild : scenario::Condition::ChildRobot;
    v.scenario.robot.policy = id.find("social") != std::string::npos && id.find("asocial") == std::string::npos ? "social"
                                                                                                         : "asocial";
    v.scenario.episodes = episodes;
    v.scenario.seed = 2017;
    v.scenario.config_hash = fnv1a64(id);
    suite.variants.push_back(std::move(v));
  }
  return suite;
}

/// A fake episode: metrics from the seed only; wall_s differs between invocations (like a real clock).
runner::EpisodeOutput fake_episode(const runner::EpisodeTask& task, int invocation) {
  Rng rng(task.seed ^ fnv1a64(task.variant->id));
  runner::EpisodeOutput out;
  out.record["duration_s"] = 600.0 + 1200.0 * rng.uniform();
  out.record["ended_by"] = "quit";
  out.record["simulated_s"] = 1000.0;
  out.record["wall_s"] = 0.001 * (invocation * 1000 + task.index);
  out.record["metrics"]["robot_item_moves_per_min"] = rng.normal(2.0, 0.5);
  out.record["metrics"]["label_share"]["purple"]["cooperative"] = rng.uniform();
  const auto id = results::RunFolder::episode_file_id(task.variant->id, task.index);
  out.files["events/" + id + ".jsonl"] = "{\"t\":0,\"event\":\"start\",\"seed\":" + std::to_string(task.seed) + "}\n";
  out.files["annotations/" + id + ".yaml"] = "episode: " + std::to_string(task.index) + "\n";
  out.simulated_s = 1000.0;
  return out;
}

/// Runs shard `index` of `count` (1-based in run.json, like `--shard I/N`) into `dir`, writing run.json.
void run_shard(const scenario::Suite& suite, const fs::path& dir, int index, int count, int invocation,
               const std::vector<std::string>& overrides = {}) {
  runner::RunOptions options;
  options.out = dir;
  options.progress = false;
  options.jobs = 2;
  options.shard_index = index;
  options.shard_count = count;
  std::atomic<bool> stop{false};
  runner::run_suite(
      suite, options, [&](const runner::EpisodeTask& t, const std::atomic<bool>&) { return fake_episode(t, invocation); },
      stop);
  nlohmann::json manifest;
  manifest["suite_file"] = "scenarios/tiny.yaml";
  manifest["suite"] = suite.name;
  manifest["overrides"] = overrides;
  manifest["shard"] = {index + 1, count};
  for (const auto& v : suite.variants) manifest["variants"].push_back({{"id", v.id}, {"episodes", v.scenario.episodes}});
  std::ofstream(dir / results::kRunManifestFile) << manifest.dump(2) << "\n";
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string without_wall_clock(const std::string& jsonl) {
  return std::regex_replace(jsonl, std::regex("\"wall_s\":[^,}]*,?"), "");
}

std::string merge_error(const std::vector<fs::path>& inputs, const fs::path& out,
                        const std::optional<results::ExpectedRun>& expected = std::nullopt) {
  const bool existed = fs::exists(out);
  try {
    merge_runs(inputs, out, expected);
  } catch (const InputError& e) {
    if (!existed) {
      EXPECT_FALSE(fs::exists(out)) << "a refused merge must not write its output";
    }
    return e.what();
  }
  return "(merged)";
}

class Merge : public ::testing::Test {
 protected:
  void SetUp() override {
    root = testing::fresh_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    suite = tiny_suite();
    runner::RunOptions whole_options;
    whole_options.out = root / "whole";
    whole_options.progress = false;
    std::atomic<bool> stop{false};
    runner::run_suite(
        suite, whole_options, [](const runner::EpisodeTask& t, const std::atomic<bool>&) { return fake_episode(t, 0); },
        stop);
    for (int i = 0; i < 3; ++i) run_shard(suite, shard(i), i, 3, i + 1);
  }
  fs::path shard(int i) const { return root / ("shard-" + std::to_string(i)); }

  fs::path root;
  scenario::Suite suite;
};

TEST_F(Merge, ShardsMergeIntoTheSingleMachineRun) {
  const auto report = merge_runs({shard(2), shard(0), shard(1)}, root / "merged");
  EXPECT_EQ(report.episodes, 18);
  EXPECT_EQ(report.inputs, 3);
  EXPECT_EQ(report.files, 36);
  const auto whole = read(root / "whole" / "episodes.jsonl");
  const auto merged = read(root / "merged" / "episodes.jsonl");
  EXPECT_NE(whole, merged);  // the wall-clock field differs…
  EXPECT_EQ(without_wall_clock(whole), without_wall_clock(merged));  // …and nothing else
  EXPECT_EQ(read(root / "whole" / "summary.csv"), read(root / "merged" / "summary.csv"));
  EXPECT_EQ(read(root / "whole" / "summary.md"), read(root / "merged" / "summary.md"));
  for (const auto& entry : fs::recursive_directory_iterator(root / "whole")) {
    if (!entry.is_regular_file() || entry.path().parent_path() == root / "whole") continue;
    const auto relative = fs::relative(entry.path(), root / "whole");
    EXPECT_EQ(read(entry.path()), read(root / "merged" / relative)) << relative;
  }
  const auto manifest = nlohmann::json::parse(read(root / "merged" / results::kRunManifestFile));
  EXPECT_EQ(manifest["shard"], nlohmann::json::array({1, 1}));
  EXPECT_EQ(manifest["merged_from"].size(), 3u);
}

TEST_F(Merge, ShardsAreBalancedAndDisjoint) {
  int total = 0;
  for (int i = 0; i < 3; ++i) {
    const int n = static_cast<int>(results::RunFolder(shard(i)).records().size());
    EXPECT_GE(n, 5);
    EXPECT_LE(n, 7);
    total += n;
  }
  EXPECT_EQ(total, 18);
}

TEST_F(Merge, RefusesMissingEpisodes) {
  const auto message = merge_error({shard(0), shard(2)}, root / "merged");
  EXPECT_NE(message.find("are missing"), std::string::npos) << message;
}

TEST_F(Merge, RefusesTheSameShardTwice) {
  fs::copy(shard(1), root / "copy", fs::copy_options::recursive);
  const auto message = merge_error({shard(0), shard(1), shard(2), root / "copy"}, root / "merged");
  EXPECT_NE(message.find("shard 2/3 is given twice"), std::string::npos) << message;
}

TEST_F(Merge, RefusesDuplicateEpisodes) {
  // The same episode in two folders whose run.json do not reveal it (a re-run into another folder).
  run_shard(suite, root / "rerun", 1, 3, 9);
  auto manifest = nlohmann::json::parse(read(root / "rerun" / results::kRunManifestFile));
  manifest.erase("shard");
  std::ofstream(root / "rerun" / results::kRunManifestFile) << manifest.dump();
  for (int i = 0; i < 3; ++i) {
    auto m = nlohmann::json::parse(read(shard(i) / results::kRunManifestFile));
    m.erase("shard");
    std::ofstream(shard(i) / results::kRunManifestFile) << m.dump();
  }
  const auto message = merge_error({shard(0), shard(1), shard(2), root / "rerun"}, root / "merged");
  EXPECT_NE(message.find("appear twice"), std::string::npos) << message;
}

TEST_F(Merge, RefusesDifferentOverrides) {
  run_shard(suite, root / "other", 1, 3, 4, {"protocol.freeplay_cap_s=60"});
  const auto message = merge_error({shard(0), root / "other", shard(2)}, root / "merged");
  EXPECT_NE(message.find("different overrides"), std::string::npos) << message;
}

TEST_F(Merge, RefusesConfigurationMismatch) {
  auto lines = read(shard(1) / "episodes.jsonl");
  lines = std::regex_replace(lines, std::regex("\"config_hash\":[0-9]+"), "\"config_hash\":12345",
                             std::regex_constants::format_first_only);  // one episode of another configuration
  std::ofstream(shard(1) / "episodes.jsonl", std::ios::binary) << lines;
  const auto message = merge_error({shard(0), shard(1), shard(2)}, root / "merged");
  EXPECT_NE(message.find("ran two configurations"), std::string::npos) << message;
  // Against the suite itself, the hash is checked directly.
  const auto against_suite = merge_error({shard(0), shard(1), shard(2)}, root / "merged", runner::expected_run(suite));
  EXPECT_NE(against_suite.find("the suite's is"), std::string::npos) << against_suite;
}

TEST_F(Merge, WithoutRunJsonTheSuiteIsNeeded) {
  for (int i = 0; i < 3; ++i) fs::remove(shard(i) / results::kRunManifestFile);
  const auto message = merge_error({shard(0), shard(1), shard(2)}, root / "merged");
  EXPECT_NE(message.find("--suite"), std::string::npos) << message;
  merge_runs({shard(0), shard(1), shard(2)}, root / "merged", runner::expected_run(suite));
  EXPECT_EQ(read(root / "whole" / "summary.csv"), read(root / "merged" / "summary.csv"));
  EXPECT_EQ(without_wall_clock(read(root / "whole" / "episodes.jsonl")),
            without_wall_clock(read(root / "merged" / "episodes.jsonl")));
}

TEST_F(Merge, RefusesANonEmptyOutputAndNonRunFolders) {
  fs::create_directories(root / "busy");
  std::ofstream(root / "busy" / "x") << "x";
  const auto busy = merge_error({shard(0), shard(1), shard(2)}, root / "busy");
  EXPECT_NE(busy.find("not empty"), std::string::npos) << busy;
  EXPECT_TRUE(fs::exists(root / "busy" / "x"));
  fs::create_directories(root / "empty-input");
  const auto not_run = merge_error({shard(0), root / "empty-input"}, root / "merged");
  EXPECT_NE(not_run.find("not a run folder"), std::string::npos) << not_run;
  // An existing empty output folder is fine.
  fs::create_directories(root / "ready");
  EXPECT_EQ(merge_runs({shard(0), shard(1), shard(2)}, root / "ready").episodes, 18);
}

}  // namespace
}  // namespace freeplay::analysis
