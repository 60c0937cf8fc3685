// The served episode driven from the web page: protocol buttons move its stages, wizard speech is the robot's
// speech, the coder's labels reach the page, and the experiment manager's components (recorder, robot side) switch.
#include <gtest/gtest.h>
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <fstream>
#include <thread>

#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/web/web_session.hpp"
#include "http_client.hpp"
#include "session_support.hpp"

using namespace freeplay;
using namespace freeplay::web;
using test_http::post;
using test_http::request;

namespace {

// Watches a session's state from its own thread (as a page would) and acts on it through the HTTP API.
class Driver {
 public:
  using Step = std::function<void(int port, const nlohmann::json& state)>;
  explicit Driver(Step step) : step_(std::move(step)) {}
  ~Driver() {
    done_ = true;
    if (thread_.joinable()) thread_.join();
  }
  void start(const std::string& url) {
    const int port = std::stoi(url.substr(url.rfind(':') + 1));
    thread_ = std::thread([this, port] {
      while (!done_) {
        const auto [status, body] = request(port, "GET", "/api/state");
        if (status == 200) step_(port, nlohmann::json::parse(body));
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    });
  }

 private:
  Step step_;
  std::atomic<bool> done_{false};
  std::thread thread_;
};

std::vector<nlohmann::json> read_events(const std::filesystem::path& file) {
  std::vector<nlohmann::json> out;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) out.push_back(nlohmann::json::parse(line));
  return out;
}

}  // namespace

TEST(WebComponents, ProtocolButtonsMoveTheServedEpisodesStages) {
  const auto scenario = test_session::scenario(
      "name: t\ncondition: child-child\nprotocol: {greeting_s: 600, tutorial_s: 600, freeplay_cap_s: 600, debriefing_s: 1}\n");
  auto options = test_session::options("freeplay-web-protocol", 10.0);
  const auto out = options.out;
  std::set<std::string> sent;
  nlohmann::json coded;  // a child's coded state as the page saw it in free play
  std::mutex mutex;
  Driver driver([&](int port, const nlohmann::json& s) {
    std::lock_guard lock(mutex);
    const auto stage = s.value("stage", "");
    auto once = [&](const std::string& name) {
      if (sent.insert(name).second) post(port, nlohmann::json{{"type", "signal"}, {"name", name}}.dump());
    };
    if (stage == "greeting" && s.value("t", 0.0) >= 0.5) once("start_tutorial");
    if (stage == "tutorial") once("start_freeplay");
    if (stage == "freeplay" && s.value("freeplay_t", 0.0) >= 3.0) {
      coded = s["children"][0]["coded"];
      once("blank_interface");
    }
  });
  options.on_listening = [&](const std::string& url) { driver.start(url); };
  const std::atomic<bool> stop{false};
  const auto report = serve_web(scenario, 5, options, stop);
  ASSERT_FALSE(report.result.aborted);
  std::vector<std::string> stages;
  std::vector<std::string> received;
  for (const auto& e : report.result.events.events()) {
    if (e.source == "protocol" && e.type() == "stage") stages.push_back(e.data()["stage"]);
    if (e.source == "protocol" && e.type() == "signal_received") received.push_back(e.data()["name"]);
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"greeting", "tutorial", "freeplay", "debriefing"}));
  EXPECT_EQ(received, (std::vector<std::string>{"start_tutorial", "start_freeplay", "blank_interface"}));
  EXPECT_EQ(report.result.record["ended_by"], "signal");
  EXPECT_GT(report.result.duration_s, 2.9);
  EXPECT_LT(report.result.duration_s, 30.0);  // ended by the button, not the 600 s cap
  EXPECT_LT(report.result.simulated_s, 60.0);  // the 600 s greeting and tutorial were cut short
  int logged = 0;
  for (const auto& e : read_events(out / "events.jsonl")) logged += e["source"] == "experimenter" && e["type"] == "signal";
  EXPECT_EQ(logged, 3);
  std::lock_guard lock(mutex);
  ASSERT_TRUE(coded.is_object()) << coded.dump();
  for (const auto* axis : {"task", "social", "attitude"}) EXPECT_FALSE(coded.value(axis, "").empty()) << axis;
}

