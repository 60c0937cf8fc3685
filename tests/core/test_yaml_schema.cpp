#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "freeplay/core/settings_archive.hpp"
#include "freeplay/core/yaml_schema.hpp"

using namespace freeplay;

namespace {

/// A settings struct as every subsystem writes one: members with their defaults, and the list of keys.
struct Example {
  double rate = 0.98;
  int count = 3;
  bool on = false;
  std::string mode = "fast";
  std::optional<int> age;

  template <typename Archive>
  void visit(Archive& a) {
    a.field("rate", rate, Schema::number(0, 1));
    a.field("count", count, Schema::integer(0, 10));
    a.field("on", on, Schema::boolean());
    a.field("mode", mode, Schema::enumeration({"fast", "pretty"}));
    a.optional("age", age, Schema::integer(4, 8));
  }
};

/// `text` validated against the schema of `Settings` (under the key `path`) and read.
template <typename Settings = Example>
Settings validated(const std::string& text, const std::string& path = "example") {
  YAML::Node node = YAML::Load(text);
  ValidationErrors errors;
  settings_schema<Settings>()->validate(node, path, "test.yaml", errors);
  errors.throw_if_any();
  return read_settings<Settings>(node);
}

}  // namespace

TEST(SettingsArchive, AnEmptyMapGetsTheStructsDefaults) {
  const Example e = validated("{}");
  EXPECT_DOUBLE_EQ(e.rate, 0.98);
  EXPECT_EQ(e.count, 3);
  EXPECT_FALSE(e.on);
  EXPECT_EQ(e.mode, "fast");
  EXPECT_FALSE(e.age.has_value());
}

TEST(SettingsArchive, ReadsEveryKeyAndValidatesRanges) {
  const Example e = validated("{rate: 0.5, count: 7, on: true, mode: pretty, age: 5}");
  EXPECT_DOUBLE_EQ(e.rate, 0.5);
  EXPECT_EQ(e.count, 7);
  EXPECT_TRUE(e.on);
  EXPECT_EQ(e.mode, "pretty");
  EXPECT_EQ(e.age, 5);
  try {
    validated("{count: 11}");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), "test.yaml:1:9: 'example.count': 11 is out of range (allowed: an integer in [0, 10])");
  }
}

TEST(SettingsArchive, AnUnvalidatedNodeIsValidatedUnderItsPathThenRead) {
  EXPECT_EQ(read_unvalidated_settings<Example>(YAML::Node(), "params").count, 3);  // absent: every default
  EXPECT_EQ(read_unvalidated_settings<Example>(YAML::Load("~"), "params").mode, "fast");
  const YAML::Node given = YAML::Load("{count: 7}");
  EXPECT_EQ(read_unvalidated_settings<Example>(given, "params").count, 7);
  EXPECT_FALSE(given["rate"].IsDefined());  // the defaults go into a copy, not into the caller's node
  try {
    read_unvalidated_settings<Example>(YAML::Load("{count: 11, on: maybe}"), "robot.params");
    FAIL() << "no error";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'robot.params.count': 11 is out of range (allowed: an integer in [0, 10])"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("'robot.params.on'"), std::string::npos) << message;
  }
}

TEST(SettingsArchive, DefaultsAreWrittenAsTheShortestText) {
  EXPECT_EQ(default_yaml_text(0.98), "0.98");
  EXPECT_EQ(default_yaml_text(5.0), "5");
  EXPECT_EQ(default_yaml_text(true), "true");
  EXPECT_EQ(default_yaml_text(YAML::Node(YAML::NodeType::Map)), "{}");
}

TEST(YamlSchema, AKeyThatIsNotANameIsAnInputError) {
  YAML::Node node = YAML::Load("? [1, 2]\n: 3\n");
  ValidationErrors errors;
  settings_schema<Example>()->validate(node, "", "test.yaml", errors);
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors.message().find("test.yaml:1:3: a key must be a name, found a list"), std::string::npos)
      << errors.message();
}

TEST(YamlSchema, AKeyGivenTwiceIsAnInputErrorNamingBothLines) {
  // yaml-cpp keeps both and answers with the first, so the second would be ignored without a word.
  YAML::Node node = YAML::Load("rate: 0.5\ncount: 2\nrate: 0.7\n");
  ValidationErrors errors;
  settings_schema<Example>()->validate(node, "", "test.yaml", errors);
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors.message().find("test.yaml:3:1: 'rate': key 'rate' appears twice (first at line 1) (allowed: each "
                                  "key once)"),
            std::string::npos)
      << errors.message();
}

