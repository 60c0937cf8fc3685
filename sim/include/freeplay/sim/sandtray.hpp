#pragma once
// The simulated sandtray: the real QML free-play game (items, touches, robot finger, drawing, zones, states).
//
// CONTRACT DRAFT written by the lead before implementation. The sim-physics owner implements it and may add
// members; other components rely on the names below, so do not rename or remove them.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
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

/// The game's global states (QML `globalstates`) and their trigger signals.
enum class GameState { Blank, Tutorial, FreePlay, ItemsPlacement };

/// The Empty signals of `sandtray/signals/*` that the game reacts to.
enum class Signal { BlankInterface, StartTutorial, StartFreeplay, StartItemsPlacement, ClearDrawing, ShuffleItems,
                    ItemsToStash };

/// Who is holding an item.
struct Holder {
  enum class Kind { None, Finger, Robot } kind = Kind::None;  ///< nobody, a child's finger, the robot finger
  int finger = 0;                                              ///< 1…6 when kind == Finger
};

/// What a press did.
enum class TouchOutcome { GrabbedItem, StartedStroke, Ignored };

/// An item's public state as the game publishes it.
struct ItemState {
  std::string name;    ///< TF frame name, e.g. "zebra"
  Pose2 pose;          ///< item centre in `sandtray`, θ = −screen rotation
  int z = 0;           ///< stacking order (higher is on top)
  bool visible = true; ///< hidden items (tutorial) still publish TF but cannot be touched
  Holder holder;       ///< who drags it now
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

  // --- the robot's virtual finger (`/poses`) ----------------------------------------------------------------
  /// One `/poses` message: grabs the item under the first pose of a stream, then drags it.
  void robot_pose(const Vec2& p);

  // --- time ---------------------------------------------------------------------------------------------------
  /// Advances the game by `dt` seconds (physics at 60 Hz substeps, timers, background republication).
  void step(double dt);
  /// Simulated time since construction (s).
  double time() const;

  // --- state out --------------------------------------------------------------------------------------------
  /// Every item's state, in catalogue order.
  std::vector<ItemState> items() const;
  /// One item's state; throws InputError naming the allowed items when unknown.
  ItemState item(const std::string& name) const;
  /// Active fingers.
  std::vector<TouchState> touches() const;
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
  /// Increments each time the background is republished (≤ 4 Hz, only when changed).
  std::uint64_t background_version() const;
  /// Colour zones of the last published background.
  const ZoneMap& zones() const;
  /// The whole screen (background, strokes, items, stash, robot hand) at `width_px` wide.
  cv::Mat render_screen(int width_px = kScreenWidthPx) const;
  /// Events since the last call (e.g. `releasing_<item>`), emptied by the call.
  std::vector<Event> drain_events();
  /// Hash of the full dynamic state (item poses/velocities, touches, strokes, timers, state).
  std::uint64_t state_hash() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace freeplay::sim
