// Full episodes (sandtray, the real policies, planner, executor): the children's social engagement depends on how
// the partner answers, through the same mechanism for every robot policy (docs/agents.md, "Playing with someone").

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <optional>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/runner/event_coding.hpp"
#include "freeplay/runner/population.hpp"

using namespace freeplay;
using namespace freeplay::runner;
using namespace freeplay::scenario;

namespace {

/// The child-robot scenario with `policy`, short protocol stages and free play capped at 10 minutes.
Scenario child_robot(const std::string& policy) {
  const std::string text = fmt::format(
      "name: t\ncondition: child-robot\nseed: 99\nrobot: {{policy: {}}}\n"
      "protocol: {{greeting_s: 0, tutorial_s: 0, debriefing_s: 0, freeplay_cap_s: 600}}\n",
      policy);
  return scenario_from_document(parse_yaml(text, "test.yaml"));
}

/// Mean share of the purple child's coded associative + cooperative time over the same 8 children.
double joint_play_share(const std::string& policy) {
  const auto sessions = run_population(child_robot(policy), 8, 2, SharedModels::shipped());
  double share = 0.0;
  for (const auto& s : sessions) {
    const auto shares = agents::label_shares(s.purple.timeline, agents::Axis::SocialEngagement);
    share += shares[3] + shares[4];
  }
  return share / static_cast<double>(sessions.size());
}

}  // namespace

TEST(Partnership, ARobotThatNeverAnswersCannotHoldAChildInJointPlay) {
  EXPECT_LT(joint_play_share("idle"), 0.05);
  EXPECT_LT(joint_play_share("asocial"), 0.05);
}

TEST(Partnership, AResponsiveRobotSustainsJointPlay) {
  EXPECT_GT(joint_play_share("social"), 0.15);
}

TEST(Partnership, FullEpisodesCarryTheCodedGroundTruthAndTheChildrensStates) {
  const std::atomic<bool> stop{false};
  const auto cc = run_episode({.scenario = scenario_from_document(parse_yaml(
                                   "name: t\ncondition: child-child\nprotocol: {greeting_s: 0, tutorial_s: 0, "
                                   "debriefing_s: 0, freeplay_cap_s: 300}\n",
                                   "test.yaml")),
                               .seed = 3,
                               .stop = stop});
  ASSERT_EQ(cc.children.size(), 2u);
  const auto session = session_result(cc);
  ASSERT_TRUE(session.yellow.has_value());
  // The annotations a user receives are the coded timelines; the children's own states are kept beside them.
  EXPECT_EQ(agents::to_pinsoro_yaml({session.purple.timeline, session.yellow->timeline}),
            agents::to_pinsoro_yaml(cc.annotations));
  const double agreement = cc.record["children"]["purple"]["coder_agreement"].get<double>();
  EXPECT_GE(agreement, 0.0);
  EXPECT_LE(agreement, 1.0);
  EXPECT_DOUBLE_EQ(agreement, agents::timeline_agreement(session.purple.timeline, session.purple.internal,
                                                         agents::Axis::SocialEngagement, cc.duration_s));
}

// The coder works on any event log: coding a recorded log agrees with the live coding. The log lacks the fingers'
// paths (touches stay at their press points, the robot's finger at its move's target) and gaze points, so joint acts
// near the other's play are judged less exactly: the codings agree on most, not all, of the session.
TEST(EventCoding, ARecordedEventLogIsCodedAsTheLiveEpisodeWas) {
  const std::atomic<bool> stop{false};
  for (const char* condition : {"child-child", "child-robot"}) {
    const auto s = scenario_from_document(parse_yaml(
        fmt::format("name: t\ncondition: {}\nrobot: {{policy: social}}\nprotocol: {{greeting_s: 0, tutorial_s: 0, "
                    "debriefing_s: 0, freeplay_cap_s: 600}}\n",
                    condition),
        "test.yaml"));
    const auto episode = run_episode({.scenario = s, .seed = 21, .stop = stop});
    const auto coded = code_event_log(episode.events.events(), SharedModels::shipped().child_params->coder);
    ASSERT_TRUE(coded.purple.has_value());
    EXPECT_EQ(coded.yellow.has_value(), std::string(condition) == "child-child");
    EXPECT_GT(agents::timeline_agreement(*coded.purple, *episode.annotations.purple, agents::Axis::SocialEngagement,
                                         episode.duration_s),
              std::string(condition) == "child-child" ? 0.85 : 0.7)
        << condition << "\nlive:\n" << agents::to_pinsoro_yaml({*episode.annotations.purple, {}})
        << "log:\n" << agents::to_pinsoro_yaml({*coded.purple, {}});
  }
}

// A robot move's result from an older log (without today's fields) is read as events::Other: the coder must still
// see the robot's finger leave the screen, so the child beside it is coded as in a log with today's result.
TEST(EventCoding, AnOlderLogsMoveResultStillLiftsTheRobotsFinger) {
  using nlohmann::json;
  events::MoveResult today;
  today.item = "zebra";
  today.status = "succeeded";
  const json older = {{"item", "zebra"}, {"status", "succeeded"}};
  // The child keeps drawing for five minutes; the robot moves one item at the start.
  const auto log = [](const std::optional<events::EventPayload>& result) {
    std::vector<Event> events;
    events.emplace_back(0.0, "protocol", "stage", json{{"stage", "freeplay"}});
    events.emplace_back(1.0, "child.purple", "touch_down", json{{"finger", 1}, {"outcome", "stroke"}, {"x", 0.3}, {"y", -0.5}});
    events.emplace_back(10.0, "robot", "move_goal", json{{"item", "zebra"}, {"x", 0.5}, {"y", -0.1}});
    if (result) events.emplace_back(12.0, "robot", *result);
    events.emplace_back(299.0, "child.purple", "touch_up", json{{"finger", 1}});
    events.emplace_back(300.0, "protocol", "stage", json{{"stage", "debriefing"}});
    return events;
  };
  const auto& coder = SharedModels::shipped().child_params->coder;
  const auto with_today = log(today);
  const auto with_older = log(events::payload_of("move_result", older));
  ASSERT_NE(with_today[3].get<events::MoveResult>(), nullptr);
  ASSERT_NE(with_older[3].get<events::Other>(), nullptr);  // the older result is not read as a typed MoveResult
  const auto coded_today = code_event_log(with_today, coder);
  const auto coded_older = code_event_log(with_older, coder);
  const auto coded_never_lifted = code_event_log(log(std::nullopt), coder);
  ASSERT_TRUE(coded_today.purple && coded_older.purple && coded_never_lifted.purple);
  const auto social = agents::Axis::SocialEngagement;
  EXPECT_DOUBLE_EQ(agents::timeline_agreement(*coded_older.purple, *coded_today.purple, social, 300.0), 1.0);
  // The check can fail: a finger that never leaves keeps the robot playing beside the child all session.
  EXPECT_LT(agents::timeline_agreement(*coded_never_lifted.purple, *coded_today.purple, social, 300.0), 0.9);
}

TEST(EventCoding, MalformedLogsAreInputErrorsNamingTheLine) {
  const auto path = std::filesystem::temp_directory_path() / fmt::format("events-{}.jsonl", ::getpid());
  write_file_atomically(path, "{\"t\": 0, \"source\": \"protocol\", \"type\": \"stage\", \"data\": {}}\nnot json\n");
  try {
    (void)read_event_log(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":2:"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
  EXPECT_THROW((void)code_event_log({}, SharedModels::shipped().child_params->coder), InputError);
}
