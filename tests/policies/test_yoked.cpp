// The yoked policy on hand-written run folders: what it replays, when, and the errors for sources it cannot use.
// The replay of a real run (event logs compared) is in tests/runner/test_yoked_replay.cpp.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "freeplay/core/error.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/policies/yoked.hpp"

using namespace freeplay;
using namespace freeplay::policies;
namespace fs = std::filesystem;

namespace {

// One source episode: the greeting (not replayed), free play from t = 390, robot actions and outcomes, debriefing.
constexpr const char* kEpisodeLog = R"({"data":{"stage":"greeting"},"source":"protocol","t":0.0,"type":"stage"}
{"data":{"duration_s":3.0,"text":"Hello, I'm Nao.","to":""},"source":"robot","t":0.0,"type":"say"}
{"data":{"stage":"freeplay"},"source":"protocol","t":390.0,"type":"stage"}
{"data":{"item":"zebra"},"source":"child.purple","t":390.5,"type":"item_grabbed"}
{"data":{"child":"purple"},"source":"robot","t":391.0,"type":"look_at"}
{"data":{"duration_s":0.5,"text":"Wow!","to":"purple"},"source":"robot","t":392.5,"type":"say"}
{"data":{"item":"lion","x":0.25,"y":-0.2},"source":"robot","t":393.0,"type":"move_goal"}
{"data":{"item":"lion","status":"succeeded"},"source":"robot","t":396.0,"type":"move_result"}
{"data":{"item":"lion","x":0.25,"y":-0.2,"z":0.0},"source":"robot","t":397.0,"type":"look_at"}
{"data":{"x":0.1,"y":-0.3},"source":"robot","t":398.0,"type":"point_at"}
{"data":null,"source":"robot","t":399.0,"type":"cancel"}
{"data":{"stage":"debriefing"},"source":"protocol","t":500.0,"type":"stage"}
)";

