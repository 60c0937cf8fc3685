#include "freeplay/sim/item_catalogue.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "freeplay/core/assets.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::sim {
namespace {

/// Box2D's b2_maxPolygonVertices: the most vertices one polygon fixture may have.
constexpr std::size_t kMaxPolygonVertices = 8;
/// Shortest polygon edge we accept (m): Box2D welds vertices that are closer than its linear slop.
constexpr double kMinEdgeM = 1e-4;

const char* const kItemKeys = "name, label, scale, polygon, physics, picture, colour";
const char* const kPhysicsKeys = "density, friction, restitution";

/// Reads one catalogue file and reports problems at their YAML position.
class CatalogueReader {
 public:
  explicit CatalogueReader(std::filesystem::path path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& problem,
                         const std::string& allowed = {}) const {
    SourceLocation where{path_.string(), 0, 0};
    if (node.IsDefined()) {
      const YAML::Mark mark = node.Mark();
      if (mark.line >= 0) where.line = mark.line + 1;
      if (mark.column >= 0) where.column = mark.column + 1;
    }
    throw InputError(problem, key, allowed, where);
  }

  std::vector<ItemSpec> read() const {
    YAML::Node root;
    try {
      root = YAML::LoadFile(path_.string());
    } catch (const YAML::BadFile&) {
      throw InputError("cannot open the item catalogue", "", "", {path_.string(), 0, 0});
    } catch (const YAML::ParserException& e) {
      throw InputError("YAML syntax error: " + e.msg, "", "",
                       {path_.string(), e.mark.line + 1, e.mark.column + 1});
    }
    if (!root.IsMap()) fail(root, "", "expected a map with the key 'items'");
    check_keys(root, "", {"items"}, "items");
    const YAML::Node items = root["items"];
    if (!items) fail(root, "items", "missing key");
    if (!items.IsSequence() || items.size() == 0) fail(items, "items", "expected a non-empty list of items");
    std::vector<ItemSpec> specs;
    std::set<std::string> names;
    for (std::size_t i = 0; i < items.size(); ++i) {
      const std::string key = fmt::format("items[{}]", i);
      ItemSpec spec = read_item(items[i], key);
      if (!names.insert(spec.name).second) {
        fail(items[i]["name"], key + ".name", fmt::format("duplicate item name '{}'", spec.name));
      }
      specs.push_back(std::move(spec));
    }
    return specs;
  }

 private:
  void check_keys(const YAML::Node& map, const std::string& prefix, const std::set<std::string>& allowed,
                  const char* allowed_text) const {
    for (const auto& entry : map) {
      const auto key = entry.first.as<std::string>();
      if (allowed.count(key) == 0) {
        fail(entry.first, prefix.empty() ? key : prefix + "." + key, "unknown key", allowed_text);
      }
    }
  }

  YAML::Node required(const YAML::Node& map, const std::string& prefix, const char* key) const {
    const YAML::Node node = map[key];
    if (!node) fail(map, prefix + "." + key, "missing key");
    return node;
  }

  double number(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, key, "expected a number");
    try {
      const double value = node.as<double>();
      if (!std::isfinite(value)) fail(node, key, "expected a finite number");
      return value;
    } catch (const YAML::BadConversion&) {
      fail(node, key, fmt::format("expected a number, got '{}'", node.Scalar()));
    }
  }

