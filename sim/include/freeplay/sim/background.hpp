#pragma once
// The game's background images (blank, free-play map, tutorial), rasterised by our code at any resolution.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

namespace freeplay::sim {

/// Which background the game shows (blank black screen, `res/map.svg`, `res/tutorial_bg.svg`).
enum class BackgroundKind { Blank, FreeplayMap, Tutorial };

/// Lower-case name of a background ("blank", "map", "tutorial").
std::string_view background_name(BackgroundKind kind);
/// Background from its name; nullopt when unknown.
std::optional<BackgroundKind> background_from_name(std::string_view name);

/// Raster height for a raster `width_px` wide: round(width × 0.335 / 0.6).
int raster_height(int width_px);

/// One filled or stroked shape of a vector map, in map units (x right, y down from the top-left corner).
struct MapShape {
  enum class Kind { Polygon, Ellipse, Polyline } kind = Kind::Polygon;  ///< what the points describe
  std::vector<cv::Point2d> points;  ///< polygon/polyline vertices; for an ellipse: {centre}
  cv::Size2d radii;                 ///< ellipse semi-axes (map units)
  double angle_deg = 0.0;           ///< ellipse rotation (degrees, clockwise on screen)
  double width = 0.0;               ///< polyline stroke width (map units); 0 for filled shapes
  bool smooth = false;              ///< polygon/polyline vertices are control points of a closed/open Catmull-Rom curve
  cv::Scalar bgr;                   ///< fill or stroke colour (B, G, R)
  std::string layer;                ///< layer name (for documentation and debugging)
};

/// An immutable vector description of a background: size in map units, base colour and shapes in paint order.
struct MapDescription {
  std::string name;                 ///< e.g. "freeplay map (June 2017)"
  cv::Size2d size;                  ///< extent in map units (the SVG viewBox: 2125.98 × 1187.01)
  cv::Scalar background_bgr;        ///< colour under every shape
  std::vector<MapShape> shapes;     ///< painted in order

  /// Loads a YAML map description; throws InputError naming file:line:column and key on bad input.
  static MapDescription load(const std::filesystem::path& path);
};

/// Rasterises a map description `width_px` wide (anti-aliased), BGR CV_8UC3, height = raster_height(width_px).
cv::Mat render_map(const MapDescription& map, int width_px);

/// Renders a background `width_px` wide: BGR CV_8UC3, height = round(width × 0.335 / 0.6); throws InputError on
/// a width outside [16, 16384]. The map comes from `assets/backgrounds/freeplay_map.yaml`.
cv::Mat render_background(BackgroundKind kind, int width_px);
/// The same image shared with every other caller (rasterised once per process): never write into it.
cv::Mat shared_background(BackgroundKind kind, int width_px);

}  // namespace freeplay::sim