/// A run folder with `episodes` finished episodes of each of `variants`, each with the same event log (or none).
fs::path make_source(const std::string& name, std::vector<std::string> variants, int episodes, bool events = true,
                     bool gz = false) {
  const auto dir = fs::path(::testing::TempDir()) / ("yoked-source-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir / "events");
  std::ofstream records(dir / "episodes.jsonl");
  for (const auto& v : variants) {
    for (int k = 0; k < episodes; ++k) {
      const auto id = fmt::format("{}-{:04d}", v, k);
      records << fmt::format(R"({{"variant":"{}","episode":{},"episode_id":"{}","duration_s":100}})", v, k, id)
              << "\n";
      if (events) std::ofstream(dir / "events" / (id + (gz ? ".jsonl.gz" : ".jsonl"))) << kEpisodeLog;
    }
  }
  return dir;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

YAML::Node params_from(const fs::path& dir, const std::string& extra = {}) {
  return YAML::Load(fmt::format("{{from: '{}'{}}}", dir.string(), extra));
}

}  // namespace

TEST(YokedPolicy, ReadsTheFreePlayRobotActionsWithFreePlayTimes) {
  const auto dir = make_source("read", {"social"}, 1);
  const auto actions = read_robot_actions(dir / "events" / "social-0000.jsonl");
  ASSERT_EQ(actions.size(), 6u);  // the greeting and move_result are left out
  const std::vector<double> times = {1.0, 2.5, 3.0, 7.0, 8.0, 9.0};
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_NEAR(actions[i].first, times[i], 1e-12) << i;
  EXPECT_EQ(std::get<LookAt>(actions[0].second).child, "purple");
  EXPECT_EQ(std::get<Say>(actions[1].second).text, "Wow!");
  EXPECT_EQ(std::get<Say>(actions[1].second).addressee, "purple");
  EXPECT_EQ(std::get<MoveItem>(actions[2].second).item, "lion");
  EXPECT_DOUBLE_EQ(std::get<MoveItem>(actions[2].second).target.y(), -0.2);
  EXPECT_DOUBLE_EQ(std::get<LookAt>(actions[3].second).point->x(), 0.25);
  EXPECT_DOUBLE_EQ(std::get<PointAt>(actions[4].second).point.y(), -0.3);
  EXPECT_TRUE(std::holds_alternative<CancelMove>(actions[5].second));
}

TEST(YokedPolicy, ReplaysEpisodeKAtTheRecordedTicksThenDoesNothing) {
  const auto dir = make_source("replay", {"social"}, 3);
  auto policy = make_policy("yoked", params_from(dir));
  PolicyContext context;
  context.episode_index = 2;
  policy->reset(context, Rng(1));
  Observation obs;
  std::vector<std::pair<double, std::size_t>> fired;
  for (long tick = 0; tick <= 3000; ++tick) {  // 300 s: far beyond the source's last action at 9 s
    obs.t = static_cast<double>(tick) * 0.1;
    for (const auto& a : policy->decide(obs)) fired.emplace_back(obs.t, a.index());
  }
  const std::vector<std::pair<double, std::size_t>> expected = {{1.0, 1}, {2.5, 3}, {3.0, 0},
                                                                {7.0, 1}, {8.0, 2}, {9.0, 5}};
  ASSERT_EQ(fired.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(fired[i].first, expected[i].first, 1e-9) << i;
    EXPECT_EQ(fired[i].second, expected[i].second) << i;
  }
  EXPECT_NO_THROW(policy->check_run(3));
}

TEST(YokedPolicy, EpisodeKReplaysAnotherChildsSessionUnlessTheOffsetIsZero) {
  const auto dir = make_source("offset", {"social"}, 3);
  std::ofstream(dir / "events" / "social-0001.jsonl")
      << R"({"data":{"stage":"freeplay"},"source":"protocol","t":10.0,"type":"stage"})" << "\n"
      << R"({"data":{"text":"Other!","to":""},"source":"robot","t":12.0,"type":"say"})" << "\n";
  const auto first_utterance = [&](const std::string& extra, int episode) {
    auto policy = make_policy("yoked", params_from(dir, extra));
    PolicyContext context;
    context.episode_index = episode;
    policy->reset(context, Rng(1));
    Observation obs;
    obs.t = 100.0;
    for (const auto& a : policy->decide(obs)) {
      if (const auto* say = std::get_if<Say>(&a)) return say->text;
    }
    return std::string("none");
  };
  EXPECT_EQ(first_utterance("", 0), "Other!");                       // default offset 1: source episode 1
  EXPECT_EQ(first_utterance("", 1), "Wow!");                         // source episode 2
  EXPECT_EQ(first_utterance("", 2), "Wow!");                         // wraps to source episode 0
  EXPECT_EQ(first_utterance(", episode_offset: 0", 1), "Other!");    // the same child's own session
  EXPECT_EQ(first_utterance(", episode_offset: 2", 2), "Other!");    // (2 + 2) mod 3 = 1
  const auto negative = error_of([&] { make_policy("yoked", params_from(dir, ", episode_offset: -1")); });
  EXPECT_NE(negative.find("episode_offset"), std::string::npos) << negative;
}

TEST(YokedPolicy, FewerSourceEpisodesFailBeforeTheRun) {
  const auto dir = make_source("fewer", {"social"}, 2);
  const auto policy = make_policy("yoked", params_from(dir));
  const auto message = error_of([&] { policy->check_run(5); });
  EXPECT_NE(message.find("robot.params.from"), std::string::npos) << message;
  EXPECT_NE(message.find("holds 2 episodes, this run has 5"), std::string::npos) << message;
  EXPECT_NE(message.find("at least 5 episodes"), std::string::npos) << message;
  // A gap in the source (an episode that did not finish) is named too.
  fs::remove(dir / "events" / "social-0001.jsonl");
  const auto gap = error_of([&] { policy->check_run(2); });
  EXPECT_NE(gap.find("social-0001.jsonl"), std::string::npos) << gap;
}

TEST(YokedPolicy, ASourceWithoutEventLogsNamesTheMissingFileAndTheFix) {
  const auto none = make_source("none", {"social"}, 2, false);
  const auto policy = make_policy("yoked", params_from(none));
  const auto message = error_of([&] { policy->check_run(2); });
  EXPECT_NE(message.find("social-0001.jsonl"), std::string::npos) << message;
  EXPECT_NE(message.find("--events all"), std::string::npos) << message;
  const auto gz = make_source("gz", {"social"}, 1, true, true);
  const auto gz_message = error_of([&] { make_policy("yoked", params_from(gz))->check_run(1); });
  EXPECT_NE(gz_message.find("gzip"), std::string::npos) << gz_message;
  EXPECT_NE(gz_message.find("gunzip"), std::string::npos) << gz_message;
}

TEST(YokedPolicy, ParametersAndVariantsAreChecked) {
  const auto missing = error_of([] { make_policy("yoked", YAML::Load("{}")); });
  EXPECT_NE(missing.find("from"), std::string::npos) << missing;
  const auto unknown_key = error_of([] { make_policy("yoked", YAML::Load("{from: x, form: y}")); });
  EXPECT_NE(unknown_key.find("form"), std::string::npos) << unknown_key;
  const auto not_a_run = error_of([] { make_policy("yoked", YAML::Load("{from: /nonexistent/run}")); });
  EXPECT_NE(not_a_run.find("not a run folder"), std::string::npos) << not_a_run;

  const auto dir = make_source("variants", {"social", "asocial"}, 1);
  const auto ambiguous = error_of([&] { make_policy("yoked", params_from(dir)); });
  EXPECT_NE(ambiguous.find("robot.params.variant"), std::string::npos) << ambiguous;
  EXPECT_NE(ambiguous.find("asocial, social"), std::string::npos) << ambiguous;
  const auto wrong = error_of([&] { make_policy("yoked", params_from(dir, ", variant: peer")); });
  EXPECT_NE(wrong.find("no variant 'peer'"), std::string::npos) << wrong;
  EXPECT_NO_THROW(make_policy("yoked", params_from(dir, ", variant: asocial"))->check_run(1));
}

TEST(YokedPolicy, AMalformedEventLogNamesFileAndLine) {
  const auto dir = make_source("malformed", {"social"}, 1);
  std::ofstream(dir / "events" / "social-0000.jsonl")
      << R"({"data":{"stage":"freeplay"},"source":"protocol","t":1.0,"type":"stage"})" << "\n"
      << R"({"data":{"text":"Wow!"},"source":"robot","t":)" << "\n";
  const auto message = error_of([&] { read_robot_actions(dir / "events" / "social-0000.jsonl"); });
  EXPECT_NE(message.find("social-0000.jsonl:2"), std::string::npos) << message;
}