TEST(WebComponents, WizardSpeechIsTheRobotsAndTheRecorderAndRobotSideSwitch) {
  const auto scenario = test_session::scenario(
      "name: t\ncondition: child-robot\nrobot: {policy: asocial}\n"
      "protocol: {greeting_s: 1, tutorial_s: 1, freeplay_cap_s: 9, debriefing_s: 1}\n");
  auto options = test_session::options("freeplay-web-components", 5.0);
  const auto out = options.out;
  std::set<std::string> done;
  std::vector<nlohmann::json> components;
  std::mutex mutex;
  Driver driver([&](int port, const nlohmann::json& s) {
    std::lock_guard lock(mutex);
    if (s.value("stage", "") != "freeplay") return;
    const double t = s.value("freeplay_t", 0.0);
    auto once = [&](const std::string& key, const std::string& body) {
      if (t >= 0 && done.insert(key).second) post(port, body);
    };
    if (t >= 1.0) {
      once("record", R"({"type":"component","name":"recorder","action":"start"})");
      once("say", R"({"type":"say","text":"Hello from the wizard","to":"purple"})");
    }
    if (t >= 4.0) {
      once("robot-stop", R"({"type":"component","name":"robot","action":"stop"})");
      once("pause", R"({"type":"component","name":"recorder","action":"stop"})");
    }
    if (t >= 2.5 && t < 3.5 && done.insert("seen-recording").second) components.push_back(s["components"]);
    if (t >= 5.0 && done.insert("seen-paused").second) components.push_back(s["components"]);
    if (t >= 6.0) once("robot-start", R"({"type":"component","name":"robot","action":"start"})");
  });
  options.on_listening = [&](const std::string& url) {
    // No cameras in the scenario: switching them is refused; an unknown component is malformed.
    const int port = std::stoi(url.substr(url.rfind(':') + 1));
    EXPECT_EQ(post(port, R"({"type":"component","name":"cameras","action":"stop"})").first, 409);
    EXPECT_EQ(post(port, R"({"type":"component","name":"kettle","action":"stop"})").first, 400);
    driver.start(url);
  };
  const std::atomic<bool> stop{false};
  const auto report = serve_web(scenario, 9, options, stop);
  ASSERT_FALSE(report.result.aborted);

  // The wizard's words are the robot's own speech in the episode's log.
  const Event* said = nullptr;
  for (const auto& e : report.result.events.events()) {
    if (e.source == "robot" && e.type() == "say" && e.data()["text"] == "Hello from the wizard") said = &e;
  }
  ASSERT_NE(said, nullptr);
  EXPECT_EQ(said->data()["to"], "purple");
  EXPECT_GT(said->data()["duration_s"].get<double>(), 0.5);

  // The page saw the components switch.
  {
    std::lock_guard lock(mutex);
    ASSERT_EQ(components.size(), 2u);
    EXPECT_EQ(components[0]["recorder"]["state"], "recording");
    EXPECT_EQ(components[0]["robot"]["state"], "running");
    EXPECT_EQ(components[0]["cameras"]["state"], "none");
    EXPECT_EQ(components[1]["recorder"]["state"], "paused");
    EXPECT_EQ(components[1]["robot"]["state"], "paused");
  }
  // Every action is in the session log; the recorder's spans are marked.
  double resumed = -1.0;
  double paused = -1.0;
  int switches = 0;
  for (const auto& e : read_events(out / "events.jsonl")) {
    if (e["source"] == "recorder" && e["type"] == "resumed") resumed = e["t"];
    if (e["source"] == "recorder" && e["type"] == "paused") paused = e["t"];
    switches += e["source"] == "experimenter" && e["type"] == "component";
    switches += e["source"] == "robot_side";
  }
  EXPECT_EQ(switches, 4 + 2);  // recorder start/stop, robot stop/start; the robot side's paused and resumed
  ASSERT_GT(resumed, 0.0);
  ASSERT_GT(paused, resumed);

  // The bag holds the recorded span only, with the whole session log (the wizard's command too) and the speech.
  rosbag::Bag bag((out / "recording" / "freeplay.bag").string());
  int events = 0;
  bool command = false;
  bool resumed_in_bag = false;
  for (const auto& m : rosbag::View(bag, rosbag::TopicQuery("/freeplay/events"))) {
    const auto e = nlohmann::json::parse(recording::std_string(m.instantiate<recording::msg::String>()->data));
    EXPECT_GE(e["tick"].get<double>(), resumed - 1e-6);
    EXPECT_LT(e["tick"].get<double>(), paused + 1e-6);
    command = command || (e["source"] == "wizard" && e["type"] == "command" && e["data"]["command"] == "say");
    resumed_in_bag = resumed_in_bag || (e["source"] == "recorder" && e["type"] == "resumed");
    ++events;
  }
  EXPECT_GT(events, 3);
  EXPECT_TRUE(command);
  EXPECT_TRUE(resumed_in_bag);
  std::vector<std::string> speech;
  for (const auto& m : rosbag::View(bag, rosbag::TopicQuery("/speech"))) {
    speech.push_back(recording::std_string(m.instantiate<recording::msg::String>()->data));
  }
  EXPECT_EQ(speech, std::vector<std::string>{"Hello from the wizard"});
  int tf = 0;
  double first = 1e18;
  double last = -1e18;
  for (const auto& m : rosbag::View(bag, rosbag::TopicQuery("/tf"))) {
    ++tf;
    first = std::min(first, m.getTime().toSec());
    last = std::max(last, m.getTime().toSec());
  }
  EXPECT_GT(tf, 20);  // ≈ 3 s at 10 Hz: items, touches and the Nao's links
  EXPECT_LT(last - first, paused - resumed + 0.5);  // not the whole session
}
