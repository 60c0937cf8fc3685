#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <fstream>

#include "freeplay/web/web_session.hpp"
#include "http_client.hpp"
#include "session_support.hpp"

using namespace freeplay;
using namespace freeplay::web;

using freeplay::web::test_http::post;

TEST(WebSession, AChildChildSessionTakesExperimentCommandsAndRefusesRobotOnes) {
  const auto scenario = test_session::scenario(
      "name: t\ncondition: child-child\nprotocol: {greeting_s: 1, tutorial_s: 1, freeplay_cap_s: 5, debriefing_s: 1}\n");
  auto options = test_session::options("freeplay-web-session", 50.0);
  const auto out = options.out;
  std::vector<std::pair<int, std::string>> answers;
  options.on_listening = [&](const std::string& url) {
    const int port = std::stoi(url.substr(url.rfind(':') + 1));
    answers.push_back(post(port, R"({"type":"move","item":"zebra","x":0.3,"y":-0.1})"));
    answers.push_back(post(port, R"({"type":"demographics","purple":{"age":5,"gender":"male","tablet_familiarity":"1"},
                                     "yellow":{"age":8,"gender":"female","tablet_familiarity":"0"}})"));
    answers.push_back(post(port, R"({"type":"signal","name":"start_tutorial"})"));
    answers.push_back(post(port, R"({"type":"marker","kind":"issue"})"));
    // Bad requests through the whole HTTP path: 400 with the reason, never a 500.
    answers.push_back(post(port, "{\"type\":\"note\",\"text\":\"caf\xC3\x28\"}"));
    answers.push_back(post(port, R"({"type":"sparc_timeout","seconds":1e999})"));
  };
  const std::atomic<bool> stop{false};
  const auto report = serve_web(scenario, 5, options, stop);
  ASSERT_FALSE(report.result.aborted);
  ASSERT_EQ(answers.size(), 6u);
  EXPECT_EQ(answers[0].first, 409);
  EXPECT_NE(answers[0].second.find("no robot"), std::string::npos);
  EXPECT_EQ(answers[1].first, 200);
  EXPECT_EQ(answers[2].first, 202);
  EXPECT_NE(answers[2].second.find("sandtray/signals/start_tutorial"), std::string::npos);
  EXPECT_EQ(answers[3].first, 409);  // before free play
  EXPECT_EQ(answers[4].first, 400);
  EXPECT_NE(answers[4].second.find("ill-formed UTF-8"), std::string::npos) << answers[4].second;
  EXPECT_EQ(answers[5].first, 400);
  EXPECT_NE(answers[5].second.find("number overflow parsing '1e999'"), std::string::npos) << answers[5].second;
  const auto yaml = YAML::LoadFile((out / "experiment.yaml").string());
  EXPECT_EQ(yaml["condition"].as<std::string>(), "childchild");
  EXPECT_EQ(yaml["yellow-participant"]["age"].as<int>(), 8);
  EXPECT_GT(yaml["timestamp"].as<std::uint64_t>(), 0u);  // free play started
  std::ifstream events(out / "events.jsonl");
  std::string line;
  int episode_events = 0;
  int signals = 0;
  while (std::getline(events, line)) {
    const auto e = nlohmann::json::parse(line);
    episode_events += e["source"] == "protocol" ? 1 : 0;
    signals += e["source"] == "experimenter" && e["type"] == "signal" ? 1 : 0;
  }
  EXPECT_GE(episode_events, 4);  // the stages and the end of free play
  EXPECT_EQ(signals, 1);
  EXPECT_TRUE(std::filesystem::exists(out / "episode.json"));
  EXPECT_GT(report.ticks, 60u);  // ≈ 80 ticks of 0.1 s
  EXPECT_GE(report.timing.ticks, 60u);  // the live episode paced and timed every tick (values: wall time, not asserted)
  EXPECT_EQ(report.server.refused, 4u);
}
