#include "freeplay/sim/item_catalogue.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "freeplay/core/assets.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/settings_archive.hpp"
#include "freeplay/core/yaml_schema.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::sim {
namespace {

/// Box2D's b2_maxPolygonVertices: the most vertices one polygon fixture may have.
constexpr std::size_t kMaxPolygonVertices = 8;
/// Shortest polygon edge we accept (m): Box2D welds vertices that are closer than its linear slop.
constexpr double kMinEdgeM = 1e-4;
/// Bound on physics parameters and vertex coordinates in the schema: far beyond any real item, so that the checks
/// after reading (metres, not pixels) give the telling message.
constexpr double kSchemaBound = 1e6;

/// `physics:` of a catalogue entry: the Box2D fixture's parameters.
struct PhysicsEntry {
  double density = 1.0;      ///< fixture density (QML units), > 0
  double friction = 1.0;     ///< fixture friction
  double restitution = 0.1;  ///< fixture restitution

  /// The keys of `physics:`.
  template <typename Archive>
  void visit(Archive& a) {
    a.required("density", density, Schema::number(0, kSchemaBound), "Box2D fixture density (> 0, kg per (32 px)²)");
    a.required("friction", friction, Schema::number(0, kSchemaBound), "Box2D fixture friction");
    a.required("restitution", restitution, Schema::number(0, 1), "Box2D fixture restitution");
  }
};

/// What `polygon:` accepts: `octagon` or a vertex list (the vertex count, convexity and units are checked after
/// reading, with Box2D's reasons).
std::shared_ptr<const Schema> polygon_schema() {
  return Schema::one_of({Schema::enumeration({"octagon"}),
                         Schema::list(Schema::list(Schema::number(-kSchemaBound, kSchemaBound), 2, 2))},
                        "'octagon' or a list of 3 to 8 [x, y] vertices (m)");
}

/// One entry of `items:`, as the catalogue file writes it (ItemSpec is built from it and checked).
struct ItemEntry {
  std::string name;                ///< TF frame name
  std::string label;               ///< label drawn on the picture
  double scale = 1.0;              ///< the QML `scale`
  YAML::Node polygon;              ///< `octagon` or the vertex list (kept as a node: either form, and its positions)
  PhysicsEntry physics;            ///< Box2D fixture parameters
  std::string picture;             ///< picture file under assets/
  std::array<int, 3> colour{};     ///< dominant RGB colour

  /// The keys of one catalogue item.
  template <typename Archive>
  void visit(Archive& a) {
    a.required("name", name, Schema::string(), "TF frame name: lower-case letters, digits and '_'");
    a.required("label", label, Schema::string(), "label drawn on the picture");
    a.required("scale", scale, Schema::number(0, 10), "the QML `scale` (> 0): box side = scale × 0.03375 m");
    a.required("polygon", polygon, polygon_schema(), "Box2D fixture and published footprint (m, item frame)");
    a.required("physics", physics, settings_schema<PhysicsEntry>(), "Box2D fixture parameters");
    a.required("picture", picture, Schema::string(), "PNG with alpha under assets/");
    a.required("colour", colour, Schema::list(Schema::integer(0, 255), 3, 3), "dominant colour [r, g, b]");
  }
};

/// A catalogue file.
struct CatalogueFile {
  std::vector<ItemEntry> items;  ///< the items, in catalogue order

  /// The keys of a catalogue file.
  template <typename Archive>
  void visit(Archive& a) {
    a.required("items", items, Schema::list(settings_schema<ItemEntry>(), 1), "the items, in catalogue order");
  }
};

/// Builds the ItemSpecs of one validated catalogue file, checking what its schema cannot say; a problem is reported
/// at its YAML position.
class CatalogueChecker {
 public:
  explicit CatalogueChecker(std::string file) : file_(std::move(file)) {}

  /// Every item of `catalogue`, read from `root` (validated; its nodes give the positions).
  std::vector<ItemSpec> specs(const CatalogueFile& catalogue, const YAML::Node& root) const {
    std::vector<ItemSpec> specs;
    std::set<std::string> names;
    for (std::size_t i = 0; i < catalogue.items.size(); ++i) {
      const std::string key = fmt::format("items[{}]", i);
      const YAML::Node at = root["items"][i];
      ItemSpec spec = item_spec(catalogue.items[i], at, key);
      if (!names.insert(spec.name).second) {
        fail(at["name"], key + ".name", fmt::format("duplicate item name '{}'", spec.name));
      }
      specs.push_back(std::move(spec));
    }
    return specs;
  }

