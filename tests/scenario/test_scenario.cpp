#include <gtest/gtest.h>

#include "freeplay/scenario/scenario.hpp"

using namespace freeplay;
using namespace freeplay::scenario;

namespace {

Scenario parse(const std::string& text, const std::vector<std::string>& overrides = {},
               const ScenarioVocabulary& vocabulary = {}) {
  return scenario_from_document(parse_yaml(text, "test.yaml"), overrides, vocabulary);
}

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {},
                     const ScenarioVocabulary& vocabulary = {}) {
  try {
    parse(text, overrides, vocabulary);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// Every one of `values` reads back from its own name (starting from another value, so that a reader that sets
// nothing fails), and each of `bad` reads as none, leaving the value as it was.
template <typename Enum>
void expect_names_round_trip(std::initializer_list<Enum> values, std::initializer_list<std::string_view> bad) {
  for (const Enum value : values) {
    Enum read = value == *values.begin() ? *std::prev(values.end()) : *values.begin();
    ASSERT_TRUE(from_string(to_string(value), read)) << to_string(value);
    EXPECT_EQ(read, value);
  }
  for (const std::string_view text : bad) {
    Enum unchanged = *values.begin();
    EXPECT_FALSE(from_string(text, unchanged)) << text;
    EXPECT_EQ(unchanged, *values.begin());
  }
}

}  // namespace

TEST(Scenario, MinimalFileGetsDefaults) {
  const auto s = parse("name: cc\ncondition: child-child\n");
  EXPECT_EQ(s.name, "cc");
  EXPECT_EQ(s.episodes, 1);
  EXPECT_EQ(s.planner.name, "astar");
  EXPECT_DOUBLE_EQ(s.protocol.freeplay_cap_s, 2400.0);
  EXPECT_DOUBLE_EQ(s.perception.face_detection_rate, 0.98);
  EXPECT_DOUBLE_EQ(s.robot.arm_reach_m, 0.5);
  EXPECT_TRUE(s.cameras.empty());
}

TEST(Scenario, UnknownKeyNamesFileLineColumnAndAllowedKeys) {
  const auto msg = error_of("name: cc\ncondition: child-child\nplanner:\n  nmae: astar\n");
  EXPECT_NE(msg.find("test.yaml:4:3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'planner.nmae'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("allowed: name, time_budget_s, finger_speed_mps"), std::string::npos) << msg;
}

TEST(Scenario, WrongTypeAndOutOfRange) {
  auto msg = error_of("name: cc\ncondition: child-child\nepisodes: many\n");
  EXPECT_NE(msg.find("test.yaml:3:11"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected an integer"), std::string::npos) << msg;
  msg = error_of("name: cc\ncondition: child-child\nchildren:\n  purple: {age: 12}\n");
  EXPECT_NE(msg.find("'children.purple.age'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("integer in [4, 8]"), std::string::npos) << msg;
}

TEST(Scenario, UnknownEnumListsAllowedValues) {
  const auto msg = error_of("name: x\ncondition: child-robot\nrobot: {policy: friendly}\n");
  EXPECT_NE(msg.find("unknown value 'friendly'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("asocial, idle, scripted, social, yoked"), std::string::npos) << msg;
}

TEST(Scenario, MissingRequiredKey) {
  const auto msg = error_of("name: x\n");
  EXPECT_NE(msg.find("missing required key 'condition'"), std::string::npos) << msg;
}

TEST(Scenario, AllProblemsReportedAtOnce) {
  const auto msg = error_of("name: x\ncondition: child-robot\nepisodes: 0\nrecord: maybe\n");
  EXPECT_NE(msg.find("episodes"), std::string::npos) << msg;
  EXPECT_NE(msg.find("record"), std::string::npos) << msg;
  EXPECT_NE(msg.find("2 problems"), std::string::npos) << msg;
}

TEST(Scenario, OverridesAreValidatedLikeTheFile) {
  const auto s = parse("name: cc\ncondition: child-child\n", {"planner.name=rrtconnect", "episodes=7"});
  EXPECT_EQ(s.planner.name, "rrtconnect");
  EXPECT_EQ(s.episodes, 7);
  const auto msg = error_of("name: cc\ncondition: child-child\n", {"planner.name=teleport"});
  EXPECT_NE(msg.find("unknown value 'teleport'"), std::string::npos) << msg;
  EXPECT_THROW(parse("name: cc\ncondition: child-child\n", {"no-equals-sign"}), InputError);
}

TEST(Scenario, RobotTakesTheYellowPlace) {
  const auto msg = error_of("name: x\ncondition: child-robot\nchildren:\n  yellow: {age: 6}\n");
  EXPECT_NE(msg.find("yellow place"), std::string::npos) << msg;
}

TEST(Scenario, SyntaxErrorHasLocation) {
  const auto msg = error_of("name: [unclosed\ncondition: child-child\n");
  EXPECT_NE(msg.find("test.yaml:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("YAML syntax error"), std::string::npos) << msg;
}

TEST(Scenario, ConfigHashDependsOnContent) {
  const auto a = parse("name: cc\ncondition: child-child\n");
  const auto b = parse("name: cc\ncondition: child-child\nseed: 2\n");
  EXPECT_NE(a.config_hash, b.config_hash);
  EXPECT_EQ(a.config_hash, parse("name: cc\ncondition: child-child\n").config_hash);
}

TEST(Scenario, KindConditionAndModeAreReadOnceIntoTheirEnums) {
  const auto s = parse("name: cr\ncondition: child-robot\nrobot: {mode: dynamic}\n");
  EXPECT_EQ(s.kind, ScenarioKind::episode);
  EXPECT_EQ(s.condition, Condition::ChildRobot);
  EXPECT_EQ(s.robot.mode, stage::StageMode::dynamic);
  EXPECT_EQ(parse("name: cc\ncondition: child-child\n").robot.mode, stage::StageMode::kinematic);
  const std::string missing = error_of("name: x\n");
  EXPECT_NE(missing.find("missing required key 'condition' (allowed: child-child, child-robot)"), std::string::npos)
      << missing;
}

TEST(Scenario, EnumNamesRoundTrip) {
  expect_names_round_trip({Condition::ChildChild, Condition::ChildRobot, Condition::Controller},
                          {"robot-robot", "childrobot", ""});
  EXPECT_EQ(to_string(Condition::ChildRobot), "child-robot");
  EXPECT_EQ(pinsoro_name(Condition::ChildRobot), "childrobot");
  EXPECT_EQ(pinsoro_name(Condition::ChildChild), "childchild");
  expect_names_round_trip({ScenarioKind::episode, ScenarioKind::controller}, {"session", "Controller"});
  expect_names_round_trip({stage::StageMode::kinematic, stage::StageMode::dynamic}, {"physics", ""});
}

TEST(Scenario, ChildrenPopulationIsAnEnumOfTheAgents) {
  using agents::PopulationName;
  expect_names_round_trip({PopulationName::pinsoro, PopulationName::pinsoro_cc, PopulationName::pinsoro_cr},
                          {"pinsoro_cc", "PInSoRo"});
  EXPECT_EQ(parse("name: cc\ncondition: child-child\n").children.population, PopulationName::pinsoro);
  const auto cr = parse("name: cc\ncondition: child-child\nchildren: {population: pinsoro-cr}\n");
  EXPECT_EQ(cr.children.population, PopulationName::pinsoro_cr);
  EXPECT_EQ(cr.source["children"]["population"].as<std::string>(), "pinsoro-cr");
  const auto bad = error_of("name: cc\ncondition: child-child\nchildren: {population: pinsoro-xx}\n");
  EXPECT_NE(bad.find("'children.population': unknown value 'pinsoro-xx' (allowed: one of pinsoro, pinsoro-cc, "
                     "pinsoro-cr)"),
            std::string::npos)
      << bad;
}

TEST(Scenario, PinsoroSpellingRoundTrips) {
  for (const auto condition : {Condition::ChildChild, Condition::ChildRobot}) {
    Condition read = condition == Condition::ChildChild ? Condition::ChildRobot : Condition::ChildChild;
    ASSERT_TRUE(agents::from_pinsoro_name(pinsoro_name(condition), read));
    EXPECT_EQ(read, condition);
  }
  // The scenario names are not the dataset's, and "controller" has no spelling of its own there.
  Condition unchanged = Condition::Controller;
  EXPECT_FALSE(agents::from_pinsoro_name("child-robot", unchanged));
  EXPECT_FALSE(agents::from_pinsoro_name("controller", unchanged));
  EXPECT_EQ(unchanged, Condition::Controller);
}

// Each block a scenario leaves out takes the defaults of the library that declares its settings (one home each); the
// literal values are the documented ones (README, Settings; docs/recording.md).
TEST(Scenario, EachLeftOutBlockTakesItsLibrarysDefaults) {
  const auto s = parse("name: cc\ncondition: child-child\n");
  EXPECT_EQ(s.rendering, stage::RenderingSettings{});
  EXPECT_EQ(s.rendering.backend, std::nullopt);
  EXPECT_EQ(s.rendering.preset, stage::VisualPreset::fast);
  EXPECT_FALSE(s.record);
  EXPECT_EQ(s.recording, recording::RecordSettings{});
  EXPECT_EQ(s.recording.jpeg_quality, 90);
  EXPECT_EQ(s.recording.png_level, 3);
  EXPECT_EQ(s.recording.chunk_kb, 768);
  EXPECT_EQ(s.recording.compression, "none");
  EXPECT_EQ(s.recording.encoder_threads, 2);
  EXPECT_EQ(s.recording.voice, "babble");
  // `record: true` and a map without the keys give the recorder's defaults too.
  const auto on = parse("name: cc\ncondition: child-child\nrecord: true\n");
  EXPECT_TRUE(on.record);
  EXPECT_EQ(on.recording, recording::RecordSettings{});
  const auto map = parse("name: cc\ncondition: child-child\nrecord: {bag: false}\n");
  EXPECT_FALSE(map.record);
  EXPECT_EQ(map.recording, recording::RecordSettings{});
  EXPECT_EQ(parse("name: cc\ncondition: child-child\nrecord: {}\n").record, true);
}

TEST(Scenario, ACameraWithOnlyItsNameTakesTheStagesDefaults) {
  const auto s = parse("name: cc\ncondition: child-child\ncameras: [{name: camera_purple}]\n");
  ASSERT_EQ(s.cameras.size(), 1u);
  stage::CameraStream expected;
  expected.name = "camera_purple";
  EXPECT_EQ(s.cameras[0], expected);
  EXPECT_DOUBLE_EQ(s.cameras[0].rate_hz, 30.0);
  EXPECT_EQ(s.cameras[0].width, 960);
  EXPECT_EQ(s.cameras[0].height, 540);
  EXPECT_FALSE(s.cameras[0].depth);
  EXPECT_FALSE(s.cameras[0].video);
}

TEST(Scenario, MovedBlocksKeepTheirKeysAndValues) {
  const auto s = parse(
      "name: cr\ncondition: child-robot\n"
      "cameras: [{name: CameraTop, rate_hz: 10, width: 320, height: 240, depth: true, video: true}]\n"
      "rendering: {backend: egl, preset: pretty}\n"
      "record: {bag: true, jpeg_quality: 50, png_level: 9, chunk_kb: 16, compression: lz4, encoder_threads: 0, "
      "voice: espeak}\n");
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].name, "CameraTop");
  EXPECT_DOUBLE_EQ(s.cameras[0].rate_hz, 10.0);
  EXPECT_EQ(s.cameras[0].width, 320);
  EXPECT_EQ(s.cameras[0].height, 240);
  EXPECT_TRUE(s.cameras[0].depth);
  EXPECT_TRUE(s.cameras[0].video);
  EXPECT_EQ(s.rendering.backend, stage::GlBackend::egl);
  EXPECT_EQ(s.rendering.preset, stage::VisualPreset::pretty);
  EXPECT_TRUE(s.record);
  EXPECT_EQ(s.recording.jpeg_quality, 50);
  EXPECT_EQ(s.recording.png_level, 9);
  EXPECT_EQ(s.recording.chunk_kb, 16);
  EXPECT_EQ(s.recording.compression, "lz4");
  EXPECT_EQ(s.recording.encoder_threads, 0);
  EXPECT_EQ(s.recording.voice, "espeak");
}

// `rendering:` reads its names into the renderer's enums (stage/render_names.hpp), and a name that is none of them is
// an error naming the key and the allowed names.
TEST(RenderingSettings, ReadsTheNamesIntoTheRenderersEnums) {
  const auto read = [](const std::string& text) {
    return read_unvalidated_settings<stage::RenderingSettings>(YAML::Load(text), "rendering");
  };
  const auto both = read("{preset: pretty, backend: egl}");
  EXPECT_EQ(both.preset, stage::VisualPreset::pretty);
  ASSERT_TRUE(both.backend.has_value());
  EXPECT_EQ(*both.backend, stage::GlBackend::egl);
  EXPECT_EQ(read("{backend: osmesa}").backend, stage::GlBackend::osmesa);
  const auto defaults = read("{}");
  EXPECT_EQ(defaults.preset, stage::kDefaultVisualPreset);
  EXPECT_FALSE(defaults.backend.has_value());
  const auto error_of_rendering = [&](const std::string& text) -> std::string {
    try {
      read(text);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error_of_rendering("{preset: bogus}"),
            "'rendering.preset': unknown value 'bogus' (allowed: one of fast, pretty)");
  EXPECT_EQ(error_of_rendering("{backend: vulkan}"),
            "'rendering.backend': unknown value 'vulkan' (allowed: one of osmesa, egl)");
}

TEST(Scenario, MovedBlocksNameTheKeyAndTheAllowedValues) {
  const auto expect_error = [](const std::string& text, const std::string& wanted) {
    const std::string msg = error_of("name: cc\ncondition: child-child\n" + text);
    EXPECT_NE(msg.find(wanted), std::string::npos) << msg;
  };
  expect_error("rendering: {preset: ugly}\n",
               "'rendering.preset': unknown value 'ugly' (allowed: one of fast, pretty)");
  expect_error("rendering: {backend: vulkan}\n",
               "'rendering.backend': unknown value 'vulkan' (allowed: one of osmesa, egl)");
  expect_error("rendering: {msaa: 4}\n", "allowed: backend, preset");
  expect_error("cameras: [{name: camera_purple, width: 8}]\n", "'cameras[0].width'");
  expect_error("cameras: [{name: camera_purple, width: 8}]\n", "integer in [16, 4096]");
  expect_error("cameras: [{name: kinect}]\n", "'cameras[0].name': unknown value 'kinect' (allowed: one of "
                                              "camera_purple, camera_yellow, env_camera, CameraTop, CameraBottom)");
  expect_error("cameras: [{name: camera_purple, fps: 30}]\n", "allowed: name, rate_hz, width, height, depth, video");
  expect_error("record: {voice: robotic}\n",
               "'record.voice': unknown value 'robotic' (allowed: one of babble, espeak)");
  expect_error("record: {compression: zip}\n",
               "'record.compression': unknown value 'zip' (allowed: one of none, lz4, bz2)");
  expect_error("record: {jpeg_quality: 0}\n", "'record.jpeg_quality'");
  expect_error("record: {jpeg_quality: 0}\n", "integer in [1, 100]");
  expect_error("record: {bags: true}\n",
               "allowed: bag, jpeg_quality, png_level, chunk_kb, compression, encoder_threads, voice");
}

TEST(Scenario, VoicesComeFromTheRecorder) {
  const ScenarioVocabulary vocabulary;
  EXPECT_EQ(vocabulary.voices, std::vector<std::string>(recording::kVoiceNames.begin(), recording::kVoiceNames.end()));
  ScenarioVocabulary babble_only;
  babble_only.voices = {"babble"};
  const auto msg = error_of("name: cc\ncondition: child-child\nrecord: {voice: espeak}\n", {}, babble_only);
  EXPECT_NE(msg.find("'record.voice': unknown value 'espeak' (allowed: one of babble)"), std::string::npos) << msg;
}
