#pragma once
// The simulated sandtray: the real QML free-play game (items, touches, robot finger, drawing, zones, states).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "freeplay/core/event_log.hpp"
#include "freeplay/core/frames.hpp"
#include "freeplay/core/geometry.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::sim {

class ItemCatalogue;
class ZoneMap;
struct ZoneSegmenterCounters;

/// Box2D length units per metre inside the sandtray world: the real game's qml-box2d scale (32 px per unit at
/// 0.0003125 m/px = 1 cm per unit), so items are 2.4–8.4 units, inside Box2D's tuned 0.1–10 range.
inline constexpr double kPhysicsUnitsPerMetre = 100.0;
/// Box2D length units per metre of the real QML world (pixelsPerMeter 32 at 1920 px), for unit conversions.
inline constexpr double kQmlUnitsPerMetre = 1.0 / (32.0 * kMetresPerPixel);

/// The game's global states (QML `globalstates`) and their trigger signals.
enum class GameState { Blank, Tutorial, FreePlay, ItemsPlacement };

/// The Empty signals of `sandtray/signals/*` that the game reacts to.
enum class Signal { BlankInterface, StartTutorial, StartFreeplay, StartItemsPlacement, ClearDrawing, ShuffleItems,
                    ItemsToStash };

/// Lower-case name of a state ("blank", "tutorial", "freeplay", "items_placement").
std::string_view game_state_name(GameState state);
/// The topic suffix of a signal (`sandtray/signals/<name>`, e.g. "start_freeplay", "clear_drawing").
std::string_view signal_name(Signal s);
/// Signal from its topic suffix; nullopt when unknown.
std::optional<Signal> signal_from_name(std::string_view name);
/// Comma-separated signal names (for error messages).
std::string signal_names();

/// Who is holding an item.
struct Holder {
  enum class Kind { None, Finger, Robot } kind = Kind::None;  ///< nobody, a child's finger, the robot finger
  int finger = 0;                                              ///< 1…6 when kind == Finger

  /// Holders are equal when they are the same kind and finger.
  bool operator==(const Holder&) const = default;
};

/// What a press did.
enum class TouchOutcome { GrabbedItem, StartedStroke, Ignored };

/// An item's public state as the game publishes it.
struct ItemState {
  std::string name;    ///< TF frame name, e.g. "zebra"
  Pose2 pose;          ///< item centre in `sandtray`, θ = −screen rotation
  int z = 0;           ///< stacking order (higher is on top)
  bool visible = true; ///< hidden items (tutorial) still publish TF but cannot be touched
  Holder holder;       ///< who drags it now (a finger before the robot when both do)
  std::vector<Holder> holders;  ///< everyone dragging it (fingers ascending, then the robot); both joints act
};

/// An active finger (`touch1` … `touch6`).
struct TouchState {
  int finger = 0;        ///< 1…6
  Vec2 position;         ///< sandtray frame
  std::string item;      ///< item being moved, empty when drawing
};

/// Tunable parameters of a sandtray (defaults = the real game).
struct SandtrayConfig {
  double linear_damping = 5.0;         ///< Box2D body damping
  double angular_damping = 5.0;        ///< Box2D body damping
  double joint_frequency_hz = 5.0;     ///< mouse-joint stiffness (qml-box2d default)
  double joint_damping_ratio = 1.0;    ///< mouse-joint damping ratio
  double joint_max_force_per_kg = 500; ///< maxForce = mass × this (in the game's units)
  bool item_collisions = true;         ///< items collide with each other
  int raster_width_px = kScreenWidthPx;///< background raster width (height follows the aspect)
};

/// The simulated game. Deterministic: same construction seed + same inputs → same state hash.
class Sandtray {
 public:
  /// Builds the game in the Blank state with every catalogue item in the stash, drawn from `rng`.
  Sandtray(std::shared_ptr<const ItemCatalogue> catalogue, SandtrayConfig config, Rng rng);
  ~Sandtray();
  Sandtray(const Sandtray&) = delete;
  Sandtray& operator=(const Sandtray&) = delete;

  // --- state machine and signals ---------------------------------------------------------------------------
  /// Applies a signal (state change or action) as the real game does.
  void signal(Signal s);
  /// Current global state.
  GameState state() const;

