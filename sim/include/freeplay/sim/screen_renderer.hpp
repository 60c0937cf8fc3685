#pragma once
// The whole sandtray screen as the children see it: background + strokes, stash, palette, items, touches, robot.

#include <memory>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "freeplay/core/geometry.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/screen.hpp"
#include "freeplay/sim/zones.hpp"

namespace freeplay::sim {

/// An item as drawn: its spec, pose in `sandtray`, stacking order and visibility.
struct ItemView {
  const ItemSpec* spec = nullptr;  ///< which item (must outlive the render call)
  Pose2 pose;                      ///< centre and θ (CCW-positive in `sandtray`, = −screen rotation)
  int z = 0;                       ///< higher is drawn on top
  bool visible = true;             ///< hidden items are skipped
};

/// What is drawn over the game besides items.
struct ScreenOverlay {
  std::vector<Vec2> touches;         ///< active fingers (dots)
  std::optional<Vec2> robot_hand;    ///< the robot's virtual finger, when it is touching
  bool stash_visible = true;         ///< the #111 stash strip on the right 12 %
  bool palette_visible = false;      ///< the drawing palette on the left edge (drawing enabled)
};

/// The item picture of `spec` as BGRA CV_8UC4, `side_px` square; loaded from the PNG `spec.picture` under the assets
/// folder when it exists and reads as a PNG (fitted into the square, aspect kept), otherwise drawn procedurally from
/// the item's name and colour.
cv::Mat item_picture(const ItemSpec& spec, int side_px);
/// Draws an item's picture procedurally (flat cartoon + label) as BGRA CV_8UC4, `side_px` square.
cv::Mat draw_item_picture(const ItemSpec& spec, int side_px);

/// Renders screen images; keeps per-width caches of the scaled item pictures (thread-safe).
class ScreenRenderer {
 public:
  /// A renderer for the items of `catalogue` (which must outlive it).
  explicit ScreenRenderer(const ItemCatalogue& catalogue);
  ~ScreenRenderer();
  ScreenRenderer(const ScreenRenderer&) = delete;
  ScreenRenderer& operator=(const ScreenRenderer&) = delete;

  /// The screen `width_px` wide (height follows the aspect): `background` (any size, resized if needed) + stash +
  /// palette + items in z order + touches + robot hand. Throws InputError on a bad width or background.
  cv::Mat render(const cv::Mat& background, const std::vector<ItemView>& items, const ScreenOverlay& overlay,
                 int width_px) const;

 private:
  struct PictureCache;
  const ItemCatalogue& catalogue_;
  std::unique_ptr<PictureCache> cache_;
};

/// Outlines every zone on `screen` (a full-screen image of any width) in its marker colour; with `labels`, writes
/// "<colour> <id>" at each centroid.
void draw_zones(cv::Mat& screen, const ZoneMap& zones, bool labels);

}  // namespace freeplay::sim
