// The scripted policy's script: every action kind is read into its action, and a bad script is an InputError
// naming the key path (under `robot.params`, or in the `file:` with its line and column) and the allowed values.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "freeplay/core/error.hpp"
#include "freeplay/policies/play_policy.hpp"

using namespace freeplay;
using namespace freeplay::policies;

namespace {

/// The actions `params` start at free-play second 1.
std::vector<Action> due_at_one(const std::string& params) {
  auto policy = make_policy("scripted", YAML::Load(params));
  policy->reset({}, Rng(1));
  Observation obs;
  obs.t = 1.0;
  return policy->decide(obs);
}

/// The InputError `params` raise (fails the test when there is none).
InputError error_of(const YAML::Node& params) {
  try {
    make_policy("scripted", params);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("none");
}

InputError error_of(const std::string& params) { return error_of(YAML::Load(params)); }

/// A script file in the temporary folder, removed at the end of the test.
class ScriptFile {
 public:
  explicit ScriptFile(const std::string& text)
      : path_(std::filesystem::path(::testing::TempDir()) /
              (std::string("freeplay_script_") + ::testing::UnitTest::GetInstance()->current_test_info()->name() +
               ".yaml")) {
    std::ofstream(path_) << text;
  }
  ~ScriptFile() { std::filesystem::remove(path_); }
  ScriptFile(const ScriptFile&) = delete;
  ScriptFile& operator=(const ScriptFile&) = delete;
  /// The file's path.
  std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace

TEST(ScriptedScript, EveryActionKindIsReadIntoItsAction) {
  const auto due = due_at_one(R"(
actions:
  - {t: 1, move: {item: lion, to: [0.25, -0.125]}}
  - {t: 1, say: {text: "Hi!"}}
  - {t: 1, say: {text: "You!", to: yellow}}
  - {t: 1, look_at: {child: purple}}
  - {t: 1, look_at: {point: [0.1, 0.2, 0.3]}}
  - {t: 1, point_at: [-0.5, 0.75]}
  - {t: 1, cancel: true}
  - {t: 1, wait: 2.5}
)");
  ASSERT_EQ(due.size(), 8u);
  const auto& move = std::get<MoveItem>(due[0]);
  EXPECT_EQ(move.item, "lion");
  EXPECT_EQ(move.target.x(), 0.25);
  EXPECT_EQ(move.target.y(), -0.125);
  EXPECT_EQ(std::get<Say>(due[1]).text, "Hi!");
  EXPECT_EQ(std::get<Say>(due[1]).addressee, "");  // `to` defaults to both: no one in particular
  EXPECT_EQ(std::get<Say>(due[2]).addressee, "yellow");
  EXPECT_EQ(std::get<LookAt>(due[3]).child.value_or(""), "purple");
  EXPECT_FALSE(std::get<LookAt>(due[3]).point.has_value());
  EXPECT_FALSE(std::get<LookAt>(due[4]).child.has_value());
  ASSERT_TRUE(std::get<LookAt>(due[4]).point.has_value());
  EXPECT_EQ(*std::get<LookAt>(due[4]).point, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(std::get<PointAt>(due[5]).point.x(), -0.5);
  EXPECT_EQ(std::get<PointAt>(due[5]).point.y(), 0.75);
  EXPECT_TRUE(std::holds_alternative<CancelMove>(due[6]));
  EXPECT_DOUBLE_EQ(std::get<Wait>(due[7]).seconds, 2.5);
}

TEST(ScriptedScript, AnEntryWithTwoKindsOrNoneNamesItsIndexAndTheKinds) {
  const auto two = error_of("actions: [{t: 1, say: {text: a}}, {t: 1, wait: 1, cancel: true}]");
  EXPECT_EQ(two.key(), "robot.params.actions[1]");
  EXPECT_EQ(two.allowed(), "move, say, look_at, point_at, cancel, wait");
  EXPECT_NE(std::string(two.what()).find("action 1 must have exactly one of"), std::string::npos) << two.what();
  EXPECT_EQ(error_of("actions: [{t: 1}]").key(), "robot.params.actions[0]");
  EXPECT_EQ(error_of("actions: [{t: 1, cancel: false}]").key(), "robot.params.actions[0]");  // false is no action
}

TEST(ScriptedScript, AnUnknownKeyNamesTheAllowedKeys) {
  const auto e = error_of("actions: [{t: 1, wait: 1}, {t: 1, dance: true}]");
  EXPECT_EQ(e.key(), "robot.params.actions[1].dance");
  EXPECT_EQ(e.allowed(), "t, every, until, move, say, look_at, point_at, cancel, wait");
  const auto nested = error_of("actions: [{t: 1, move: {item: zebra, to: [0, 0], speed: 2}}]");
  EXPECT_EQ(nested.key(), "robot.params.actions[0].move.speed");
  EXPECT_EQ(nested.allowed(), "item, to");
  EXPECT_EQ(error_of("{acts: []}").key(), "robot.params.acts");
}

TEST(ScriptedScript, APointOfTheWrongLengthIsRejected) {
  const auto e = error_of("actions: [{t: 1, wait: 1}, {t: 2, move: {item: zebra, to: [0.1, 0.2, 0.3]}}]");
  EXPECT_EQ(e.key(), "robot.params.actions[1].move.to");
  EXPECT_NE(e.problem().find("3 element(s)"), std::string::npos) << e.what();
  EXPECT_EQ(error_of("actions: [{t: 1, point_at: [0.1]}]").key(), "robot.params.actions[0].point_at");
  EXPECT_EQ(error_of("actions: [{t: 1, look_at: {point: [0, 0]}}]").key(), "robot.params.actions[0].look_at.point");
}

TEST(ScriptedScript, AMissingTimeOrTextIsNamed) {
  const auto t = error_of("actions: [{say: {text: a}}]");
  EXPECT_EQ(t.key(), "robot.params.actions[0].t");
  EXPECT_NE(t.problem().find("missing required key 't'"), std::string::npos) << t.what();
  EXPECT_EQ(error_of("actions: [{t: 1, say: {to: purple}}]").key(), "robot.params.actions[0].say.text");
  EXPECT_EQ(error_of("actions: [{t: 1, say: {text: a, to: everyone}}]").allowed(), "one of purple, yellow, both");
  EXPECT_EQ(error_of("{}").key(), "robot.params");  // neither actions nor file
}

TEST(ScriptedScript, AScriptFileIsReadAndItsProblemsNamedInTheFile) {
  const ScriptFile good("actions:\n  - {t: 1, say: {text: from the file}}\n");
  const auto due = due_at_one("file: " + good.path());
  ASSERT_EQ(due.size(), 1u);
  EXPECT_EQ(std::get<Say>(due[0]).text, "from the file");

  const ScriptFile bad(
      "actions:\n"
      "  - {t: 1, wait: 1}\n"
      "  - {t: 2, wait: 1}\n"
      "  - {t: 3, move: {item: zebra, to: [0.1]}}\n");
  const auto e = error_of("file: " + bad.path());
  EXPECT_EQ(e.key(), "actions[2].move.to");
  EXPECT_EQ(e.where().file, bad.path());
  EXPECT_EQ(e.where().line, 4);
  EXPECT_EQ(e.where().column, 36);
  EXPECT_NE(std::string(e.what()).find(bad.path() + ":4:36: 'actions[2].move.to'"), std::string::npos) << e.what();
}

TEST(ScriptedScript, AnEntryProblemInAScriptFileHasItsPosition) {
  const ScriptFile two("actions:\n  - {t: 1, wait: 1}\n  - {t: 2, wait: 1, say: {text: a}}\n");
  const auto e = error_of("file: " + two.path());
  EXPECT_EQ(e.key(), "robot.params.actions[1]");
  EXPECT_EQ(e.where().file, two.path());
  EXPECT_EQ(e.where().line, 3);
  EXPECT_EQ(e.where().column, 5);
}

TEST(ScriptedScript, AMissingScriptFileIsAnInputError) {
  const auto e = error_of("file: /nonexistent/script.yaml");
  EXPECT_EQ(e.where().file, "/nonexistent/script.yaml");
}

TEST(ScriptedScript, AScriptFileWithoutActionsIsNamed) {
  const ScriptFile empty("acts: []\n");
  const auto e = error_of("file: " + empty.path());
  EXPECT_EQ(e.key(), "actions");
  EXPECT_EQ(e.where().file, empty.path());
}