TEST(YamlSchema, AnOverrideIndexTooLargeForAnIntegerIsAnInputError) {
  YAML::Node root = YAML::Load("cameras: [{name: a}]");
  EXPECT_THROW(apply_override(root, "cameras.99999999999999999999.rate=1"), InputError);
  EXPECT_THROW(apply_override(root, "cameras[1].rate=1"), InputError);
  apply_override(root, "cameras[0].rate=2");
  EXPECT_EQ(root["cameras"][0]["rate"].as<int>(), 2);
}

TEST(YamlSchema, AnUnknownAliasIsASyntaxErrorWithItsLine) {
  try {
    parse_yaml("a: 1\nb: *nothing\n", "x.yaml");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.where().line, 2);
    EXPECT_NE(std::string(error.what()).find("x.yaml:2:"), std::string::npos) << error.what();
  }
}

TEST(YamlSchema, AFolderIsNotAFile) {
  EXPECT_THROW(load_yaml_file(::testing::TempDir()), InputError);
}

TEST(YamlSchema, AnAllowedNameEndingInAStarAcceptsItsPrefix) {
  const auto schema = Schema::enumeration({"idle", "python:*"});
  const auto check = [&](const std::string& value) {
    ValidationErrors errors;
    schema->validate(YAML::Node(value), "robot.policy", "test.yaml", errors);
    return errors.empty();
  };
  EXPECT_TRUE(check("idle"));
  EXPECT_TRUE(check("python:module:Class"));
  EXPECT_FALSE(check("python"));
  EXPECT_FALSE(check("pyth"));
  EXPECT_FALSE(check("idle2"));
}

namespace {

/// An enum as a library declares one for a settings key: its names next to it, found by argument-dependent lookup.
enum class Shade { light, dark };
constexpr std::string_view to_string(Shade shade) { return shade == Shade::dark ? "dark" : "light"; }
constexpr bool from_string(std::string_view text, Shade& shade) {
  return enum_from_string(text, {Shade::light, Shade::dark}, shade);
}

/// A settings struct with an enum member and an optional one (absent: nullopt, as `rendering.backend`).
struct Shaded {
  Shade shade = Shade::dark;
  std::optional<Shade> border;

  template <typename Archive>
  void visit(Archive& a) {
    a.field("shade", shade, Schema::enumeration(enum_names({Shade::light, Shade::dark})));
    a.optional("border", border, Schema::enumeration(enum_names({Shade::light, Shade::dark})));
  }
};

}  // namespace

TEST(SettingsArchive, EnumMembersAreReadAndWrittenByTheirNames) {
  EXPECT_EQ(default_yaml_text(Shade::dark), "dark");
  EXPECT_EQ(enum_names({Shade::dark, Shade::light}), (std::vector<std::string>{"dark", "light"}));
  EXPECT_EQ(validated<Shaded>("{}", "shaded").shade, Shade::dark);
  EXPECT_EQ(validated<Shaded>("{shade: light}", "shaded").shade, Shade::light);
  Shade unchanged = Shade::light;
  EXPECT_FALSE(from_string("grey", unchanged));
  EXPECT_EQ(unchanged, Shade::light);
  try {
    validated<Shaded>("{shade: grey}", "shaded");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "test.yaml:1:9: 'shaded.shade': unknown value 'grey' (allowed: one of light, dark)");
  }
}

namespace {

/// A settings struct used as a list element and as an optional nested block.
struct Waypoint {
  double x = 0.0;
  std::string label = "here";

  template <typename Archive>
  void visit(Archive& a) {
    a.required("x", x, Schema::number(-1, 1));
    a.field("label", label, Schema::string());
  }
};

/// A settings struct holding a list of settings structs and optional nested ones.
struct Route {
  std::vector<Waypoint> stops;
  std::optional<Waypoint> detour;
  std::optional<std::vector<Waypoint>> extras;
  std::vector<std::string> tags = {"default"};
  std::array<double, 2> at{};

  template <typename Archive>
  void visit(Archive& a) {
    a.optional("stops", stops, Schema::list(settings_schema<Waypoint>()));
    a.optional("detour", detour, settings_schema<Waypoint>());
    a.optional("extras", extras, Schema::list(settings_schema<Waypoint>()));
    a.optional("tags", tags, Schema::list(Schema::string()));
    a.optional("at", at, Schema::list(Schema::number(-1, 1), 2, 2));
  }
};

}  // namespace

