#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <set>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "freeplay/results/run_folder.hpp"
#include "../scratch_dir.hpp"

using namespace freeplay;
using namespace freeplay::runner;
using namespace freeplay::scenario;

namespace {

/// A scratch folder for this file's test `name`.
std::filesystem::path fresh_dir(const std::string& name) { return test_support::fresh_dir("suite_runner-" + name); }

Suite two_variant_suite(const std::filesystem::path& dir) {
  write_file_atomically(dir / "cc.yaml", "name: cc\ncondition: child-child\nepisodes: 7\nseed: 3\n");
  write_file_atomically(dir / "cr.yaml", "name: cr\ncondition: child-robot\nepisodes: 5\nseed: 3\n");
  write_file_atomically(dir / "s.yaml", "suite: s\nscenarios:\n  - scenario: cc.yaml\n  - scenario: cr.yaml\n");
  return load_suite(dir / "s.yaml");
}

// A fake episode: its "duration" is a pure function of the seed.
EpisodeOutput fake_episode(const EpisodeTask& task, const std::atomic<bool>& /*stop*/) {
  EpisodeOutput out;
  Rng rng(task.seed);
  out.record["duration_s"] = rng.uniform(60, 2400);
  out.record["metrics"] = nlohmann::json{{"x", rng.uniform()}};
  out.files["events/" + results::RunFolder::episode_file_id(task.variant->id, task.index) + ".jsonl"] = "{}\n";
  out.simulated_s = 100;
  return out;
}

RunOptions options(int jobs, const std::filesystem::path& out) {
  RunOptions o;
  o.jobs = jobs;
  o.out = out;
  o.progress = false;
  return o;
}

std::string episodes_of(const std::filesystem::path& dir) {
  auto text = read_file(dir / "episodes.jsonl");
  // program_version is the same for both runs of one binary; nothing else varies.
  return text;
}

}  // namespace

