#include "serve_web.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <iostream>

#include "command_registry.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "vocabulary.hpp"

#ifdef FREEPLAY_WITH_WEB
#include "freeplay/web/web_session.hpp"
#endif
#if defined(FREEPLAY_WITH_WEB) && defined(FREEPLAY_WITH_ROS)
#include <mutex>

#include "freeplay/ros/graph.hpp"
#include "freeplay/ros/serve.hpp"
#include "freeplay/ros/sparc_listener.hpp"
#endif

namespace freeplay::cli {

void add_web_options(CLI::App& serve, WebCliOptions& o) {
  serve.add_option("--web", o.listen, "Serve the experimenter's web page on [ADDR:]PORT (127.0.0.1 unless ADDR; no "
                                      "ROS master needed; docs/web.md)");
  serve.add_option("--web-token", o.token, "Access token every request must carry (required beyond loopback)");
  serve.add_option("--web-out", o.out, "Session folder for events.jsonl and experiment.yaml (default runs/web-<UTC>)");
  [[maybe_unused]] auto* mode = serve.add_option("--web-mode", o.mode, "Who drives the robot at the start");
#ifdef FREEPLAY_WITH_WEB
  mode->check(CLI::IsMember(web::robot_mode_names()));
#endif
  serve.add_option("--sparc-timeout", o.sparc_timeout_s, "Supervised mode: a proposal executes after this many "
                                                         "simulated seconds unless vetoed")
      ->check(CLI::Range(0.1, 60.0));
  serve.add_flag("--web-record", o.record, "Record the session's bag from the start (<web-out>/recording/freeplay.bag; "
                                         "else paused until the page starts it)");
  serve.add_flag("--web-no-linger", o.no_linger, "Exit when the episode ends instead of waiting for 'finalise'");
  serve.add_flag("--web-graph", o.graph, "Also serve the game on the ROS master as plain serve does (its topics, "
                                         "services and sandtray/signals/*; ROS_MASTER_URI; --master-timeout)");
  serve.add_flag("--web-ros", o.ros, "Also take the real WoZ GUI's sparc/selected_action from the ROS master "
                                     "(ROS_MASTER_URI; --master-timeout)");
}

void run_web_serve(const std::string& file, const std::vector<std::string>& overrides, std::optional<std::uint64_t> seed,
                   double rate, const WebCliOptions& o, const std::atomic<bool>& stop) {
#ifdef FREEPLAY_WITH_WEB
  web::WebSessionOptions options;
  const auto colon = o.listen.rfind(':');
  const std::string port_text = colon == std::string::npos ? o.listen : o.listen.substr(colon + 1);
  if (colon != std::string::npos) options.server.address = o.listen.substr(0, colon);
  if (!options.server.address.empty() && options.server.address.front() == '[') {
    options.server.address = options.server.address.substr(1, options.server.address.size() - 2);
  }
  try {
    std::size_t used = 0;
    options.server.port = std::stoi(port_text, &used);
    if (used != port_text.size() || options.server.port < 0 || options.server.port > 65535) throw std::out_of_range("");
  } catch (const std::logic_error&) {
    throw InputError(fmt::format("--web '{}': '{}' is not a port", o.listen, port_text), "--web",
                     "[ADDR:]PORT with PORT in 0…65535 (0: any free port), e.g. 8080 or 0.0.0.0:8080");
  }
  options.server.token = o.token;
  if (!o.token.empty() && o.token.size() < 16) {
    throw InputError("--web-token is shorter than 16 characters", "--web-token", "16 or more characters");
  }
  auto scenario = scenario::load_scenario(file, overrides, scenario_vocabulary());
  options.rate = rate;
  web::from_string(o.mode, options.mode);  // checked by --web-mode's IsMember
  options.sparc_timeout_s = o.sparc_timeout_s;
  options.linger = !o.no_linger;
  options.record = o.record;
  options.out = o.out.empty() ? std::filesystem::path("runs") / fmt::format("web-{:%Y%m%dT%H%M%S}", fmt::gmtime(std::time(nullptr)))
                              : std::filesystem::path(o.out);
  const auto episode_seed = runner::episode_seed(seed.value_or(scenario.seed), 0);
  options.on_listening = [&](const std::string& url) {
    std::cout << "web: " << url << std::endl;  // the first line of output: scripts and tests read the URL here
    spdlog::info("serving '{}' (seed {}, rate {}×) on the web; session folder {}", scenario.name, episode_seed, rate,
                 options.out.string());
  };
#ifdef FREEPLAY_WITH_ROS
  // `sparc/selected_action` (the real WoZ GUI) becomes a move in the item's frame, checked as a page's command.
  std::mutex sink_mutex;
  web::CommandSink sink;
  std::unique_ptr<ros_live::SparcListener> sparc;
  std::unique_ptr<ros_live::GraphSide> graph;
  if ((o.ros || o.graph) && std::getenv("ROS_IP") == nullptr && std::getenv("ROS_HOSTNAME") == nullptr) {
    setenv("ROS_IP", "127.0.0.1", 1);
  }
  if (o.graph) {  // the game's topics and services on the master, its signals into the episode
    ros_live::ServeOptions serve;
    serve.rate = rate;
    serve.master_timeout_s = o.master_timeout_s;
    try {
      graph = std::make_unique<ros_live::GraphSide>(scenario, episode_seed, serve);
    } catch (const std::runtime_error& e) {
      if (dynamic_cast<const InputError*>(&e) != nullptr) throw;
      std::cerr << "error: " << e.what() << "\n";
      fail_with(1);
    }
    options.also_observe = &graph->publisher();
    options.also_frames = &graph->cameras();
    options.signals = &graph->signals();
  }
  if (o.ros) {
    std::string error;
    if (!ros_graph::start_ros("sandtray_web", o.master_timeout_s, error)) {
      std::cerr << "error: " << error << "\n";
      fail_with(1);
    }
    options.on_commands = [&](web::CommandSink s) {
      std::lock_guard lock(sink_mutex);
      sink = std::move(s);
    };
    sparc = std::make_unique<ros_live::SparcListener>([&](const std::string& item, double x, double y) {
      std::lock_guard lock(sink_mutex);
      if (!sink) return;
      const auto reply = sink(nlohmann::json{{"type", "move"}, {"item", item}, {"x", x}, {"y", y}, {"frame", "item"},
                                             {"via", "sparc/selected_action"}}
                                  .dump());
      if (reply.status >= 400) spdlog::warn("sparc/selected_action for '{}' refused: {}", item, reply.body);
    });
  }
#else
  if (o.ros || o.graph) {
    throw InputError("this freeplay was built without ROS 1", o.ros ? "--web-ros" : "--web-graph",
                     "install it with scripts/setup.sh and rebuild");
  }
#endif
  const auto report = web::serve_web(scenario, episode_seed, options, stop);
  nlohmann::json summary{{"aborted", report.result.aborted},
                         {"duration_s", report.result.duration_s},
                         {"simulated_s", report.result.simulated_s},
                         {"ticks", report.ticks},
                         {"timing", runner::timing_json(report.timing)},
                         {"web",
                          {{"frames_sent", report.server.frames_sent},
                           {"frames_dropped", report.server.frames_dropped},
                           {"requests", report.server.requests},
                           {"refused", report.server.refused}}}};
  std::cout << summary.dump() << std::endl;
  if (report.result.aborted) fail_with(130);
#else
  (void)file, (void)overrides, (void)seed, (void)rate, (void)o, (void)stop;
  throw InputError("this freeplay was built without the web page (websocketpp)", "--web",
                   "install libwebsocketpp-dev with scripts/setup.sh and rebuild");
#endif
}

}  // namespace freeplay::cli
