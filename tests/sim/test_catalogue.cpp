// The item catalogue: the shipped items match the real game, and bad catalogues are rejected with positions.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "freeplay/core/error.hpp"
#include "freeplay/core/geometry.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::sim {
namespace {

struct Expected {
  const char* name;
  double scale;
  double min_x, max_x, min_y, max_y;  // logged footprint extents (reference §3.3)
  std::size_t vertices;
  double density, friction, restitution;
};

// Reference §3.3: real scales, logged footprint extents, vertex counts and physics.
constexpr double kOct = 0.03375 / 2.0;
const Expected kExpected[] = {
    {"zebra", 1.0, -0.0169, 0.0132, -0.0157, 0.0168, 6, 1.0, 1.0, 0.1},
    {"elephant", 1.5, -0.0258, 0.0234, -0.0158, 0.0170, 6, 1.0, 1.0, 0.1},
    {"giraffe", 1.5, -0.0174, 0.0136, -0.0226, 0.0276, 5, 1.0, 1.0, 0.1},
    {"hippo", 1.5, -0.0239, 0.0257, -0.0142, 0.0167, 6, 1.0, 1.0, 0.1},
    {"lion", 1.0, -0.0124, 0.0156, -0.0181, 0.0147, 7, 1.0, 1.0, 0.1},
    {"crocodile", 1.0, -0.0137, 0.0172, -0.0155, 0.0174, 7, 1.0, 1.0, 0.1},
    {"caravan", 2.5, -0.0400, 0.0435, -0.0120, 0.0175, 6, 2.0, 2.0, 0.1},
    {"ball", 0.7, -0.7 * kOct, 0.7 * kOct, -0.7 * kOct, 0.7 * kOct, 8, 0.5, 0.1, 0.7},
    {"boy", 1.0, -kOct, kOct, -kOct, kOct, 8, 1.0, 1.0, 0.1},
    {"girl", 1.0, -kOct, kOct, -kOct, kOct, 8, 1.0, 1.0, 0.1},
};

TEST(ItemCatalogue, DefaultCatalogueMatchesTheRealItems) {
  const ItemCatalogue catalogue = ItemCatalogue::load_default();
  ASSERT_EQ(catalogue.items().size(), std::size(kExpected));
  for (std::size_t i = 0; i < std::size(kExpected); ++i) {
    const Expected& e = kExpected[i];
    const ItemSpec& spec = catalogue.items()[i];
    SCOPED_TRACE(e.name);
    EXPECT_EQ(spec.name, e.name);
    EXPECT_DOUBLE_EQ(spec.scale, e.scale);
    EXPECT_NEAR(spec.box_side_m, e.scale * kItemBaseSideM, 1e-12);
    EXPECT_EQ(spec.polygon.size(), e.vertices);
    const auto [lo, hi] = bounds(spec.polygon);
    EXPECT_NEAR(lo.x(), e.min_x, 1e-4);
    EXPECT_NEAR(hi.x(), e.max_x, 1e-4);
    EXPECT_NEAR(lo.y(), e.min_y, 1e-4);
    EXPECT_NEAR(hi.y(), e.max_y, 1e-4);
    EXPECT_GT(signed_area(spec.polygon), 0.0) << "polygons are stored counter-clockwise";
    EXPECT_DOUBLE_EQ(spec.density, e.density);
    EXPECT_DOUBLE_EQ(spec.friction, e.friction);
    EXPECT_DOUBLE_EQ(spec.restitution, e.restitution);
    EXPECT_EQ(spec.picture, std::string("items/") + e.name + ".png");
    EXPECT_FALSE(spec.label.empty());
  }
  EXPECT_NEAR(catalogue.get("boy").polygon[0].x(), 0.016875, 1e-12) << "octagon radius = box / 2";
}

TEST(ItemCatalogue, LookupsNameTheAllowedItems) {
  const ItemCatalogue catalogue = ItemCatalogue::load_default();
  EXPECT_EQ(catalogue.index_of("caravan"), 6U);
  EXPECT_EQ(catalogue.find("unicorn"), nullptr);
  try {
    (void)catalogue.get("unicorn");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unicorn"), std::string::npos);
    EXPECT_NE(e.allowed().find("zebra, elephant"), std::string::npos);
  }
}

class CatalogueFileTest : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() /
                      ("freeplay_catalogue_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                       "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".yaml");
    std::ofstream(path) << text;
    paths_.push_back(path);
    return path;
  }
  void TearDown() override {
    for (const auto& p : paths_) std::filesystem::remove(p);
  }

  /// Loads `text` and returns the error (fails the test when none is thrown).
  InputError error_of(const std::string& text) {
    const auto path = write(text);
    try {
      (void)ItemCatalogue::load(path);
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, path.string());
      EXPECT_NE(std::string(e.what()).find(path.string() + ":"), std::string::npos) << e.what();
      return e;
    }
    ADD_FAILURE() << "no InputError for:\n" << text;
    return InputError("none");
  }

  std::vector<std::filesystem::path> paths_;
};

