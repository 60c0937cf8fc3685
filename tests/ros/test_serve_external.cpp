// `freeplay serve --robot external` on a live graph: a goal sent through actionlib to `move_sandbox_items` is driven
// by the episode's one robot side, so the event log holds its robot move events as an in-process episode's, and the
// action's feedback and result come from that driver. A real rosmaster on a free loopback port is started and stopped
// here (skipped only when it cannot start, as the other live checks).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>

#include "freeplay/ros/serve.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "goal_client.hpp"

using namespace freeplay;

namespace {

int free_port() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  socklen_t len = sizeof addr;
  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  close(fd);
  return ntohs(addr.sin_port);
}

bool accepts(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  const bool ok = connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
  close(fd);
  return ok;
}

/// A rosmaster of our own on a free loopback port, with this process's ROS environment pointing at it.
class Master {
 public:
  Master() {
    dir_ = std::filesystem::temp_directory_path() / ("freeplay-ros-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir_);
    port_ = free_port();
    setenv("ROS_MASTER_URI", ("http://127.0.0.1:" + std::to_string(port_) + "/").c_str(), 1);
    setenv("ROS_IP", "127.0.0.1", 1);
    unsetenv("ROS_HOSTNAME");
    setenv("ROS_HOME", dir_.c_str(), 1);
    setenv("ROS_LOG_DIR", dir_.c_str(), 1);
    if (access("/usr/bin/rosmaster", X_OK) != 0) return;
    pid_ = fork();
    if (pid_ == 0) {
      setsid();
      const auto log = (dir_ / "rosmaster.log").string();
      (void)!freopen(log.c_str(), "w", stdout);
      (void)!freopen(log.c_str(), "a", stderr);
      const auto port = std::to_string(port_);
      execl("/usr/bin/rosmaster", "rosmaster", "--core", "-p", port.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(15);
    while (std::chrono::steady_clock::now() < deadline && waitpid(pid_, nullptr, WNOHANG) == 0) {
      if (accepts(port_)) {
        up_ = true;
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  ~Master() {
    if (pid_ > 0) {
      kill(-pid_, SIGINT);
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(8);
      while (waitpid(pid_, nullptr, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
          kill(-pid_, SIGKILL);
          waitpid(pid_, nullptr, 0);
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    }
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  /// True once the master answers.
  bool up() const { return up_; }

 private:
  std::filesystem::path dir_;
  int port_ = 0;
  pid_t pid_ = -1;
  bool up_ = false;
};

// At the first free-play tick, picks the item nearest the robot's shoulder and a target 4 cm towards it (in reach).
class PickGoal final : public runner::EpisodeObserver {
 public:
  explicit PickGoal(Vec2 reach_centre) : centre_(reach_centre) {}
  void observe(const runner::EpisodeSnapshot& s) override {
    if (s.stage != "freeplay" || picked_) return;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& item : s.tray->items()) {
      const double d = (item.pose.position() - centre_).norm();
      if (d < best) {
        best = d;
        item_ = item.name;
        target_ = item.pose.position() + 0.04 * (centre_ - item.pose.position()).normalized();
      }
    }
    std::lock_guard lock(mutex_);
    picked_ = true;
    changed_.notify_all();
  }
  /// Waits (at most `seconds`) for free play; the item and its target, or nothing.
  std::optional<std::pair<std::string, Vec2>> wait(double seconds) {
    std::unique_lock lock(mutex_);
    if (!changed_.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return picked_.load(); })) return {};
    return std::make_pair(item_, target_);
  }

 private:
  Vec2 centre_;
  std::atomic<bool> picked_{false};
  std::string item_;
  Vec2 target_ = Vec2::Zero();
  std::mutex mutex_;
  std::condition_variable changed_;
};

}  // namespace

TEST(ServeExternal, AnActionlibGoalIsDrivenByTheOneRobotSideWithItsMoveEventsFeedbackAndResult) {
  Master master;
  if (!master.up()) GTEST_SKIP() << "rosmaster cannot start (install python3-rosmaster: scripts/setup.sh)";
  const auto scenario = scenario::scenario_from_document(parse_yaml(
      "name: external\ncondition: child-robot\n"
      "protocol: {greeting_s: 1, tutorial_s: 1, freeplay_cap_s: 20, debriefing_s: 1}\n",
      "external.yaml"));
  ros_live::ServeOptions options;
  options.rate = 2.0;
  options.external_robot = true;
  options.node_name = "sandtray_test";
  ros_live::GraphSide side(scenario, 17, options);
  const auto reach =
      runner::SharedModels::shipped().robot_body(scenario.robot.mode, scenario.robot.arm_reach_m)->reach();
  PickGoal pick(reach.centre);
  runner::LiveEpisode live(options.rate);
  live.attach(side.publisher());
  live.attach(pick);
  runner::EpisodeResult result;
  std::thread episode([&] { result = live.run(side.inputs(scenario, 17)); });
  const auto goal = pick.wait(30.0);
  std::optional<ros_test::GoalOutcome> sent;
  if (goal) sent = ros_test::send_move_goal(goal->first, goal->second.x(), goal->second.y(), 20.0);
  episode.join();
  ros_test::shutdown_ros();
  ASSERT_TRUE(goal.has_value()) << "free play did not start";
  ASSERT_TRUE(sent->server) << "no move_sandbox_items server";
  ASSERT_TRUE(sent->finished) << "no result for the goal";
  ASSERT_FALSE(result.aborted);
  // The robot's move events, as an in-process episode writes them.
  std::vector<const Event*> goals;
  std::vector<const Event*> results;
  for (const auto& e : result.events.events()) {
    if (e.source == "robot" && e.type() == "move_goal") goals.push_back(&e);
    if (e.source == "robot" && e.type() == "move_result") results.push_back(&e);
  }
  ASSERT_EQ(goals.size(), 1u);
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(goals[0]->data()["item"], goal->first);
  EXPECT_NEAR(goals[0]->data()["x"].get<double>(), goal->second.x(), 1e-9);
  EXPECT_NEAR(goals[0]->data()["y"].get<double>(), goal->second.y(), 1e-9);
  EXPECT_EQ(results[0]->data()["item"], goal->first);
  // The action's result and feedback are the driver's.
  const auto status = results[0]->data()["status"].get<std::string>();
  const std::string state = status == "succeeded" ? "SUCCEEDED" : status == "preempted" ? "PREEMPTED" : "ABORTED";
  EXPECT_EQ(sent->state, state) << sent->text;
  EXPECT_EQ(status, "succeeded") << sent->text;  // a short drag inside the reach, as in-process episodes make them
  const auto poses = results[0]->data()["poses"].get<int>();
  ASSERT_GT(poses, 1);
  ASSERT_FALSE(sent->feedback.empty());
  EXPECT_TRUE(std::is_sorted(sent->feedback.begin(), sent->feedback.end()));
  EXPECT_GT(sent->feedback.back(), 50);
}
