#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "freeplay/core/error.hpp"
#include "freeplay/recording/bag_recorder.hpp"
#include "freeplay/recording/child_replay.hpp"
#include "freeplay/recording/publishers.hpp"
#include "freeplay/recording/replay.hpp"
#include "freeplay/recording/robot_links.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/stage/nao_description.hpp"
#include "freeplay/stage/stage_state.hpp"

using namespace freeplay;
using namespace freeplay::recording;

namespace {

const runner::SharedModels& models() { return runner::SharedModels::shipped(); }

scenario::Scenario short_session(const std::string& condition) {
  return scenario::scenario_from_document(parse_yaml(
      fmt::format("name: replayed\ncondition: {}\nrecord: true\n"
                  "protocol: {{greeting_s: 1, tutorial_s: 1, freeplay_cap_s: 40, debriefing_s: 1}}\n",
                  condition),
      "replayed.yaml"));
}

struct Session {
  std::filesystem::path dir;
  runner::EpisodeResult result;
};

Session record(const std::string& condition, std::uint64_t seed) {
  const auto root = std::filesystem::temp_directory_path() / ("freeplay-child-replay-" + condition + "-" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::remove_all(root);
  const auto scenario = short_session(condition);
  runner::EpisodeObservers observers;
  observers.push_back(std::make_unique<BagRecorder>(root / "sessions", scenario.recording));
  const std::atomic<bool> stop{false};
  Session s;
  s.result =
      runner::run_episode({.scenario = scenario, .seed = seed, .models = models(), .stop = stop, .id = "replayed-0000"},
                          runner::observed_by(observers));
  s.dir = root / "sessions" / "replayed-0000";
  return s;
}

const Session& child_robot() {
  static const Session s = record("child-robot", 11);
  return s;
}

// The children's touch events: time, who, what, finger and point (the outcome depends on the robot).
std::vector<std::string> child_touches(const EventLog& log) {
  std::vector<std::string> out;
  for (const auto& e : log.events()) {
    if (e.source.rfind("child.", 0) != 0) continue;
    if (e.type() != "touch_down" && e.type() != "touch_up" && e.type() != "touch_missed") continue;
    out.push_back(fmt::format("{:.6f} {} {} {} {} {}", e.t, e.source, e.type(), e.data().value("finger", 0),
                              e.data().value("x", 0.0), e.data().value("y", 0.0)));
  }
  return out;
}

int count_events(const EventLog& log, const std::string& source, const std::string& type) {
  int n = 0;
  for (const auto& e : log.events()) n += e.source == source && e.type() == type ? 1 : 0;
  return n;
}

}  // namespace

TEST(ChildReplay, SamePolicyReproducesTheChildrensTouchesExactly) {
  const auto& s = child_robot();
  ASSERT_FALSE(s.result.aborted);
  const auto recorded = read_recorded_children(s.dir);
  EXPECT_EQ(recorded.episode_id, "replayed-0000");
  EXPECT_EQ(recorded.seed, 11U);
  EXPECT_DOUBLE_EQ(recorded.freeplay_duration_s, s.result.duration_s);
  const auto original = child_touches(s.result.events);
  ASSERT_GT(original.size(), 4U) << "the session needs touches to be a meaningful test";
  const auto scenario = replay_scenario(recorded, "");
  EXPECT_EQ(scenario.robot.policy, "asocial");
  const auto replay = replay_children(recorded, scenario, models());
  ASSERT_FALSE(replay.aborted);
  EXPECT_EQ(child_touches(replay.events), original);
  EXPECT_DOUBLE_EQ(replay.duration_s, s.result.duration_s);
  EXPECT_EQ(replay.record.value("ended_by", ""), s.result.record.value("ended_by", ""));
  // A valid episode: the record's metrics, the children's touch rate as recorded, no annotations.
  const auto& m = replay.record.at("metrics");
  EXPECT_DOUBLE_EQ(m.at("child").at("purple").at("touches_per_min").get<double>(),
                   s.result.record.at("metrics").at("child").at("purple").at("touches_per_min").get<double>());
  EXPECT_FALSE(m.contains("label_share"));
  EXPECT_FALSE(replay.annotations.purple.has_value());
  EXPECT_EQ(count_events(replay.events, "protocol", "freeplay_ended"), 1);
  // Same policy, same seed, same children: the robot plays as it did.
  EXPECT_EQ(count_events(replay.events, "robot", "move_goal"), count_events(s.result.events, "robot", "move_goal"));
}

TEST(ChildReplay, IdlePolicyMakesNoMovesWhileTheChildrensTouchesStayTheSame) {
  const auto& s = child_robot();
  ASSERT_GT(count_events(s.result.events, "robot", "move_goal"), 0) << "the recorded robot should have moved";
  const auto recorded = read_recorded_children(s.dir);
  const auto scenario = replay_scenario(recorded, "idle");
  EXPECT_EQ(scenario.robot.policy, "idle");
  const auto replay = replay_children(recorded, scenario, models());
  EXPECT_EQ(count_events(replay.events, "robot", "move_goal"), 0);
  EXPECT_EQ(replay.record.at("metrics").at("robot_actions").at("move").get<int>(), 0);
  EXPECT_EQ(child_touches(replay.events), child_touches(s.result.events));
}

TEST(ChildReplay, ChildChildSessionsReplayBothChildren) {
  const auto s = record("child-child", 5);
  const auto recorded = read_recorded_children(s.dir);
  EXPECT_EQ(recorded.seats, (std::vector<std::string>{"purple", "yellow"}));
  const auto replay = replay_children(recorded, replay_scenario(recorded, ""), models());
  EXPECT_EQ(child_touches(replay.events), child_touches(s.result.events));
  EXPECT_THROW(replay_scenario(recorded, "idle"), InputError);  // no robot to give a policy
}

TEST(ChildReplay, BadSessionFoldersGiveClearErrors) {
  const auto empty = std::filesystem::temp_directory_path() / ("freeplay-child-replay-empty-" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::remove_all(empty);
  std::filesystem::create_directories(empty);
  try {
    read_recorded_children(empty);
    FAIL() << "no error for a folder without a bag";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no freeplay.bag"), std::string::npos) << e.what();
  }
  {  // a bag from an older recorder: no /freeplay/scenario
    rosbag::Bag bag;
    bag.open((empty / "freeplay.bag").string(), rosbag::bagmode::Write);
    msg::String text;
    text.data = ros_string("{}");
    bag.write(topics::kAnnotations, ros_time(1.0), text);
    bag.close();
  }
  try {
    read_recorded_children(empty);
    FAIL() << "no error for a bag without the scenario";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/freeplay/scenario"), std::string::npos) << e.what();
  }
  std::filesystem::remove(empty / "freeplay.bag");
  std::ofstream(empty / "freeplay.bag") << "not a bag";
  EXPECT_THROW(read_recorded_children(empty), InputError);
}

TEST(RobotLinks, LinkFramesEqualTheStageBodiesForTheRecordedJoints) {
  const auto& s = child_robot();
  Bag bag;
  open_session_bag(s.dir, bag);
  // A joint state while the arm streams a move (the tick of the last /poses message) and the Nao's links of that
  // tick (each publisher sends it at its own phase after the tick).
  ros::Time last_pose;
  for (const auto& m : rosbag::View(bag.get(), rosbag::TopicQuery(topics::kPoses))) last_pose = m.getTime();
  ASSERT_FALSE(last_pose.isZero()) << "the recorded robot should have moved an item";
  const double tick_t = tick_time(publication_tick(sandtray_time(last_pose)));
  const ros::Time stamp = ros_time(tick_t);
  const ros::Time until = ros_time(tick_t + kMaxPublishDelayS);
  std::vector<std::string> names;
  std::vector<double> positions;
  for (const auto& m : rosbag::View(bag.get(), rosbag::TopicQuery(topics::kJointStates), stamp, until)) {
    const auto js = m.instantiate<msg::JointState>();
    for (const auto& n : js->name) names.push_back(std_string(n));
    positions.assign(js->position.begin(), js->position.end());
  }
  ASSERT_EQ(names.size(), 26U);
  std::map<std::string, std::pair<std::string, Eigen::Isometry3d>> links;  // child → (parent, parent_T_child)
  for (const auto& m : rosbag::View(bag.get(), rosbag::TopicQuery(topics::kTf), stamp, until)) {
    const auto tf = m.instantiate<msg::TFMessage>();  // keeps the message alive
      for (const auto& x : tf->transforms) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.translation() << x.transform.translation.x, x.transform.translation.y, x.transform.translation.z;
      T.linear() = Eigen::Quaterniond(x.transform.rotation.w, x.transform.rotation.x, x.transform.rotation.y,
                                      x.transform.rotation.z)
                       .toRotationMatrix();
      links[std_string(x.child_frame_id)] = {std_string(x.header.frame_id), T};
    }
  }
  for (const char* name : {"base_link", "torso", "Head", "RShoulder", "RElbow", "r_wrist", "r_gripper"}) {
    ASSERT_TRUE(links.contains(name)) << name;
  }
  EXPECT_EQ(links.at("base_link").first, "sandtray");
  EXPECT_EQ(links.at("Head").first, "Neck");
  EXPECT_EQ(links.at("r_gripper").first, "r_wrist");
  // An independent stage with the recorded joint angles.
  stage::StageConfig config;
  config.scene = stage::SceneKind::child_robot;
  stage::Stage stage(stage::StageModel::create(config), stage::StageMode::kinematic);
  for (std::size_t i = 0; i < names.size(); ++i) {
    stage::set_qpos(stage, stage.model().nao().qpos[static_cast<std::size_t>(stage::nao_joint_index(names[i]))], positions[i]);
  }
  stage.update_kinematics();
  for (const char* name : {"torso", "Head", "RShoulder", "RElbow", "r_wrist", "r_gripper"}) {
    Eigen::Isometry3d sandtray_T_link = Eigen::Isometry3d::Identity();
    for (std::string frame = name; frame != "sandtray";) {
      ASSERT_TRUE(links.contains(frame)) << frame;
      sandtray_T_link = links.at(frame).second * sandtray_T_link;
      frame = links.at(frame).first;
    }
    const int body = stage::body_id(stage.model(), name);
    ASSERT_GE(body, 0) << name;
    const Eigen::Vector3d expected = stage::body_pose(stage, body).translation();
    EXPECT_LT((sandtray_T_link.translation() - expected).norm(), 1e-9) << name;
  }
  // The arm moved during the session: the recorded gripper is not where StandInit puts it.
  NaoLinkFrames rest;
  rest.compute({}, {});
  const int gripper = stage::body_id(rest.stage().model(), "r_gripper");
  const Eigen::Vector3d at_rest = stage::body_pose(rest.stage(), gripper).translation();
  const int body = stage::body_id(stage.model(), "r_gripper");
  EXPECT_GT((stage::body_pose(stage, body).translation() - at_rest).norm(), 1e-6);
  // The links are not items for the metric recomputation.
  const auto session = read_session(s.dir);
  for (const auto& [t, items] : session.item_positions) {
    EXPECT_FALSE(items.contains("Head"));
    EXPECT_FALSE(items.contains("torso"));
  }
  EXPECT_TRUE(NaoLinkFrames().compute({"HeadYaw"}, {0.1}).size() > 20U);
  EXPECT_THROW(NaoLinkFrames().compute({"Tail"}, {0.0}), InputError);
}
