#pragma once
// The interactive items of the game (immutable description), loaded from assets/items/catalogue.yaml.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/core/geometry.hpp"

namespace freeplay::sim {

/// One interactive item: size, bounding polygon, physics and picture (CONTRACT: fields may be added, not renamed).
struct ItemSpec {
  std::string name;            ///< TF frame name, e.g. "zebra"
  std::string label;           ///< human-readable label drawn on the picture, e.g. "Zebra"
  double scale = 1.0;          ///< QML `scale` (box side = scale × 0.03375 m)
  double box_side_m = 0.0;     ///< side of the square item box (m)
  Polygon2 polygon;            ///< bounding polygon in the item frame (m, centred on the box centre, y up)
  double density = 1.0;        ///< Box2D fixture density (QML units)
  double friction = 1.0;       ///< Box2D fixture friction
  double restitution = 0.1;    ///< Box2D fixture restitution
  std::string picture;         ///< picture file relative to the assets folder (PNG with alpha)
  std::array<std::uint8_t, 3> colour = {128, 128, 128};  ///< dominant RGB colour (fallback drawing, legends)
};

/// The immutable set of items of a game, in catalogue order.
class ItemCatalogue {
 public:
  /// Loads and validates a catalogue YAML file; throws InputError naming file:line:column and key on bad input.
  static ItemCatalogue load(const std::filesystem::path& path);
  /// Loads `assets/items/catalogue.yaml`.
  static ItemCatalogue load_default();
  /// Builds a catalogue from already validated specs (tests, tools).
  explicit ItemCatalogue(std::vector<ItemSpec> items);

  /// All items in catalogue order.
  const std::vector<ItemSpec>& items() const { return items_; }
  /// The item called `name`; throws InputError listing the allowed names when unknown.
  const ItemSpec& get(std::string_view name) const;
  /// The item called `name`, or nullptr.
  const ItemSpec* find(std::string_view name) const;
  /// Index of `name` in catalogue order; throws InputError when unknown.
  std::size_t index_of(std::string_view name) const;
  /// Comma-separated item names (for error messages).
  std::string names() const;

 private:
  std::vector<ItemSpec> items_;
};

}  // namespace freeplay::sim
