// `freeplay serve SCENARIO` (the simulated sandtray on a live ROS 1 graph) and `freeplay robot --policy NAME` (a
// policy driving a ROS sandtray). See docs/hardware.md.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <iostream>

#include "command_registry.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/planning/planner_settings.hpp"
#include "serve_web.hpp"

#ifdef FREEPLAY_WITH_ROS
#include "freeplay/ros/robot_node.hpp"
#include "freeplay/ros/serve.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "vocabulary.hpp"
#endif

namespace freeplay::cli {
namespace {

std::atomic<bool> g_ros_stop{false};

extern "C" void on_ros_interrupt(int /*signal*/) {
  if (g_ros_stop.exchange(true)) std::_Exit(130);  // a second Ctrl-C quits at once
}

#ifdef FREEPLAY_WITH_ROS
// Servers bind to loopback by default: without ROS_IP / ROS_HOSTNAME our nodes advertise (and roscpp binds)
// 127.0.0.1 only; set ROS_IP to the machine's address to reach the lab's graph.
void default_to_loopback() {
  if (std::getenv("ROS_IP") == nullptr && std::getenv("ROS_HOSTNAME") == nullptr) setenv("ROS_IP", "127.0.0.1", 1);
}
#endif

#ifndef FREEPLAY_WITH_ROS
[[noreturn]] void no_ros() {
  throw InputError("this freeplay was built without ROS 1 (roscpp, actionlib, gencpp)", "serve/robot",
                   "install them with scripts/setup.sh and rebuild");
}
#endif

struct ServeCommandOptions {
  std::string file;
  std::vector<std::string> overrides;
  std::optional<std::uint64_t> seed;
  double rate = 1.0;
  std::string robot = "sim";
  double master_timeout_s = 10.0;
  WebCliOptions web;
};

void serve_command(const ServeCommandOptions& o) {
  if (!o.web.listen.empty()) {  // the web page needs no ROS master
    if (o.robot == "external") {
      throw InputError("--web drives the robot from the page: it cannot take --robot external", "--robot", "sim");
    }
    std::signal(SIGINT, on_ros_interrupt);
    std::signal(SIGTERM, on_ros_interrupt);
    auto web = o.web;
    web.master_timeout_s = o.master_timeout_s;
    run_web_serve(o.file, o.overrides, o.seed, o.rate, web, g_ros_stop);
    return;
  }
#ifdef FREEPLAY_WITH_ROS
  auto scenario = scenario::load_scenario(o.file, o.overrides, scenario_vocabulary());
  if (o.robot == "external" && scenario.condition != scenario::Condition::ChildRobot) {
    throw InputError(fmt::format("{}: --robot external needs a child-robot scenario (condition is '{}')", o.file,
                                 scenario::to_string(scenario.condition)),
                     "--robot", "sim, or a scenario with condition: child-robot");
  }
  ros_live::ServeOptions options;
  options.rate = o.rate;
  options.external_robot = o.robot == "external";
  options.master_timeout_s = o.master_timeout_s;
  default_to_loopback();
  const auto seed = runner::episode_seed(o.seed.value_or(scenario.seed), 0);
  std::signal(SIGINT, on_ros_interrupt);
  std::signal(SIGTERM, on_ros_interrupt);
  spdlog::info("serving '{}' (seed {}, rate {}×, robot {}) on the ROS graph", scenario.name, seed, o.rate, o.robot);
  runner::PacingTiming timing;
  runner::EpisodeResult result;
  try {
    result = ros_live::serve(scenario, seed, options, g_ros_stop, &timing);
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const InputError*>(&e) != nullptr) throw;
    std::cerr << "error: " << e.what() << "\n";
    fail_with(1);
  }
  nlohmann::json summary{{"aborted", result.aborted},
                         {"duration_s", result.duration_s},
                         {"simulated_s", result.simulated_s},
                         {"timing", runner::timing_json(timing)}};
  if (!result.aborted) {
    summary["ended_by"] = result.record["ended_by"];
    summary["metrics"] = result.record["metrics"];
  }
  std::cout << summary.dump() << std::endl;
  if (result.aborted) fail_with(130);
#else
  (void)o;
  no_ros();
#endif
}

struct RobotCommandOptions {
  std::string policy = "asocial";
  std::string planner = planning::PlannerSettings{}.name;
  std::uint64_t seed = 1;
  double duration_s = 0.0;
  double master_timeout_s = 10.0;
};

void robot_command(const RobotCommandOptions& o) {
#ifdef FREEPLAY_WITH_ROS
  ros_live::RobotNodeOptions options;
  options.policy = o.policy;
  options.planner = o.planner;
  options.seed = o.seed;
  options.duration_s = o.duration_s;
  options.master_timeout_s = o.master_timeout_s;
  default_to_loopback();
  std::signal(SIGINT, on_ros_interrupt);
  std::signal(SIGTERM, on_ros_interrupt);
  ros_live::RobotNodeStats stats;
  try {
    stats = ros_live::run_robot_node(options, g_ros_stop);
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const InputError*>(&e) != nullptr) throw;
    std::cerr << "error: " << e.what() << "\n";
    fail_with(1);
  }
  std::cout << nlohmann::json{{"decisions", stats.decisions},
                              {"moves_started", stats.moves_started},
                              {"moves_succeeded", stats.moves_succeeded},
                              {"moves_failed", stats.moves_failed},
                              {"poses_sent", stats.poses_sent}}
                   .dump()
            << std::endl;
#else
  (void)o;
  no_ros();
#endif
}

const RegisterCommand kServe(60, [](CLI::App& program) {
  auto o = std::make_shared<ServeCommandOptions>();
  auto* cmd = program.add_subcommand(
      "serve", "Run one live episode on a ROS 1 graph with the real game and core interface (ROS_MASTER_URI)");
  cmd->add_option("scenario", o->file, "Scenario file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--set", o->overrides, "Override a scenario value, KEY.PATH=VALUE (repeatable)");
  cmd->add_option("--seed", o->seed, "Root seed (default: the scenario's)");
  cmd->add_option("--rate", o->rate, "Simulated seconds per wall second; other than 1 publishes /clock")
      ->check(CLI::Range(0.01, 1000.0));
  cmd->add_option("--robot", o->robot, "sim: the scenario's policy plays; external: the graph decides")
      ->check(CLI::IsMember({"sim", "external"}));
  cmd->add_option("--master-timeout", o->master_timeout_s, "Seconds to wait for the ROS master")
      ->check(CLI::Range(0.1, 3600.0));
  add_web_options(*cmd, o->web);
  cmd->callback([o] { serve_command(*o); });
});

const RegisterCommand kRobot(61, [](CLI::App& program) {
  auto o = std::make_shared<RobotCommandOptions>();
  auto* cmd = program.add_subcommand(
      "robot", "Run a play policy, planner and move executor as ROS nodes against a live sandtray (ROS_MASTER_URI)");
  cmd->add_option("--policy", o->policy, "Registered policy (freeplay list policies)");
  cmd->add_option("--planner", o->planner, "Motion planner");
  cmd->add_option("--seed", o->seed, "Seed of the policy's and planner's random streams");
  cmd->add_option("--duration", o->duration_s, "Stop after this many seconds (default: until Ctrl-C)")
      ->check(CLI::Range(0.0, 1e7));
  cmd->add_option("--master-timeout", o->master_timeout_s, "Seconds to wait for the ROS master")
      ->check(CLI::Range(0.1, 3600.0));
  cmd->callback([o] { robot_command(*o); });
});

}  // namespace
}  // namespace freeplay::cli
