#pragma once
// The sandtray screen: its size, pixel scale, stash strip and drawing palette, as in the real QML game.

#include <array>
#include <optional>
#include <string_view>

#include "freeplay/core/geometry.hpp"

namespace freeplay::sim {

/// Physical width of the active area (m), `physicalMapWidth` of the real game.
inline constexpr double kScreenWidthM = 0.600;
/// Physical height of the active area (m), `MAP_HEIGHT` of the real planner and play policy.
inline constexpr double kScreenHeightM = 0.335;
/// Screen width in pixels of the real 27" touchscreen.
inline constexpr int kScreenWidthPx = 1920;
/// Metres per pixel (`pixel2meter` = 0.6 / 1920).
inline constexpr double kMetresPerPixel = kScreenWidthM / kScreenWidthPx;
/// Raster height in pixels at full resolution. Departure: the real screen has 1080 rows (0.3375 m) while all
/// the real software uses 0.335 m; we keep the metric height and use 1072 rows so raster and metres agree.
inline constexpr int kScreenHeightPx = 1072;
/// Side of the base item box (m): 2 × 1080 px × 30/600 = 108 px at 0.0003125 m/px.
inline constexpr double kItemBaseSideM = 0.03375;
/// The stash strip is the right 12 % of the screen (x >= 0.528 m).
inline constexpr double kStashFraction = 0.12;
/// Left edge of the stash strip (m).
inline constexpr double kStashMinX = kScreenWidthM * (1.0 - kStashFraction);
/// Simultaneous fingers the game tracks (`touch1` … `touch6`).
inline constexpr int kMaxTouches = 6;
/// Robot finger auto-release delay after the last `/poses` message (s).
inline constexpr double kRobotReleaseDelayS = 1.0;
/// Rate of the game's TF output (items and touches), Hz.
inline constexpr double kGameTickHz = 10.0;
/// Box2D step of the QML world (qml-box2d default timeStep), s.
inline constexpr double kPhysicsStepS = 1.0 / 60.0;
/// Minimum period between background republications (polled every 250 ms → ≤ 4 Hz), s.
inline constexpr double kBackgroundPeriodS = 0.25;
/// Drawing stroke width in pixels at 1920 px (`lineWidth 50`).
inline constexpr int kStrokeWidthPx = 50;

/// Sandtray-frame point of a full-resolution pixel position (x right, y down in pixels → y up in metres).
inline Vec2 pixel_to_sandtray(double px, double py) { return {px * kMetresPerPixel, -py * kMetresPerPixel}; }
/// Full-resolution pixel position of a sandtray-frame point.
inline Vec2 sandtray_to_pixel(const Vec2& p) { return {p.x() / kMetresPerPixel, -p.y() / kMetresPerPixel}; }
/// True when `p` lies on the active area: x in [0, 0.6], y in [−0.335, 0].
inline bool on_screen(const Vec2& p) {
  return p.x() >= 0.0 && p.x() <= kScreenWidthM && p.y() <= 0.0 && p.y() >= -kScreenHeightM;
}
/// True when `p` lies in the stash strip.
inline bool in_stash(const Vec2& p) { return on_screen(p) && p.x() >= kStashMinX; }
/// Centre of the screen in the sandtray frame (the dataset's `sandtray_centre`, rounded as there: (0.3, −0.169)).
inline Vec2 screen_centre() { return {0.3, -0.169}; }

/// The drawing palette of the real game (Tango colours) plus the eraser.
enum class PaletteColour { Yellow, Orange, Green, Black, Blue, Purple, Red, White, Eraser };

/// Every palette entry, in the order of the real ColorPicker.
inline constexpr std::array<PaletteColour, 9> kPalette = {
    PaletteColour::Yellow, PaletteColour::Orange, PaletteColour::Green,  PaletteColour::Black, PaletteColour::Blue,
    PaletteColour::Purple, PaletteColour::Red,    PaletteColour::White, PaletteColour::Eraser};

/// Lower-case name of a palette entry ("yellow", …, "eraser").
std::string_view palette_name(PaletteColour colour);
/// Palette entry from its name; nullopt when unknown.
std::optional<PaletteColour> palette_from_name(std::string_view name);
/// Comma-separated list of the palette names (for error messages).
std::string_view palette_names();
/// RGB of a palette entry (the eraser has none: returns {0, 0, 0}).
std::array<unsigned char, 3> palette_rgb(PaletteColour colour);

}  // namespace freeplay::sim