 private:
  /// Throws the InputError for `problem` at `node`'s position, naming `key`.
  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& problem,
                         const std::string& allowed = {}) const {
    throw InputError(problem, key, allowed, location_of(node, file_));
  }

  /// Rejects an empty string (the schema accepts any scalar).
  void require_text(const std::string& value, const YAML::Node& at, const std::string& key) const {
    if (value.empty()) fail(at, key, "expected a non-empty string");
  }

  /// The ItemSpec of `entry` (its node `at`, key path `key`): frame name, positive scale and density, polygon.
  ItemSpec item_spec(const ItemEntry& entry, const YAML::Node& at, const std::string& key) const {
    ItemSpec spec;
    spec.name = entry.name;
    require_text(spec.name, at["name"], key + ".name");
    const bool valid_name =
        std::islower(static_cast<unsigned char>(spec.name.front())) != 0 &&
        std::all_of(spec.name.begin(), spec.name.end(), [](char c) {
          return std::islower(static_cast<unsigned char>(c)) != 0 || std::isdigit(static_cast<unsigned char>(c)) != 0 ||
                 c == '_';
        });
    if (!valid_name) {
      fail(at["name"], key + ".name", fmt::format("'{}' is not a valid TF frame name", spec.name),
           "lower-case letters, digits and '_', starting with a letter");
    }
    spec.label = entry.label;
    require_text(spec.label, at["label"], key + ".label");
    spec.scale = entry.scale;
    if (spec.scale <= 0.0) fail(at["scale"], key + ".scale", "out of range", "0 < scale <= 10");
    spec.box_side_m = spec.scale * kItemBaseSideM;
    spec.polygon = polygon_of(entry.polygon, key + ".polygon", spec.box_side_m);
    spec.density = entry.physics.density;
    if (spec.density <= 0.0) fail(at["physics"]["density"], key + ".physics.density", "must be positive");
    spec.friction = entry.physics.friction;
    spec.restitution = entry.physics.restitution;
    spec.picture = entry.picture;
    require_text(spec.picture, at["picture"], key + ".picture");
    for (std::size_t i = 0; i < 3; ++i) spec.colour[i] = static_cast<std::uint8_t>(entry.colour[i]);
    return spec;
  }

  /// The polygon `node` gives (the schema let through `octagon` or a list of [x, y]), counter-clockwise.
  Polygon2 polygon_of(const YAML::Node& node, const std::string& key, double box_side_m) const {
    if (node.IsScalar()) {  // octagon
      Polygon2 octagon;
      for (int k = 0; k < 8; ++k) {
        const double angle = k * std::numbers::pi / 4.0;
        octagon.emplace_back(0.5 * box_side_m * std::cos(angle), 0.5 * box_side_m * std::sin(angle));
      }
      return octagon;
    }
    if (node.size() < 3 || node.size() > kMaxPolygonVertices) {
      fail(node, key, fmt::format("{} vertices (Box2D polygons have 3 to {})", node.size(), kMaxPolygonVertices));
    }
    Polygon2 polygon;
    for (const auto& [x, y] : node.as<std::vector<std::array<double, 2>>>()) {
      const Vec2 v(x, y);
      if (std::abs(v.x()) > box_side_m || std::abs(v.y()) > box_side_m) {
        fail(node[polygon.size()], fmt::format("{}[{}]", key, polygon.size()),
             fmt::format("vertex lies far outside the item box (side {:.4f} m): metres expected", box_side_m));
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

  std::string file_;
};

}  // namespace

ItemCatalogue ItemCatalogue::load(const std::filesystem::path& path) {
  const auto doc = load_yaml_file(path);
  YAML::Node root = doc.root;
  ValidationErrors errors;
  settings_schema<CatalogueFile>()->validate(root, "", doc.file, errors);
  errors.throw_if_any();
  return ItemCatalogue(CatalogueChecker(doc.file).specs(read_settings<CatalogueFile>(root), root));
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