TEST(SuiteRunner, OneAndTwoJobsGiveIdenticalResults) {
  const auto dir = fresh_dir("runner_jobs");
  const auto suite = two_variant_suite(dir);
  std::atomic<bool> stop{false};
  const auto one = options(1, dir / "one");
  const auto two = options(2, dir / "two");
  const auto r1 = run_suite(suite, one, fake_episode, stop);
  const auto r2 = run_suite(suite, two, fake_episode, stop);
  EXPECT_EQ(r1.finished, 12);
  EXPECT_EQ(r2.finished, 12);
  EXPECT_EQ(episodes_of(dir / "one"), episodes_of(dir / "two"));
  EXPECT_EQ(read_file(dir / "one" / "summary.csv"), read_file(dir / "two" / "summary.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "one" / "events" / "cc-0006.jsonl"));
  EXPECT_TRUE(std::filesystem::exists(dir / "one" / "summary.md"));
}

TEST(SuiteRunner, InterruptedRunKeepsFinishedEpisodesAndResumes) {
  const auto dir = fresh_dir("runner_resume");
  const auto suite = two_variant_suite(dir);
  std::atomic<bool> stop{false};
  int calls = 0;
  auto interrupting = [&](const EpisodeTask& task, const std::atomic<bool>& s) {
    if (++calls == 5) stop.store(true);  // Ctrl-C while the 5th episode runs: it is discarded
    if (s.load()) return EpisodeOutput{};
    return fake_episode(task, s);
  };
  const auto first = run_suite(suite, options(1, dir / "run"), interrupting, stop);
  EXPECT_TRUE(first.interrupted);
  EXPECT_EQ(first.finished, 4);
  EXPECT_NE(read_file(dir / "run" / "summary.md").find("| cc |"), std::string::npos);  // summary of the 4
  stop.store(false);
  int resumed_calls = 0;
  auto counting = [&](const EpisodeTask& task, const std::atomic<bool>& s) {
    ++resumed_calls;
    return fake_episode(task, s);
  };
  const auto second = run_suite(suite, options(1, dir / "run"), counting, stop);
  EXPECT_EQ(second.skipped, 4);
  EXPECT_EQ(resumed_calls, 8);
  run_suite(suite, options(1, dir / "whole"), fake_episode, stop);
  EXPECT_EQ(episodes_of(dir / "run"), episodes_of(dir / "whole"));
}

TEST(SuiteRunner, ShardsAreDisjointBalancedAndCoverTheSuite) {
  std::set<std::pair<std::string, int>> seen;
  for (int shard = 0; shard < 3; ++shard) {
    int count = 0;
    for (const char* variant : {"cc", "cr[x=1]"}) {
      for (int i = 0; i < 30; ++i) {
        if (!in_shard(variant, i, shard, 3)) continue;
        EXPECT_TRUE(seen.insert({variant, i}).second);
        ++count;
      }
    }
    EXPECT_EQ(count, 20);
  }
  EXPECT_EQ(seen.size(), 60u);
}

TEST(SuiteRunner, EpisodeSeedsDependOnScenarioSeedAndIndexOnly) {
  EXPECT_EQ(episode_seed(3, 5), episode_seed(3, 5));
  EXPECT_NE(episode_seed(3, 5), episode_seed(3, 6));
  EXPECT_NE(episode_seed(3, 5), episode_seed(4, 5));
}

// --events: all writes the logs, gz writes them gzip-compressed (same bytes once unpacked), none writes none, and
// auto keeps them for a run this small.
TEST(SuiteRunner, EventsOutputKeepsCompressesOrDropsTheEventLogs) {
  const auto dir = fresh_dir("runner_events");
  const auto suite = two_variant_suite(dir);
  std::atomic<bool> stop{false};
  const auto run = [&](EventsOutput events, const std::string& name) {
    auto o = options(1, dir / name);
    o.events = events;
    run_suite(suite, o, fake_episode, stop);
    return dir / name;
  };
  EXPECT_EQ(read_file(run(EventsOutput::All, "all") / "events/cc-0003.jsonl"), "{}\n");
  EXPECT_TRUE(std::filesystem::exists(run(EventsOutput::Auto, "auto") / "events/cr-0004.jsonl"));
  const auto gz = run(EventsOutput::Gz, "gz");
  EXPECT_FALSE(std::filesystem::exists(gz / "events/cc-0003.jsonl"));
  const auto unpacked = dir / "unpacked.jsonl";
  ASSERT_EQ(std::system(("gzip -dc " + (gz / "events/cc-0003.jsonl.gz").string() + " > " + unpacked.string()).c_str()), 0);
  EXPECT_EQ(read_file(unpacked), "{}\n");
  const auto none = run(EventsOutput::None, "none");
  EXPECT_FALSE(std::filesystem::exists(none / "events"));
  EXPECT_EQ(episodes_of(none), episodes_of(dir / "all"));  // the records do not depend on the event logs
  EXPECT_EQ(events_output_from_name("gz"), EventsOutput::Gz);
  EXPECT_THROW(events_output_from_name("zip"), InputError);
}

// The run folder streams its records from disk: the visitor sees what records() returns, in file order.
TEST(SuiteRunner, RunFolderStreamsItsRecords) {
  const auto dir = fresh_dir("runner_stream");
  const auto suite = two_variant_suite(dir);
  std::atomic<bool> stop{false};
  run_suite(suite, options(2, dir / "run"), fake_episode, stop);
  const results::RunFolder folder(dir / "run");
  std::vector<nlohmann::json> seen;
  folder.for_each_record([&](const nlohmann::json& r) { seen.push_back(r); });
  EXPECT_EQ(folder.record_count(), 12u);
  EXPECT_EQ(seen, folder.records());
  EXPECT_EQ(seen.front()["variant"], "cc");
  EXPECT_EQ(seen.front()["episode"], 0);
  EXPECT_EQ(seen.back()["variant"], "cr");
  EXPECT_EQ(seen.back()["episode"], 4);
}