  // --- children's fingers (throw InputError and change nothing on bad input) --------------------------------
  /// Finger `finger` (1…6) presses at `p`: grabs the top-most item under it or starts a stroke.
  TouchOutcome touch_down(int finger, const Vec2& p);
  /// Finger `finger` moves to `p`.
  void touch_move(int finger, const Vec2& p);
  /// Finger `finger` lifts: detaches its item or ends its stroke.
  void touch_up(int finger);
  /// Selects the global brush colour, as a tap on the palette swatch does.
  void select_colour(PaletteColour colour);
  /// Selects the brush colour by name ("yellow", …, "eraser"); throws InputError listing the palette names.
  void select_colour(std::string_view colour_name);
  /// The current brush colour (the real game starts with no swatch selected, which erases).
  PaletteColour colour() const;
  /// True when a press on the background starts a stroke (free-play state).
  bool drawing_enabled() const;

  // --- the robot's virtual finger (`/poses`) ----------------------------------------------------------------
  /// One `/poses` message: grabs the item under the first pose of a stream, then drags it.
  void robot_pose(const Vec2& p);
  /// The item the robot finger holds now, if any.
  std::optional<std::string> robot_item() const;
  /// Where the robot's hand sprite is shown (last pose, until the 1 s release timer expires).
  std::optional<Vec2> robot_hand() const;

  // --- setup only (tools and tests; not a game action, nothing in the real game does this) ---------------------
  /// Teleports `name` to `pose` at rest (a layout for tools and tests); throws InputError, changing nothing, for an
  /// unknown item, a non-finite pose, a centre off the screen or an item someone holds.
  void place_item(const std::string& name, const Pose2& pose);

  // --- time ---------------------------------------------------------------------------------------------------
  /// Advances the game by `dt` seconds (physics at 60 Hz substeps, timers, background republication).
  void step(double dt);
  /// Simulated time since construction (s).
  double time() const;
  /// Number of whole 10 Hz game ticks elapsed: the episode loop publishes items/touches when it changes.
  std::int64_t tick_count() const;
  /// Number of b2World::Step calls made so far (an idle, all-asleep tray takes none).
  std::uint64_t physics_steps() const;
  /// Number of calls so far that may have changed an item's state (signals, touches, robot poses, placements,
  /// steps): while it stays the same, `items()` answers the same.
  std::uint64_t input_count() const;
  /// True when no item body is awake (the next physics steps will be skipped).
  bool asleep() const;

  // --- state out --------------------------------------------------------------------------------------------
  /// Every item's state, in catalogue order.
  std::vector<ItemState> items() const;
  /// The same into `out`, reusing its storage (no allocation once `out` has held a snapshot: for the 10 Hz tick).
  void items(std::vector<ItemState>& out) const;
  /// One item's state; throws InputError naming the allowed items when unknown.
  ItemState item(const std::string& name) const;
  /// Active fingers.
  std::vector<TouchState> touches() const;
  /// The same into `out`, reusing its storage (for the 10 Hz tick).
  void touches(std::vector<TouchState>& out) const;
  /// The top-most visible item under `p`, if any.
  std::optional<std::string> item_at(const Vec2& p) const;
  /// Footprint of an item in the `sandtray` frame (current pose).
  Polygon2 footprint(const std::string& name) const;
  /// Footprints of all items as published on `/footprints`: polygon in the item frame, vertex-mean-centred.
  std::vector<std::pair<std::string, Polygon2>> published_footprints() const;
  /// `sandtray` → items and active touches, as the game's TF broadcaster publishes them.
  FrameTree frames() const;
  /// Background (map + strokes, no items), BGR 8-bit at the raster resolution.
  const cv::Mat& background() const;
  /// Fraction of the screen covered by the children's strokes (0 on a bare background).
  double drawing_coverage() const;
  /// Increments each time the background is republished (≤ 4 Hz, only when changed).
  std::uint64_t background_version() const;
  /// Colour zones of the last published background.
  const ZoneMap& zones() const;
  /// Work the zone segmentation did so far (images segmented, colour masks recomputed or reused).
  const ZoneSegmenterCounters& zone_counters() const;
  /// The whole screen (background, strokes, items, stash, robot hand) at `width_px` wide.
  cv::Mat render_screen(int width_px = kScreenWidthPx) const;
  /// Events since the last call (e.g. `releasing_<item>`), emptied by the call.
  std::vector<Event> drain_events();
  /// Hash of the full dynamic state (item poses/velocities, touches, strokes, timers, state).
  std::uint64_t state_hash() const;
  /// The catalogue the tray was built from.
  const ItemCatalogue& catalogue() const;
  /// The configuration the tray was built with.
  const SandtrayConfig& config() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace freeplay::sim