  std::string text(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar() || node.Scalar().empty()) fail(node, key, "expected a non-empty string");
    return node.Scalar();
  }

  ItemSpec read_item(const YAML::Node& node, const std::string& key) const {
    if (!node.IsMap()) fail(node, key, "expected a map describing one item");
    check_keys(node, key, {"name", "label", "scale", "polygon", "physics", "picture", "colour"}, kItemKeys);
    ItemSpec spec;
    spec.name = text(required(node, key, "name"), key + ".name");
    const bool valid_name =
        std::islower(static_cast<unsigned char>(spec.name.front())) != 0 &&
        std::all_of(spec.name.begin(), spec.name.end(), [](char c) {
          return std::islower(static_cast<unsigned char>(c)) != 0 || std::isdigit(static_cast<unsigned char>(c)) != 0 ||
                 c == '_';
        });
    if (!valid_name) {
      fail(node["name"], key + ".name", fmt::format("'{}' is not a valid TF frame name", spec.name),
           "lower-case letters, digits and '_', starting with a letter");
    }
    spec.label = text(required(node, key, "label"), key + ".label");
    const YAML::Node scale = required(node, key, "scale");
    spec.scale = number(scale, key + ".scale");
    if (spec.scale <= 0.0 || spec.scale > 10.0) fail(scale, key + ".scale", "out of range", "0 < scale <= 10");
    spec.box_side_m = spec.scale * kItemBaseSideM;
    spec.polygon = read_polygon(required(node, key, "polygon"), key + ".polygon", spec.box_side_m);
    read_physics(required(node, key, "physics"), key + ".physics", spec);
    spec.picture = text(required(node, key, "picture"), key + ".picture");
    spec.colour = read_colour(required(node, key, "colour"), key + ".colour");
    return spec;
  }

  Polygon2 read_polygon(const YAML::Node& node, const std::string& key, double box_side_m) const {
    if (node.IsScalar()) {
      if (node.Scalar() != "octagon") fail(node, key, "expected a list of [x, y] vertices or 'octagon'");
      Polygon2 octagon;
      for (int k = 0; k < 8; ++k) {
        const double angle = k * std::numbers::pi / 4.0;
        octagon.emplace_back(0.5 * box_side_m * std::cos(angle), 0.5 * box_side_m * std::sin(angle));
      }
      return octagon;
    }
    if (!node.IsSequence()) fail(node, key, "expected a list of [x, y] vertices or 'octagon'");
    if (node.size() < 3 || node.size() > kMaxPolygonVertices) {
      fail(node, key, fmt::format("{} vertices (Box2D polygons have 3 to {})", node.size(), kMaxPolygonVertices));
    }
    Polygon2 polygon;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string vkey = fmt::format("{}[{}]", key, i);
      const YAML::Node vertex = node[i];
      if (!vertex.IsSequence() || vertex.size() != 2) fail(vertex, vkey, "expected [x, y] in metres");
      const Vec2 v(number(vertex[0], vkey + "[0]"), number(vertex[1], vkey + "[1]"));
      if (std::abs(v.x()) > box_side_m || std::abs(v.y()) > box_side_m) {
        fail(vertex, vkey, fmt::format("vertex lies far outside the item box (side {:.4f} m): metres expected",
                                       box_side_m));
      }
      polygon.push_back(v);
    }
    const std::size_t n = polygon.size();
    for (std::size_t i = 0; i < n; ++i) {
      if ((polygon[(i + 1) % n] - polygon[i]).norm() < kMinEdgeM) {
        fail(node[(i + 1) % n], fmt::format("{}[{}]", key, (i + 1) % n),
             "vertex closer than 0.1 mm to the previous one (Box2D would merge them)");
      }
    }
    int sign = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 e1 = polygon[(i + 1) % n] - polygon[i];
      const Vec2 e2 = polygon[(i + 2) % n] - polygon[(i + 1) % n];
      const double cross = e1.x() * e2.y() - e1.y() * e2.x();
      const int s = cross > 1e-12 ? 1 : (cross < -1e-12 ? -1 : 0);
      if (s == 0 || (sign != 0 && s != sign)) {
        fail(node[(i + 1) % n], fmt::format("{}[{}]", key, (i + 1) % n),
             "polygon is not strictly convex at this vertex (Box2D needs convex polygons)");
      }
      sign = s;
    }
    double turning = 0.0;  // a star polygon turns the same way at every vertex but winds more than once
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 e1 = polygon[(i + 1) % n] - polygon[i];
      const Vec2 e2 = polygon[(i + 2) % n] - polygon[(i + 1) % n];
      turning += std::atan2(e1.x() * e2.y() - e1.y() * e2.x(), e1.dot(e2));
    }
    if (std::abs(std::abs(turning) - 2.0 * std::numbers::pi) > 1e-6) {
      fail(node, key, "polygon winds around more than once (self-intersecting)");
    }
    if (sign < 0) std::reverse(polygon.begin(), polygon.end());
    return polygon;
  }

  void read_physics(const YAML::Node& node, const std::string& key, ItemSpec& spec) const {
    if (!node.IsMap()) fail(node, key, "expected a map", kPhysicsKeys);
    check_keys(node, key, {"density", "friction", "restitution"}, kPhysicsKeys);
    const YAML::Node density = required(node, key, "density");
    spec.density = number(density, key + ".density");
    if (spec.density <= 0.0) fail(density, key + ".density", "must be positive");
    const YAML::Node friction = required(node, key, "friction");
    spec.friction = number(friction, key + ".friction");
    if (spec.friction < 0.0) fail(friction, key + ".friction", "must not be negative");
    const YAML::Node restitution = required(node, key, "restitution");
    spec.restitution = number(restitution, key + ".restitution");
    if (spec.restitution < 0.0 || spec.restitution > 1.0) {
      fail(restitution, key + ".restitution", "out of range", "0 <= restitution <= 1");
    }
  }

  std::array<std::uint8_t, 3> read_colour(const YAML::Node& node, const std::string& key) const {
    if (!node.IsSequence() || node.size() != 3) fail(node, key, "expected [r, g, b] with 0…255 integers");
    std::array<std::uint8_t, 3> rgb{};
    for (std::size_t i = 0; i < 3; ++i) {
      const std::string ckey = fmt::format("{}[{}]", key, i);
      const double value = number(node[i], ckey);
      if (value < 0.0 || value > 255.0 || value != std::floor(value)) {
        fail(node[i], ckey, "expected an integer", "0…255");
      }
      rgb[i] = static_cast<std::uint8_t>(value);
    }
    return rgb;
  }

  std::filesystem::path path_;
};

}  // namespace

