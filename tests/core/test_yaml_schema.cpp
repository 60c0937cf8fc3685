#include <gtest/gtest.h>

#include <string>

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

Example validated(const std::string& text) {
  YAML::Node node = YAML::Load(text);
  ValidationErrors errors;
  settings_schema<Example>()->validate(node, "example", "test.yaml", errors);
  errors.throw_if_any();
  return read_settings<Example>(node);
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
