#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "freeplay/web/experiment.hpp"

using namespace freeplay::web;

namespace {

Command command(const std::string& body) { return parse_command(body, {"zebra"}); }

}  // namespace

TEST(WebExperiment, DemographicsMarkersAndLikertWriteExperimentYaml) {
  const auto dir = std::filesystem::temp_directory_path() / "freeplay-web-experiment";
  std::filesystem::create_directories(dir);
  const auto path = dir / "experiment.yaml";
  std::filesystem::remove(path);
  SessionLog log;
  ExperimentManager manager(path, freeplay::scenario::Condition::ChildChild, 1500000000, log);  // 2017-07-14 02:40 UTC
  manager.apply(command(R"({"type":"demographics","purple":{"age":7,"gender":"female","tablet_familiarity":"2"},
                            "yellow":{"age":6,"gender":"male","tablet_familiarity":"na"}})"),
                -10.0, 5.0);
  ASSERT_TRUE(std::filesystem::exists(path));
  try {
    manager.apply(command(R"({"type":"marker","kind":"issue"})"), -10.0, 5.0);
    FAIL() << "a marker before free play is refused";
  } catch (const CommandError& e) {
    EXPECT_EQ(e.status(), 409);
  }
  manager.freeplay_started(1500000100000000000ULL);
  manager.apply(command(R"({"type":"marker","kind":"interesting","text":"they share the zebra"})"), 12.5, 30.0);
  manager.apply(command(R"({"type":"likert","social_engagement":4})"), 100.0, 120.0);
  const auto yaml = YAML::LoadFile(path.string());
  EXPECT_EQ(yaml["condition"].as<std::string>(), "childchild");
  EXPECT_EQ(yaml["timestamp"].as<std::uint64_t>(), 1500000100000000000ULL);
  EXPECT_EQ(yaml["purple-participant"]["id"].as<std::string>(), "2017-07-14-02:40-p1");
  EXPECT_EQ(yaml["purple-participant"]["age"].as<int>(), 7);
  EXPECT_EQ(yaml["purple-participant"]["gender"].as<std::string>(), "female");
  EXPECT_EQ(yaml["purple-participant"]["details"]["tablet-familiarity"].as<std::string>(), "2");
  EXPECT_EQ(yaml["yellow-participant"]["details"]["tablet-familiarity"].as<std::string>(), "na");
  EXPECT_EQ(yaml["markers"]["12.5"].as<std::string>(), "interesting");
  EXPECT_EQ(yaml["notes"]["12.5"].as<std::string>(), "they share the zebra");
  EXPECT_EQ(yaml["extras"]["social-engagement"].as<int>(), 4);
  int experiment_events = 0;
  for (const auto& e : log.all()) experiment_events += e.source == "experiment" ? 1 : 0;
  EXPECT_EQ(experiment_events, 3);
  manager.apply(command(R"({"type":"finalise"})"), 100.0, 120.0);
  EXPECT_THROW(manager.apply(command(R"({"type":"likert","social_engagement":2})"), 100.0, 120.0), CommandError);
}

TEST(WebExperiment, TheConditionCommandSwitchesTheSessionsCondition) {
  SessionLog log;
  const auto path = std::filesystem::temp_directory_path() / "freeplay-web-experiment-switch.yaml";
  ExperimentManager manager(path, freeplay::scenario::Condition::ChildChild, 1500000000, log);
  EXPECT_EQ(manager.state()["condition"], "childchild");
  manager.apply(command(R"({"type":"condition","condition":"childrobot"})"), -1.0, 1.0);
  EXPECT_EQ(manager.state()["condition"], "childrobot");
  EXPECT_EQ(YAML::LoadFile(path.string())["condition"].as<std::string>(), "childrobot");
  // A child-robot session now: the yellow place is the robot's.
  EXPECT_THROW(manager.apply(command(R"({"type":"demographics","purple":{"age":7,"gender":"female","tablet_familiarity":"2"},
                                       "yellow":{"age":6,"gender":"male","tablet_familiarity":"na"}})"),
                             -1.0, 1.0),
               CommandError);
}

TEST(WebExperiment, ChildRobotSessionsHaveNoYellowChild) {
  SessionLog log;
  const auto path = std::filesystem::temp_directory_path() / "freeplay-web-experiment-cr.yaml";
  ExperimentManager manager(path, freeplay::scenario::Condition::ChildRobot, 1500000000, log);
  EXPECT_THROW(manager.apply(command(R"({"type":"demographics","purple":{"age":7,"gender":"female","tablet_familiarity":"2"},
                                       "yellow":{"age":6,"gender":"male","tablet_familiarity":"na"}})"),
                             -1.0, 1.0),
               CommandError);
  manager.apply(command(R"({"type":"demographics","purple":{"age":5,"gender":"male","tablet_familiarity":"0"}})"), -1.0, 1.0);
  EXPECT_EQ(YAML::LoadFile(path.string())["purple-participant"]["id"].as<std::string>(), "2017-07-14-02:40-p2");
}