ItemCatalogue ItemCatalogue::load(const std::filesystem::path& path) {
  return ItemCatalogue(CatalogueReader(path).read());
}

ItemCatalogue ItemCatalogue::load_default() { return load(asset_path("items/catalogue.yaml")); }

ItemCatalogue::ItemCatalogue(std::vector<ItemSpec> items) : items_(std::move(items)) {
  std::set<std::string> names;
  for (const auto& spec : items_) {
    if (spec.name.empty()) throw InputError("item without a name", "items");
    if (!names.insert(spec.name).second) throw InputError(fmt::format("duplicate item '{}'", spec.name), "items");
    if (spec.polygon.size() < 3 || spec.polygon.size() > kMaxPolygonVertices) {
      throw InputError("polygon needs 3 to 8 vertices", spec.name + ".polygon");
    }
  }
}

const ItemSpec* ItemCatalogue::find(std::string_view name) const {
  for (const auto& spec : items_) {
    if (spec.name == name) return &spec;
  }
  return nullptr;
}

const ItemSpec& ItemCatalogue::get(std::string_view name) const { return items_[index_of(name)]; }

std::size_t ItemCatalogue::index_of(std::string_view name) const {
  for (std::size_t i = 0; i < items_.size(); ++i) {
    if (items_[i].name == name) return i;
  }
  throw InputError(fmt::format("unknown item '{}'", name), "item", names());
}

std::string ItemCatalogue::names() const {
  std::string out;
  for (const auto& spec : items_) {
    if (!out.empty()) out += ", ";
    out += spec.name;
  }
  return out;
}

}  // namespace freeplay::sim