TEST(SettingsArchive, ListsOfSettingsStructsAreReadElementByElementWithTheirDefaults) {
  const Route route = validated<Route>("{stops: [{x: 0.5}, {x: -1, label: start}], tags: [a, b]}", "route");
  ASSERT_EQ(route.stops.size(), 2u);
  EXPECT_DOUBLE_EQ(route.stops[0].x, 0.5);
  EXPECT_EQ(route.stops[0].label, "here");  // the element's default
  EXPECT_DOUBLE_EQ(route.stops[1].x, -1.0);
  EXPECT_EQ(route.stops[1].label, "start");
  EXPECT_EQ(route.tags, (std::vector<std::string>{"a", "b"}));
  EXPECT_FALSE(route.detour.has_value());
  EXPECT_FALSE(route.extras.has_value());
  EXPECT_TRUE(validated<Route>("{}", "route").stops.empty());
  EXPECT_EQ(validated<Route>("{}", "route").tags, (std::vector<std::string>{"default"}));  // absent: the initialiser
}

TEST(SettingsArchive, OptionalSettingsStructsAreReadWhenGiven) {
  const Route route = validated<Route>("{detour: {x: 0.25}, extras: []}", "route");
  ASSERT_TRUE(route.detour.has_value());
  EXPECT_DOUBLE_EQ(route.detour->x, 0.25);
  EXPECT_EQ(route.detour->label, "here");
  ASSERT_TRUE(route.extras.has_value());  // given, though empty
  EXPECT_TRUE(route.extras->empty());
  EXPECT_EQ(validated<Route>("{extras: [{x: 1}]}", "route").extras->at(0).x, 1.0);
}

TEST(SettingsArchive, AProblemInAListElementNamesItsIndexAndPosition) {
  try {
    validated<Route>("stops:\n  - {x: 0}\n  - {x: 2}\n", "route");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "test.yaml:3:9: 'route.stops[1].x': 2 is out of range (allowed: a number in [-1, 1])");
  }
  try {
    validated<Route>("detour: {label: x}\n", "route");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "route.detour.x");
    EXPECT_EQ(error.where().line, 1);
  }
}

TEST(SettingsArchive, AStdArrayWithAListSchemaIsAFixedLengthList) {
  const Route route = validated<Route>("{at: [0.5, -0.25]}", "route");
  EXPECT_EQ(route.at, (std::array<double, 2>{0.5, -0.25}));
  EXPECT_THROW(validated<Route>("{at: [0.5]}", "route"), InputError);
}

TEST(SettingsArchive, ListsAndOptionalStructsAreWrittenBackToTheSameValues) {
  const Route route =
      validated<Route>("{stops: [{x: 0.5}, {x: -1, label: start}], detour: {x: 0.25}, extras: [], at: [0.5, -0.25]}",
                       "route");
  const Route again = validated<Route>(write_settings(route), "route");
  ASSERT_EQ(again.stops.size(), 2u);
  EXPECT_EQ(again.stops[1].label, "start");
  EXPECT_DOUBLE_EQ(again.stops[0].x, 0.5);
  ASSERT_TRUE(again.detour.has_value());
  EXPECT_DOUBLE_EQ(again.detour->x, 0.25);
  ASSERT_TRUE(again.extras.has_value());
  EXPECT_TRUE(again.extras->empty());
  EXPECT_EQ(again.tags, route.tags);
  EXPECT_EQ(again.at, route.at);
}

TEST(SettingsArchive, OptionalEnumMembersAreReadByTheirNames) {
  EXPECT_FALSE(validated<Shaded>("{}").border.has_value());
  const Shaded given = validated<Shaded>("{shade: light, border: dark}");
  EXPECT_EQ(given.shade, Shade::light);
  EXPECT_EQ(given.border, Shade::dark);
  EXPECT_EQ(validated<Shaded>("{border: light}").border, Shade::light);
  try {
    validated<Shaded>("{border: grey}");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "test.yaml:1:10: 'example.border': unknown value 'grey' (allowed: one of light, dark)");
  }
  // Read without validation, a name that is none of the enum's is still refused (the reader's own check).
  EXPECT_THROW(read_settings<Shaded>(YAML::Load("{shade: dark, border: grey}")), std::invalid_argument);
  // Written back by name through the same list, and left out when empty.
  EXPECT_EQ(write_settings(given), "shade: light\nborder: dark");
  EXPECT_EQ(write_settings(Shaded{}), "shade: dark");
}