const char* const kGoodItem =
    "items:\n"
    "  - name: zebra\n"
    "    label: Zebra\n"
    "    scale: 1.0\n"
    "    polygon: octagon\n"
    "    physics: {density: 1.0, friction: 1.0, restitution: 0.1}\n"
    "    picture: items/zebra.png\n"
    "    colour: [1, 2, 3]\n";

std::string with(const std::string& from, const std::string& to) {
  std::string text = kGoodItem;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos);
  text.replace(at, from.size(), to);
  return text;
}

TEST_F(CatalogueFileTest, AcceptsAMinimalItem) {
  const auto catalogue = ItemCatalogue::load(write(kGoodItem));
  ASSERT_EQ(catalogue.items().size(), 1U);
  EXPECT_EQ(catalogue.items()[0].colour[2], 3);
}

TEST_F(CatalogueFileTest, UnknownKeyNamesLineColumnAndKeyPath) {
  const InputError e = error_of(with("    colour: [1, 2, 3]\n", "    colour: [1, 2, 3]\n    colour_name: red\n"));
  EXPECT_EQ(e.key(), "items[0].colour_name");
  EXPECT_EQ(e.where().line, 9);
  EXPECT_EQ(e.where().column, 5);
  EXPECT_NE(e.allowed().find("polygon"), std::string::npos);
}

TEST_F(CatalogueFileTest, WrongTypeIsRejected) {
  const InputError e = error_of(with("scale: 1.0", "scale: big"));
  EXPECT_EQ(e.key(), "items[0].scale");
  EXPECT_EQ(e.where().line, 4);
  EXPECT_EQ(e.where().column, 12);
  EXPECT_EQ(error_of(with("label: Zebra", "label: [a, b]")).key(), "items[0].label");
  EXPECT_EQ(error_of(with("colour: [1, 2, 3]", "colour: [1, 2, 300]")).key(), "items[0].colour[2]");
  EXPECT_EQ(error_of(with("restitution: 0.1", "restitution: 1.5")).key(), "items[0].physics.restitution");
}

TEST_F(CatalogueFileTest, AMisspeltKeyIsReportedWithTheKeyItLeavesMissing) {
  // Every problem the schema finds is reported at once, each with its position.
  const auto path = write(with("density: 1.0", "densty: 1.0"));
  try {
    (void)ItemCatalogue::load(path);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "items[0].physics.densty");
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string() + ":6:15: 'items[0].physics.densty': unknown key"), std::string::npos)
        << message;
    EXPECT_NE(message.find(path.string() + ":6:14: 'items[0].physics.density': missing required key"),
              std::string::npos)
        << message;
  }
}

TEST_F(CatalogueFileTest, MissingKeyIsNamed) {
  EXPECT_EQ(error_of(with("    picture: items/zebra.png\n", "")).key(), "items[0].picture");
}

TEST_F(CatalogueFileTest, NonConvexPolygonIsRejectedAtTheVertex) {
  const InputError e = error_of(with(
      "polygon: octagon",
      "polygon: [[-0.01, -0.01], [0.01, -0.01], [0.0, -0.005], [0.01, 0.01], [-0.01, 0.01]]"));
  EXPECT_EQ(e.key().rfind("items[0].polygon[", 0), 0U) << e.key();
  EXPECT_NE(e.problem().find("convex"), std::string::npos);
  EXPECT_EQ(e.where().line, 5);
}

