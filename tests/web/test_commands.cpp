#include <gtest/gtest.h>

#include "freeplay/web/commands.hpp"
#include "freeplay/web/robot_mode.hpp"

using namespace freeplay::web;

namespace {

const std::vector<std::string> kItems = {"zebra", "elephant", "ball"};

// The status and message a body is refused with ({0, ""} when accepted).
std::pair<int, std::string> refusal(const std::string& body) {
  try {
    parse_command(body, kItems);
  } catch (const CommandError& e) {
    return {e.status(), e.what()};
  }
  return {0, ""};
}

}  // namespace

TEST(WebCommands, MoveIsNormalisedAndRoutedToTheRobot) {
  const auto c = parse_command(R"({"type":"move","item":"zebra","x":0.3,"y":-0.1})", kItems);
  EXPECT_EQ(c.type, "move");
  EXPECT_EQ(c.target, CommandTarget::Robot);
  EXPECT_EQ(c.args["item"], "zebra");
  EXPECT_DOUBLE_EQ(c.args["x"].get<double>(), 0.3);
}

TEST(WebCommands, IllFormedUtf8AndOverflowingNumbersAreBadRequests) {
  // Both used to escape as 500: the overflow is not a parse_error, and the message quoted the invalid bytes.
  auto [status, message] = refusal("{\"type\":\"say\",\"text\":\"caf\xC3\x28\"}");
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("not JSON"), std::string::npos) << message;
  EXPECT_NE(message.find("ill-formed UTF-8"), std::string::npos) << message;
  EXPECT_NE(message.find("column 27"), std::string::npos) << message;
  EXPECT_EQ(message.find("json.exception"), std::string::npos) << message;
  for (const char ch : message) EXPECT_TRUE(ch >= 0x20 && ch < 0x7f) << message;
  for (const std::string number : {"1e999", "-1e999"}) {
    std::tie(status, message) = refusal(R"({"type":"sparc_timeout","seconds":)" + number + "}");
    EXPECT_EQ(status, 400);
    EXPECT_NE(message.find("number out of range: number overflow parsing '" + number + "'"), std::string::npos)
        << message;
    EXPECT_NE(message.find("allowed: magnitudes up to 1.79769e+308"), std::string::npos) << message;
  }
}

TEST(WebCommands, MalformedAndOutOfRangeCommandsAreRefusedWithTheAllowedValues) {
  auto [status, message] = refusal("{not json");
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("not JSON"), std::string::npos);
  std::tie(status, message) = refusal(R"({"type":"fly"})");
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("allowed: move, say"), std::string::npos) << message;
  std::tie(status, message) = refusal(R"({"type":"move","item":"unicorn","x":0.3,"y":-0.1})");
  EXPECT_NE(message.find("'item'"), std::string::npos);
  EXPECT_NE(message.find("zebra, elephant, ball"), std::string::npos) << message;
  std::tie(status, message) = refusal(R"({"type":"move","item":"zebra","x":0.3,"y":0.1})");
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("'y' = 0.1 is out of range (allowed: [-0.335, 0])"), std::string::npos) << message;
  std::tie(status, message) = refusal(R"({"type":"move","item":"zebra","x":"0.3","y":-0.1})");
  EXPECT_NE(message.find("'x' is not a number"), std::string::npos) << message;
  std::tie(status, message) = refusal(R"({"type":"move","item":"zebra","x":0.3,"y":-0.1,"speed":9})");
  EXPECT_NE(message.find("'speed' is not a field"), std::string::npos) << message;
  std::tie(status, message) = refusal(R"({"type":"move","item":"zebra","x":0.3})");
  EXPECT_NE(message.find("'y' is missing"), std::string::npos) << message;
  EXPECT_EQ(refusal(R"([1,2])").first, 400);
}

TEST(WebCommands, ExperimentAndProtocolCommandsAreChecked) {
  EXPECT_EQ(parse_command(R"({"type":"signal","name":"start_tutorial"})", kItems).target, CommandTarget::Protocol);
  EXPECT_NE(refusal(R"({"type":"signal","name":"start_party"})").second.find("start_freeplay"), std::string::npos);
  const auto d = parse_command(
      R"({"type":"demographics","purple":{"age":7,"gender":"female","tablet_familiarity":"2"}})", kItems);
  EXPECT_EQ(d.target, CommandTarget::Experiment);
  EXPECT_EQ(d.args["purple"]["age"], 7);
  EXPECT_NE(refusal(R"({"type":"demographics","purple":{"age":12,"gender":"female","tablet_familiarity":"2"}})")
                .second.find("[3, 8]"),
            std::string::npos);
  EXPECT_NE(refusal(R"({"type":"marker","kind":"funny"})").second.find("note, interesting, issue, screenshot"),
            std::string::npos);
  EXPECT_NE(refusal(R"({"type":"likert","social_engagement":6})").second.find("[1, 5]"), std::string::npos);
  EXPECT_NE(refusal(R"({"type":"say","text":""})").second.find("1…500"), std::string::npos);
  EXPECT_EQ(parse_command(R"({"type":"mode","mode":"supervised"})", kItems).args["mode"], "supervised");
  EXPECT_EQ(refusal(R"({"type":"sparc_timeout","seconds":0})").first, 400);
  EXPECT_EQ(parse_command(R"({"type":"camera","name":"env_camera"})", kItems).target, CommandTarget::View);
  EXPECT_NE(refusal(R"({"type":"camera","name":"webcam"})").second.find("env_camera"), std::string::npos);
  // The experiment's condition in the PInSoRo spelling of the one Condition (agents/condition.hpp).
  EXPECT_EQ(parse_command(R"({"type":"condition","condition":"childrobot"})", kItems).target, CommandTarget::Experiment);
  EXPECT_NE(refusal(R"({"type":"condition","condition":"child-robot"})").second.find("allowed: childchild, childrobot"),
            std::string::npos);
  const auto relative = parse_command(R"({"type":"move","item":"ball","x":-0.05,"y":0.02,"frame":"item","via":"sparc/selected_action"})", kItems);
  EXPECT_EQ(relative.args["frame"], "item");
  EXPECT_EQ(relative.args["via"], "sparc/selected_action");
}

TEST(WebCommands, RobotModeNamesRoundTripAndBadModesAreRefused) {
  for (const auto mode : {RobotMode::Autonomous, RobotMode::Wizard, RobotMode::Supervised}) {
    RobotMode read = mode == RobotMode::Wizard ? RobotMode::Supervised : RobotMode::Wizard;
    ASSERT_TRUE(from_string(to_string(mode), read));
    EXPECT_EQ(read, mode);
  }
  RobotMode unchanged = RobotMode::Supervised;
  EXPECT_FALSE(from_string("manual", unchanged));
  EXPECT_FALSE(from_string("Wizard", unchanged));
  EXPECT_EQ(unchanged, RobotMode::Supervised);
  EXPECT_EQ(robot_mode_names(), (std::vector<std::string>{"autonomous", "wizard", "supervised"}));
  // The page's `mode` command accepts exactly these names and lists them when refusing another.
  for (const auto& name : robot_mode_names()) {
    EXPECT_EQ(parse_command(R"({"type":"mode","mode":")" + name + R"("})", kItems).args["mode"], name);
  }
  const auto [status, message] = refusal(R"({"type":"mode","mode":"manual"})");
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("allowed: autonomous, wizard, supervised"), std::string::npos) << message;
}
