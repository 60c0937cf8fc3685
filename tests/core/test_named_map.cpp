#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/core/settings_archive.hpp"
#include "freeplay/core/yaml_schema.hpp"

using namespace freeplay;

namespace {

const std::vector<std::string> kColours = {"red", "green", "blue"};

/// A settings struct with a value per name (all names required), a partial one, a map of maps and a section.
struct PerName {
  std::array<double, 4> weight{9, 9, 9, 9};      // element 3 has no name
  std::array<double, 3> bonus{7, 7, 7};          // names are optional: an absent one reads as 0
  std::array<std::array<double, 3>, 3> mix{};    // a row per colour, partial rows
  std::optional<int> level;
  int depth = 2;

  template <typename Archive>
  void visit(Archive& a) {
    a.required("weight", weight, named_map(kColours, Schema::number(0, 10), KeyCoverage::All));
    a.required("bonus", bonus, named_map(kColours, Schema::number(-1, 1), KeyCoverage::Some));
    a.optional("mix", mix,
               named_map(kColours, named_map(kColours, Schema::number(0, 1), KeyCoverage::Some), KeyCoverage::Some));
    a.optional("level", level, Schema::integer(0, 5));
    a.section("deep", [this](auto& nested) { nested.field("depth", depth, Schema::integer(0, 9)); });
  }
};

/// `text` validated against the schema of PerName and read; the problems when it is not valid.
PerName read(const std::string& text) {
  YAML::Node node = YAML::Load(text);
  ValidationErrors errors;
  settings_schema<PerName>()->validate(node, "colours", "test.yaml", errors);
  errors.throw_if_any();
  return read_settings<PerName>(node);
}

/// The message of the InputError reading `text` throws.
std::string problem(const std::string& text) {
  try {
    (void)read(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(NamedMap, IsAMapSchemaWithOneKeyPerNameInOrder) {
  const auto all = named_map(kColours, Schema::number(0, 1), KeyCoverage::All);
  ASSERT_EQ(all->kind(), Schema::Kind::Map);
  ASSERT_EQ(all->fields().size(), 3U);
  EXPECT_EQ(all->fields()[2].key, "blue");
  EXPECT_TRUE(all->fields()[0].required);
  EXPECT_EQ(all->describe(), "a map with keys red, green, blue");
  const auto some = named_map(kColours, Schema::number(0, 1), KeyCoverage::Some);
  EXPECT_FALSE(some->fields()[0].required);
  EXPECT_FALSE(some->fields()[0].fallback.has_value());
}

TEST(NamedMap, ReadsAStdArrayElementByName) {
  const PerName p = read("{weight: {blue: 3, red: 1, green: 2}, bonus: {green: 0.5}, mix: {red: {blue: 0.25}},"
                         " deep: {depth: 4}}");
  EXPECT_EQ(p.weight, (std::array<double, 4>{1, 2, 3, 9}));  // an element without a name keeps its value
  EXPECT_EQ(p.bonus, (std::array<double, 3>{0, 0.5, 0}));    // absent names read as zero, not as the default
  EXPECT_EQ(p.mix[0], (std::array<double, 3>{0, 0, 0.25}));
  EXPECT_EQ(p.mix[1], (std::array<double, 3>{}));
  EXPECT_FALSE(p.level.has_value());
  EXPECT_EQ(p.depth, 4);
}

TEST(NamedMap, ProblemsNameTheKeyPathAndTheAllowedValues) {
  EXPECT_EQ(problem("{weight: {red: 1, green: 2}, bonus: {}, deep: {}}"),
            "test.yaml:1:10: 'colours.weight.blue': missing required key 'blue' (allowed: a number in [0, 10])");
  EXPECT_EQ(problem("{weight: {red: 1, green: 2, blue: 3, pink: 4}, bonus: {}, deep: {}}"),
            "test.yaml:1:38: 'colours.weight.pink': unknown key 'pink' (allowed: red, green, blue)");
  EXPECT_EQ(problem("{weight: {red: 1, green: 2, blue: 3}, bonus: {red: 2}, deep: {}}"),
            "test.yaml:1:52: 'colours.bonus.red': 2 is out of range (allowed: a number in [-1, 1])");
  EXPECT_EQ(problem("{weight: {red: 1, green: 2, blue: x}, bonus: {}, deep: {}}"),
            "test.yaml:1:35: 'colours.weight.blue': expected a finite number, found 'x' (allowed: a number in [0, 10])");
  EXPECT_NE(problem("{weight: {red: 1, green: 2, blue: 3}, bonus: {}}").find("missing required key 'deep'"),
            std::string::npos);
}

TEST(NamedMap, WritesThroughTheSameListAndReadsBackTheSameValues) {
  PerName p = read("{weight: {red: 1.5, green: 0, blue: 0.1}, bonus: {blue: -0.3}, mix: {green: {red: 0.5}},"
                   " deep: {depth: 4}}");
  const std::string text = write_settings(p);
  EXPECT_EQ(text,
            "weight: {red: 1.5, green: 0, blue: 0.1}\n"  // required names are written even when zero
            "bonus: {blue: -0.3}\n"                       // zero under an optional name is left out
            "mix:\n"
            "  green: {red: 0.5}\n"
            "deep:\n"
            "  depth: 4");
  const PerName q = read(text);
  EXPECT_EQ(q.weight, p.weight);
  EXPECT_EQ(q.bonus, p.bonus);
  EXPECT_EQ(q.mix, p.mix);
  EXPECT_EQ(q.depth, p.depth);
  p.level = 3;
  EXPECT_NE(write_settings(p).find("level: 3\n"), std::string::npos);  // an optional that holds a value
}