TEST_F(CatalogueFileTest, StarPolygonIsRejected) {
  std::string star = "polygon: [";
  for (int k = 0; k < 5; ++k) {
    const double a = k * 4.0 * std::numbers::pi / 5.0;
    star += fmt::format("[{}, {}]", 0.01 * std::cos(a), 0.01 * std::sin(a));
    star += k < 4 ? ", " : "]";
  }
  EXPECT_EQ(error_of(with("polygon: octagon", star)).key(), "items[0].polygon");
}

TEST_F(CatalogueFileTest, TooManyVerticesForBox2DIsRejected) {
  std::string nine = "polygon: [";
  for (int k = 0; k < 9; ++k) {
    const double a = k * 2.0 * std::numbers::pi / 9.0;
    nine += fmt::format("[{}, {}]", 0.01 * std::cos(a), 0.01 * std::sin(a));
    nine += k < 8 ? ", " : "]";
  }
  const InputError e = error_of(with("polygon: octagon", nine));
  EXPECT_EQ(e.key(), "items[0].polygon");
  EXPECT_NE(e.problem().find("9 vertices"), std::string::npos);
}

TEST_F(CatalogueFileTest, PixelUnitsAreRejected) {
  EXPECT_EQ(error_of(with("polygon: octagon", "polygon: [[-50, -50], [50, -50], [0, 50]]")).key(),
            "items[0].polygon[0]");
}

TEST_F(CatalogueFileTest, DuplicateNamesAreRejected) {
  std::string text = kGoodItem;
  text += std::string(kGoodItem).substr(std::string("items:\n").size());
  const InputError e = error_of(text);
  EXPECT_EQ(e.key(), "items[1].name");
  EXPECT_EQ(e.where().line, 9);
  EXPECT_NE(e.problem().find("duplicate"), std::string::npos);
}

TEST_F(CatalogueFileTest, BadValuesAreNamedAtTheirPosition) {
  struct Case {
    const char* from;
    const char* to;
    const char* key;
    int line;
    int column;
  };
  const Case cases[] = {
      {"name: zebra", "name: Zebra", "items[0].name", 2, 11},            // not a TF frame name
      {"label: Zebra", "label: ''", "items[0].label", 3, 12},            // empty
      {"scale: 1.0", "scale: 0", "items[0].scale", 4, 12},               // not > 0
      {"scale: 1.0", "scale: 11", "items[0].scale", 4, 12},              // above 10
      {"polygon: octagon", "polygon: hexagon", "items[0].polygon", 5, 14},
      {"polygon: octagon", "polygon: [[0, 0, 0], [0.01, 0], [0, 0.01]]", "items[0].polygon[0]", 5, 15},
      {"density: 1.0", "density: 0", "items[0].physics.density", 6, 24},
      {"friction: 1.0", "friction: -1", "items[0].physics.friction", 6, 39},
      {"picture: items/zebra.png", "picture: ''", "items[0].picture", 7, 14},
      {"colour: [1, 2, 3]", "colour: [1, 2]", "items[0].colour", 8, 13},
      {"colour: [1, 2, 3]", "colour: [1, 2.5, 3]", "items[0].colour[1]", 8, 17},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    const InputError e = error_of(with(c.from, c.to));
    EXPECT_EQ(e.key(), c.key);
    EXPECT_EQ(e.where().line, c.line);
    EXPECT_EQ(e.where().column, c.column);
  }
}

TEST_F(CatalogueFileTest, AFileWithoutItemsIsNamed) {
  EXPECT_EQ(error_of("items: []\n").key(), "items");
  EXPECT_EQ(error_of("{}\n").key(), "items");
  EXPECT_EQ(error_of("- zebra\n").where().line, 1);
}

TEST_F(CatalogueFileTest, SyntaxErrorsHaveAPosition) {
  const InputError e = error_of("items:\n  - name: [zebra\n");
  EXPECT_GT(e.where().line, 0);
}

TEST_F(CatalogueFileTest, MissingFileIsInputError) {
  EXPECT_THROW((void)ItemCatalogue::load("/nonexistent/catalogue.yaml"), InputError);
}

}  // namespace
}  // namespace freeplay::sim
