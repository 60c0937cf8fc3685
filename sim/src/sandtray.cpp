#include "freeplay/sim/sandtray.hpp"

#include <box2d/box2d.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <optional>

#include "freeplay/core/error.hpp"
#include "freeplay/sim/canvas.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/screen_renderer.hpp"
#include "freeplay/sim/zones.hpp"

namespace freeplay::sim {

std::string_view game_state_name(GameState state) {
  switch (state) {
    case GameState::Blank: return "blank";
    case GameState::Tutorial: return "tutorial";
    case GameState::FreePlay: return "freeplay";
    case GameState::ItemsPlacement: return "items_placement";
  }
  return "blank";
}

namespace {

constexpr std::array<std::pair<Signal, std::string_view>, 7> kSignalNames = {{
    {Signal::BlankInterface, "blank_interface"},
    {Signal::StartTutorial, "start_tutorial"},
    {Signal::StartFreeplay, "start_freeplay"},
    {Signal::StartItemsPlacement, "start_items_placement"},
    {Signal::ClearDrawing, "clear_drawing"},
    {Signal::ShuffleItems, "shuffle_items"},
    {Signal::ItemsToStash, "items_to_stash"},
}};

using Nanoseconds = std::int64_t;
constexpr Nanoseconds kSecond = 1'000'000'000;
constexpr Nanoseconds kNever = std::numeric_limits<Nanoseconds>::max();
constexpr Nanoseconds kRobotReleaseDelayNs = static_cast<Nanoseconds>(kRobotReleaseDelayS * 1e9);
constexpr Nanoseconds kBackgroundPeriodNs = static_cast<Nanoseconds>(kBackgroundPeriodS * 1e9);
constexpr Nanoseconds kGameTickNs = static_cast<Nanoseconds>(1e9 / kGameTickHz);
constexpr int kPhysicsRateHz = 60;  // kPhysicsStepS = 1/60 s
constexpr int kVelocityIterations = 8;
constexpr int kPositionIterations = 3;
/// Incoming robot poses that move less than this are ignored, as the real RosPoseSubscriber (EPSILON = 0.5 px).
constexpr double kRobotPoseEpsilonM = 0.5 * kMetresPerPixel;
/// Wall thickness (m). The real walls are 32 px (1 cm); thicker walls behave the same and cannot be crossed by
/// an item that starts overlapping one (stash placement near the edges).
constexpr double kWallThicknessM = 0.05;
constexpr std::uint16_t kWallCategory = 0x0001;
constexpr std::uint16_t kItemCategory = 0x0002;
/// Maximum drag acceleration of the real game: maxForce = 500 × mass in QML Box2D units (1 unit = 1 cm).
constexpr double kQmlMaxAccelerationToUnits = kPhysicsUnitsPerMetre / kQmlUnitsPerMetre;

b2Vec2 to_b2(const Vec2& p) {
  return {static_cast<float>(p.x() * kPhysicsUnitsPerMetre), static_cast<float>(p.y() * kPhysicsUnitsPerMetre)};
}
Vec2 from_b2(const b2Vec2& v) {
  return {static_cast<double>(v.x) / kPhysicsUnitsPerMetre, static_cast<double>(v.y) / kPhysicsUnitsPerMetre};
}

bool finite(const Vec2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

std::string touch_frame(int finger) { return fmt::format("touch{}", finger); }

/// FNV-1a accumulation of raw bytes (bit-exact state hashing).
class Hasher {
 public:
  template <typename T>
  void add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    for (unsigned char b : bytes) {
      hash_ ^= b;
      hash_ *= 1099511628211ULL;
    }
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 14695981039346656037ULL;
};

}  // namespace

std::string_view signal_name(Signal s) {
  for (const auto& [signal, name] : kSignalNames) {
    if (signal == s) return name;
  }
  return "";
}

std::optional<Signal> signal_from_name(std::string_view name) {
  for (const auto& [signal, signal_text] : kSignalNames) {
    if (signal_text == name) return signal;
  }
  return std::nullopt;
}

std::string signal_names() {
  std::string out;
  for (const auto& entry : kSignalNames) {
    if (!out.empty()) out += ", ";
    out += entry.second;
  }
  return out;
}

struct Sandtray::Impl {
  /// What a finger that is down is doing.
  enum class FingerMode { Idle, Item, Stroke };
  struct Finger {
    bool down = false;
    FingerMode mode = FingerMode::Idle;
    Vec2 position = Vec2::Zero();
    int item = -1;
    b2MouseJoint* joint = nullptr;
  };
  struct Robot {
    int item = -1;
    b2MouseJoint* joint = nullptr;
    std::optional<Vec2> hand;            // hand sprite position while shown
    std::optional<Vec2> last_pose;       // last accepted pose (persists, for the 0.5 px filter)
    Nanoseconds deadline = kNever;       // release timer
  };
  struct Item {
    const ItemSpec* spec = nullptr;
    b2Body* body = nullptr;
    int z = 0;
    bool visible = true;
  };

  Impl(std::shared_ptr<const ItemCatalogue> catalogue_in, SandtrayConfig config_in, Rng rng_in)
      : catalogue(std::move(catalogue_in)),
        config(config_in),
        rng(rng_in),
        world(b2Vec2(0.0F, 0.0F)),
        canvas(config.raster_width_px),
        renderer(*catalogue) {}

  std::shared_ptr<const ItemCatalogue> catalogue;
  SandtrayConfig config;
  Rng rng;
  b2World world;
  b2Body* anchor = nullptr;
  std::vector<Item> items;
  std::array<Finger, kMaxTouches + 1> fingers{};  // index 1…6
  Robot robot;
  GameState state = GameState::Blank;
  PaletteColour colour = PaletteColour::Eraser;
  bool drawing = false;
  bool items_collide = true;
  DrawingCanvas canvas;
  cv::Mat published_background;
  ZoneMap zone_map;
  ZoneSegmenter segmenter;
  std::uint64_t background_version = 0;
  bool publish_requested = false;
  ScreenRenderer renderer;
  Nanoseconds now = 0;
  std::int64_t physics_slots = 0;      // 1/60 s slots elapsed (stepped or skipped)
  std::uint64_t physics_steps = 0;     // b2World::Step calls
  std::uint64_t input_count = 0;       // calls that may change an item's state (Sandtray::input_count)
  Nanoseconds next_poll = kBackgroundPeriodNs;
  std::vector<Event> events;

  // --- construction ---------------------------------------------------------------------------------------
  void build_world() {
    world.SetAllowSleeping(true);
    b2BodyDef anchor_def;
    anchor_def.type = b2_staticBody;
    anchor = world.CreateBody(&anchor_def);
    // The walls live on their own static body: bodies joined by a joint do not collide (collideConnected is
    // false), so walls on the joints' anchor body would let a dragged item through.
    b2Body* walls_body = world.CreateBody(&anchor_def);
    const double t = kWallThicknessM;
    const double w = kScreenWidthM;
    const double h = kScreenHeightM;
    // {centre x, centre y, half width, half height} just outside each edge, overlapping at the corners.
    const std::array<std::array<double, 4>, 4> walls = {{{-t / 2, -h / 2, t / 2, h / 2 + t},
                                                        {w + t / 2, -h / 2, t / 2, h / 2 + t},
                                                        {w / 2, t / 2, w / 2 + t, t / 2},
                                                        {w / 2, -h - t / 2, w / 2 + t, t / 2}}};
    for (const auto& wall : walls) {
      b2PolygonShape box;
      box.SetAsBox(static_cast<float>(wall[2] * kPhysicsUnitsPerMetre),
                   static_cast<float>(wall[3] * kPhysicsUnitsPerMetre), to_b2(Vec2(wall[0], wall[1])), 0.0F);
      b2FixtureDef fixture;
      fixture.shape = &box;
      fixture.density = 1.0F;
      fixture.friction = 1.0F;
      fixture.filter.categoryBits = kWallCategory;
      walls_body->CreateFixture(&fixture);
    }
    for (const auto& spec : catalogue->items()) {
      b2BodyDef def;
      def.type = b2_dynamicBody;
      def.linearDamping = static_cast<float>(config.linear_damping);
      def.angularDamping = static_cast<float>(config.angular_damping);
      b2Body* body = world.CreateBody(&def);
      std::array<b2Vec2, b2_maxPolygonVertices> vertices{};
      for (std::size_t i = 0; i < spec.polygon.size(); ++i) vertices[i] = to_b2(spec.polygon[i]);
      b2PolygonShape shape;
      shape.Set(vertices.data(), static_cast<int>(spec.polygon.size()));
      b2FixtureDef fixture;
      fixture.shape = &shape;
      fixture.density = static_cast<float>(spec.density);
      fixture.friction = static_cast<float>(spec.friction);
      fixture.restitution = static_cast<float>(spec.restitution);
      fixture.filter.categoryBits = kItemCategory;
      body->CreateFixture(&fixture);
      items.push_back(Item{&spec, body, 0, true});
    }
    set_item_collisions(config.item_collisions);
  }

  // --- helpers --------------------------------------------------------------------------------------------
  // wrap_angle(angle) without its libm call for the angles a body has after at most one turn: std::remainder is
  // exact, so within (-π, π] it returns the angle itself, and within (π, 3π) or (-3π, -π) the angle ∓ 2π, which the
  // subtraction gives exactly (Sterbenz: the operands are within a factor of 2 of each other).
  static double wrap_body_angle(double angle) {
    constexpr double kPi = std::numbers::pi;
    if (angle > -kPi && angle <= kPi) return angle;
    if (angle > kPi && angle < 3 * kPi) return angle - 2 * kPi;
    if (angle < -kPi && angle > -3 * kPi) return angle + 2 * kPi;
    return wrap_angle(angle);
  }

  Pose2 pose_of(const Item& item) const {
    const b2Vec2 p = item.body->GetPosition();
    const Vec2 position = from_b2(p);
    return {position.x(), position.y(), wrap_body_angle(static_cast<double>(item.body->GetAngle()))};
  }

  double seconds() const { return static_cast<double>(now) * 1e-9; }

  void emit(events::EventPayload payload) { events.push_back(Event{seconds(), "sandtray", std::move(payload)}); }

  int item_index_at(const Vec2& p) const {
    if (state == GameState::Blank) return -1;
    int best = -1;
    for (std::size_t i = 0; i < items.size(); ++i) {
      const Item& item = items[i];
      if (!item.visible) continue;
      if (best >= 0 && item.z < items[static_cast<std::size_t>(best)].z) continue;
      if (point_in_polygon(item.spec->polygon, pose_of(item).to_local(p))) best = static_cast<int>(i);
    }
    return best;
  }

  // Everyone dragging item `index` (fingers ascending, then the robot) into `out`, reusing its storage.
  void holders_into(int index, std::vector<Holder>& out) const {
    out.clear();
    for (int f = 1; f <= kMaxTouches; ++f) {
      const Finger& finger = fingers[static_cast<std::size_t>(f)];
      if (finger.down && finger.mode == FingerMode::Item && finger.item == index) {
        out.push_back(Holder{Holder::Kind::Finger, f});
      }
    }
    if (robot.item == index) out.push_back(Holder{Holder::Kind::Robot, 0});
  }

  std::vector<Holder> holders_of(int index) const {
    std::vector<Holder> out;
    holders_into(index, out);
    return out;
  }

  // Writes item `index`'s published state but its holders into `s`, reusing its storage.
  void fields_into(std::size_t index, ItemState& s) const {
    const Item& item = items[index];
    s.name = item.spec->name;
    s.pose = pose_of(item);
    s.z = item.z;
    s.visible = item.visible;
  }

  // Writes item `index`'s published state into `s`, reusing its storage.
  void state_into(std::size_t index, ItemState& s) const {
    fields_into(index, s);
    holders_into(static_cast<int>(index), s.holders);
    s.holder = s.holders.empty() ? Holder{} : s.holders.front();
  }

  /// The finger of a holder in an event (empty for the robot).
  static std::optional<int> holder_finger(const Holder& holder) {
    if (holder.kind == Holder::Kind::Robot) return std::nullopt;
    return holder.finger;
  }

  b2MouseJoint* attach(int index, const Vec2& target) {
    b2Body* body = items[static_cast<std::size_t>(index)].body;
    b2MouseJointDef def;
    def.bodyA = anchor;
    def.bodyB = body;
    def.target = to_b2(target);
    // maxForce = mass × 500 in the game's units is an acceleration cap of 500 QML units/s² (= 5 m/s²).
    def.maxForce = static_cast<float>(config.joint_max_force_per_kg * kQmlMaxAccelerationToUnits) *
                   body->GetMass();
    b2LinearStiffness(def.stiffness, def.damping, static_cast<float>(config.joint_frequency_hz),
                      static_cast<float>(config.joint_damping_ratio), def.bodyA, def.bodyB);
    body->SetAwake(true);
    return static_cast<b2MouseJoint*>(world.CreateJoint(&def));
  }

  void grabbed_event(int index, const Holder& holder) {
    events::ItemGrabbed grabbed{items[static_cast<std::size_t>(index)].spec->name, holder_finger(holder), {}};
    for (const Holder& other : holders_of(index)) {
      if (other == holder) continue;
      grabbed.shared_with.push_back(other.kind == Holder::Kind::Robot ? std::string("robot")
                                                                      : touch_frame(other.finger));
    }
    emit(std::move(grabbed));
  }

  void released_event(int index, const Holder& holder, const char* reason) {
    emit(events::ItemReleased{items[static_cast<std::size_t>(index)].spec->name, holder_finger(holder), reason});
  }

  void release_finger(int f, const char* reason) {
    Finger& finger = fingers[static_cast<std::size_t>(f)];
    if (finger.mode == FingerMode::Item) {
      world.DestroyJoint(finger.joint);
      const int index = finger.item;
      finger.joint = nullptr;
      finger.item = -1;
      finger.mode = FingerMode::Idle;
      released_event(index, Holder{Holder::Kind::Finger, f}, reason);
    } else if (finger.mode == FingerMode::Stroke) {
      canvas.end_stroke(f);
      finger.mode = FingerMode::Idle;
      publish_requested = true;
      emit(events::StrokeFinished{f});
    }
  }

  void release_robot(const char* reason) {
    if (robot.item >= 0) {
      const int index = robot.item;
      world.DestroyJoint(robot.joint);
      robot.joint = nullptr;
      robot.item = -1;
      if (std::string_view(reason) == "timeout") {
        emit(events::InteractionEvent{"releasing_" + items[static_cast<std::size_t>(index)].spec->name});
      }
      released_event(index, Holder{Holder::Kind::Robot, 0}, reason);
    }
    robot.hand.reset();
    robot.deadline = kNever;
  }

  void place(Item& item, const Vec2& centre, double theta) {
    item.body->SetTransform(to_b2(centre), static_cast<float>(theta));
    item.body->SetLinearVelocity(b2Vec2(0.0F, 0.0F));
    item.body->SetAngularVelocity(0.0F);
    if (item.body->IsEnabled()) item.body->SetAwake(true);
  }

  double random_theta() { return -rng.uniform(0.0, 360.0) * std::numbers::pi / 180.0; }

  void items_to_stash() {
    const double stash_width = kScreenWidthM - kStashMinX;
    const double half_base = 0.5 * kItemBaseSideM;  // QML x/y is the unscaled box corner; scale is about the centre
    for (Item& item : items) {
      const double left = kStashMinX + 10.0 * kMetresPerPixel + rng.uniform() * stash_width / 2.0;
      const double top = rng.uniform() * 0.9 * kScreenHeightM;
      const double theta = random_theta();
      place(item, Vec2(left + half_base, -(top + half_base)), theta);
    }
  }

  void shuffle_items() {
    for (Item& item : items) {
      const double x = rng.uniform(0.1, 0.9) * kScreenWidthM;
      const double y = -rng.uniform(0.1, 0.9) * kScreenHeightM;
      const double theta = random_theta();
      place(item, Vec2(x, y), theta);
    }
  }

  void set_item_collisions(bool collide) {
    items_collide = collide;
    for (Item& item : items) {
      b2Fixture* fixture = item.body->GetFixtureList();
      b2Filter filter = fixture->GetFilterData();
      filter.maskBits = collide ? 0xFFFF : kWallCategory;
      fixture->SetFilterData(filter);
    }
  }

  void set_visible(std::size_t index, bool visible) {
    Item& item = items[index];
    if (!visible) {
      for (int f = 1; f <= kMaxTouches; ++f) {
        if (fingers[static_cast<std::size_t>(f)].item == static_cast<int>(index)) release_finger(f, "hidden");
      }
      if (robot.item == static_cast<int>(index)) release_robot("hidden");
    }
    item.visible = visible;
    item.body->SetEnabled(visible);
  }

  void set_drawing(bool enabled) {
    if (drawing != enabled) {
      drawing = enabled;
      emit(events::BackgroundDrawing{enabled});
    }
  }

  void publish_background() {
    // Only the pixels changed since the last publication are copied and converted again.
    const double metres_per_pixel = kScreenWidthM / static_cast<double>(canvas.width_px());
    if (published_background.size() != canvas.image().size()) {
      canvas.image().copyTo(published_background);
      const cv::Rect whole(0, 0, published_background.cols, published_background.rows);
      zone_map = segmenter.segment(published_background, metres_per_pixel, whole);  // a new background
    } else {
      const ChangedPixels& changed = canvas.unpublished();
      const cv::Rect& box = changed.box();
      for (int y = box.y; y < box.y + box.height; ++y) {
        const cv::Range columns = changed.columns(y);
        if (columns.empty()) continue;
        const std::size_t offset = static_cast<std::size_t>(columns.start) * 3;
        std::memcpy(published_background.ptr(y) + offset, canvas.image().ptr(y) + offset,
                    static_cast<std::size_t>(columns.size()) * 3);
      }
      zone_map = segmenter.segment(published_background, metres_per_pixel, changed);
    }
    canvas.mark_published();
    publish_requested = false;
    ++background_version;
    emit(events::BackgroundPublished{background_version});
  }

  void enter_state(GameState next) {
    for (int f = 1; f <= kMaxTouches; ++f) {
      if (fingers[static_cast<std::size_t>(f)].mode == FingerMode::Stroke) release_finger(f, "state_change");
    }
    const auto show_only = [&](std::initializer_list<std::string_view> shown, bool invert) {
      for (std::size_t i = 0; i < items.size(); ++i) {
        const bool listed = std::find(shown.begin(), shown.end(), items[i].spec->name) != shown.end();
        set_visible(i, listed != invert);
      }
    };
    state = next;
    switch (next) {
      case GameState::Blank:
        for (int f = 1; f <= kMaxTouches; ++f) release_finger(f, "state_change");
        release_robot("state_change");
        show_only({}, true);
        set_drawing(false);
        set_item_collisions(config.item_collisions);
        canvas.set_background(BackgroundKind::Blank);
        break;
      case GameState::Tutorial:
        show_only({"boy", "girl"}, false);
        set_drawing(false);
        set_item_collisions(config.item_collisions);
        canvas.set_background(BackgroundKind::Tutorial);
        items_to_stash();
        break;
      case GameState::FreePlay:
        show_only({}, true);
        set_drawing(true);
        set_item_collisions(config.item_collisions);
        canvas.set_background(BackgroundKind::FreeplayMap);
        items_to_stash();
        break;
      case GameState::ItemsPlacement:
        show_only({"girl", "caravan"}, true);
        set_drawing(false);
        set_item_collisions(false);
        canvas.set_background(BackgroundKind::FreeplayMap);
        break;
    }
    emit(events::StateChanged{std::string(game_state_name(next))});
    publish_background();
  }

  // --- validation (before any mutation) ---------------------------------------------------------------------
  static void check_finger_id(int finger) {
    if (finger < 1 || finger > kMaxTouches) {
      throw InputError(fmt::format("finger {} does not exist (the game tracks 6 touch points)", finger), "finger",
                       "1…6");
    }
  }

  static void check_point(const Vec2& p, const char* key) {
    if (!finite(p)) throw InputError("point is not finite", key, "finite x, y in metres");
    if (!on_screen(p)) {
      throw InputError(fmt::format("point ({:.4f}, {:.4f}) is outside the screen", p.x(), p.y()), key,
                       "x in [0, 0.6], y in [-0.335, 0] (sandtray frame, metres)");
    }
  }

  const Finger& finger_down(int f) const {
    check_finger_id(f);
    const Finger& finger = fingers[static_cast<std::size_t>(f)];
    if (!finger.down) throw InputError(fmt::format("finger {} is not down", f), "finger", "a finger that is down");
    return finger;
  }

  // --- time -----------------------------------------------------------------------------------------------
  static Nanoseconds slot_time(std::int64_t slot) { return slot * kSecond / kPhysicsRateHz; }

  bool all_asleep() const {
    return std::none_of(items.begin(), items.end(),
                        [](const Item& item) { return item.body->IsEnabled() && item.body->IsAwake(); });
  }

  void advance(Nanoseconds target) {
    while (true) {
      const Nanoseconds next_physics = slot_time(physics_slots + 1);
      const Nanoseconds next_event = std::min({next_physics, robot.deadline, next_poll});
      if (next_event > target) break;
      now = next_event;
      if (robot.deadline == now) release_robot("timeout");
      if (next_physics == now) {
        ++physics_slots;
        if (!all_asleep()) {
          world.Step(static_cast<float>(kPhysicsStepS), kVelocityIterations, kPositionIterations);
          ++physics_steps;
        } else {
          // Nothing can move until an input arrives: jump over the idle slots up to the next timer or `target`.
          const Nanoseconds until = std::min({target, robot.deadline, next_poll});
          const std::int64_t last_slot = until * kPhysicsRateHz / kSecond;
          if (last_slot > physics_slots) physics_slots = last_slot;
        }
      }
      if (next_poll == now) {
        if (publish_requested) publish_background();
        next_poll += kBackgroundPeriodNs;
      }
    }
    now = target;
  }

  void hash_into(Hasher& h) const {
    h.add(now);
    h.add(physics_slots);
    h.add(physics_steps);
    h.add(next_poll);
    h.add(state);
    h.add(colour);
    h.add(drawing);
    h.add(items_collide);
    h.add(publish_requested);
    h.add(background_version);
    Rng probe = rng;
    h.add(probe());
    for (const Item& item : items) {
      const b2Transform& xf = item.body->GetTransform();
      h.add(xf.p.x);
      h.add(xf.p.y);
      h.add(item.body->GetAngle());
      h.add(item.body->GetLinearVelocity().x);
      h.add(item.body->GetLinearVelocity().y);
      h.add(item.body->GetAngularVelocity());
      h.add(item.body->IsAwake());
      h.add(item.body->IsEnabled());
      h.add(item.z);
      h.add(item.visible);
    }
    const auto hash_joint = [&h](const b2MouseJoint* joint) {
      if (joint == nullptr) {
        h.add(false);
        return;
      }
      h.add(true);
      h.add(joint->GetTarget().x);
      h.add(joint->GetTarget().y);
      h.add(joint->GetAnchorB().x);
      h.add(joint->GetAnchorB().y);
    };
    for (int f = 1; f <= kMaxTouches; ++f) {
      const Finger& finger = fingers[static_cast<std::size_t>(f)];
      h.add(finger.down);
      h.add(finger.mode);
      h.add(finger.position.x());
      h.add(finger.position.y());
      h.add(finger.item);
      hash_joint(finger.joint);
    }
    h.add(robot.item);
    hash_joint(robot.joint);
    h.add(robot.deadline);
    h.add(robot.hand.has_value());
    if (robot.hand) {
      h.add(robot.hand->x());
      h.add(robot.hand->y());
    }
    h.add(robot.last_pose.has_value());
    if (robot.last_pose) {
      h.add(robot.last_pose->x());
      h.add(robot.last_pose->y());
    }
    h.add(canvas.hash());
  }
};

Sandtray::Sandtray(std::shared_ptr<const ItemCatalogue> catalogue, SandtrayConfig config, Rng rng) {
  if (!catalogue) throw InputError("no item catalogue given", "catalogue");
  if (config.raster_width_px < 16 || config.raster_width_px > 16384) {
    throw InputError(fmt::format("raster width {} px is out of range", config.raster_width_px), "raster_width_px",
                     "16…16384");
  }
  const auto positive = [](double value, const char* key) {
    if (!std::isfinite(value) || value <= 0.0) throw InputError("must be a positive number", key);
  };
  positive(config.joint_frequency_hz, "joint_frequency_hz");
  positive(config.joint_damping_ratio, "joint_damping_ratio");
  positive(config.joint_max_force_per_kg, "joint_max_force_per_kg");
  if (!std::isfinite(config.linear_damping) || config.linear_damping < 0.0) {
    throw InputError("must be a non-negative number", "linear_damping");
  }
  if (!std::isfinite(config.angular_damping) || config.angular_damping < 0.0) {
    throw InputError("must be a non-negative number", "angular_damping");
  }
  impl_ = std::make_unique<Impl>(std::move(catalogue), config, rng);
  impl_->build_world();
  impl_->items_to_stash();
  impl_->canvas.set_background(BackgroundKind::Blank);
  impl_->publish_background();
  impl_->events.clear();
}

Sandtray::~Sandtray() = default;

void Sandtray::signal(Signal s) {
  Impl& d = *impl_;
  ++d.input_count;
  switch (s) {
    case Signal::BlankInterface:
    case Signal::StartTutorial:
    case Signal::StartFreeplay:
    case Signal::StartItemsPlacement: {
      const GameState next = s == Signal::BlankInterface    ? GameState::Blank
                             : s == Signal::StartTutorial   ? GameState::Tutorial
                             : s == Signal::StartFreeplay   ? GameState::FreePlay
                                                            : GameState::ItemsPlacement;
      if (next != d.state) d.enter_state(next);
      break;
    }
    case Signal::ClearDrawing:
      for (int f = 1; f <= kMaxTouches; ++f) {
        if (d.fingers[static_cast<std::size_t>(f)].mode == Impl::FingerMode::Stroke) {
          d.release_finger(f, "clear_drawing");
        }
      }
      d.canvas.clear_strokes();
      d.publish_requested = true;
      break;
    case Signal::ShuffleItems: d.shuffle_items(); break;
    case Signal::ItemsToStash: d.items_to_stash(); break;
  }
  d.emit(events::GameSignal{std::string(signal_name(s))});
}

GameState Sandtray::state() const { return impl_->state; }

TouchOutcome Sandtray::touch_down(int finger, const Vec2& p) {
  Impl& d = *impl_;
  ++d.input_count;
  Impl::check_finger_id(finger);
  Impl::check_point(p, "touch position");
  Impl::Finger& f = d.fingers[static_cast<std::size_t>(finger)];
  if (f.down) {
    throw InputError(fmt::format("finger {} is already down", finger), "finger", "a finger that is not down");
  }
  const int hit = d.item_index_at(p);
  TouchOutcome outcome = TouchOutcome::Ignored;
  Impl::FingerMode mode = Impl::FingerMode::Idle;
  if (hit >= 0) {
    outcome = TouchOutcome::GrabbedItem;
    mode = Impl::FingerMode::Item;
  } else if (d.drawing) {
    d.canvas.begin_stroke(finger, d.colour, p);  // the only call that may throw; nothing changed before it
    outcome = TouchOutcome::StartedStroke;
    mode = Impl::FingerMode::Stroke;
  }
  f.down = true;
  f.position = p;
  f.mode = mode;
  if (mode == Impl::FingerMode::Item) {
    int max_z = 0;
    for (const auto& item : d.items) max_z = std::max(max_z, item.z);
    d.items[static_cast<std::size_t>(hit)].z = max_z + 1;
    f.item = hit;
    f.joint = d.attach(hit, p);
    d.grabbed_event(hit, Holder{Holder::Kind::Finger, finger});
  } else if (mode == Impl::FingerMode::Stroke) {
    d.emit(events::StrokeStarted{finger, std::string(palette_name(d.colour))});
  }
  return outcome;
}

void Sandtray::touch_move(int finger, const Vec2& p) {
  Impl& d = *impl_;
  ++d.input_count;
  d.finger_down(finger);
  Impl::check_point(p, "touch position");
  Impl::Finger& f = d.fingers[static_cast<std::size_t>(finger)];
  if (f.mode == Impl::FingerMode::Stroke) d.canvas.extend_stroke(finger, p);
  if (f.mode == Impl::FingerMode::Item) f.joint->SetTarget(to_b2(p));
  f.position = p;
}

void Sandtray::touch_up(int finger) {
  Impl& d = *impl_;
  ++d.input_count;
  d.finger_down(finger);
  d.release_finger(finger, "touch_up");
  d.fingers[static_cast<std::size_t>(finger)] = Impl::Finger{};
}

void Sandtray::select_colour(PaletteColour colour) {
  if (std::find(kPalette.begin(), kPalette.end(), colour) == kPalette.end()) {
    throw InputError("unknown palette colour", "colour", std::string(palette_names()));
  }
  impl_->colour = colour;
}

void Sandtray::select_colour(std::string_view colour_name) {
  const auto colour = palette_from_name(colour_name);
  if (!colour) {
    throw InputError(fmt::format("unknown palette colour '{}'", colour_name), "colour", std::string(palette_names()));
  }
  impl_->colour = *colour;
}

PaletteColour Sandtray::colour() const { return impl_->colour; }

bool Sandtray::drawing_enabled() const { return impl_->drawing; }

void Sandtray::robot_pose(const Vec2& p) {
  Impl& d = *impl_;
  ++d.input_count;
  if (!finite(p)) throw InputError("robot pose is not finite", "pose", "finite x, y in metres (sandtray frame)");
  if (d.state == GameState::Blank) return;  // the sandbox is hidden: the real subscriber ignores poses
  if (d.robot.last_pose && (*d.robot.last_pose - p).norm() < kRobotPoseEpsilonM) return;
  d.robot.last_pose = p;
  d.robot.hand = p;
  d.robot.deadline = d.now + kRobotReleaseDelayNs;
  if (d.robot.item < 0) {
    const int hit = d.item_index_at(p);
    if (hit >= 0) {
      d.robot.item = hit;
      d.robot.joint = d.attach(hit, p);
      d.grabbed_event(hit, Holder{Holder::Kind::Robot, 0});
    }
  } else {
    d.robot.joint->SetTarget(to_b2(p));
  }
}

std::optional<std::string> Sandtray::robot_item() const {
  if (impl_->robot.item < 0) return std::nullopt;
  return impl_->items[static_cast<std::size_t>(impl_->robot.item)].spec->name;
}

std::optional<Vec2> Sandtray::robot_hand() const { return impl_->robot.hand; }

void Sandtray::place_item(const std::string& name, const Pose2& pose) {
  Impl& d = *impl_;
  ++d.input_count;
  const std::size_t index = d.catalogue->index_of(name);
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    throw InputError(fmt::format("pose of '{}' is not finite", name), "pose", "finite x, y (m) and theta (rad)");
  }
  if (pose.x < 0.0 || pose.x > kScreenWidthM || pose.y > 0.0 || pose.y < -kScreenHeightM) {
    throw InputError(fmt::format("centre ({}, {}) of '{}' is off the screen", pose.x, pose.y, name), "pose",
                     "x in [0, 0.6], y in [-0.335, 0] (sandtray frame, m)");
  }
  if (!d.holders_of(static_cast<int>(index)).empty()) {
    throw InputError(fmt::format("'{}' is being held", name), "item", "an item nobody holds");
  }
  d.place(d.items[index], pose.position(), pose.theta);
}

void Sandtray::step(double dt) {
  if (!std::isfinite(dt) || dt < 0.0 || dt > 3600.0) {
    throw InputError(fmt::format("time step {} s is not allowed", dt), "dt", "0 <= dt <= 3600 seconds");
  }
  ++impl_->input_count;
  impl_->advance(impl_->now + std::llround(dt * 1e9));
}

double Sandtray::time() const { return impl_->seconds(); }

std::int64_t Sandtray::tick_count() const { return impl_->now / kGameTickNs; }

std::uint64_t Sandtray::physics_steps() const { return impl_->physics_steps; }

std::uint64_t Sandtray::input_count() const { return impl_->input_count; }

bool Sandtray::asleep() const { return impl_->all_asleep(); }

std::vector<ItemState> Sandtray::items() const {
  std::vector<ItemState> out;
  items(out);
  return out;
}

void Sandtray::items(std::vector<ItemState>& out) const {
  const auto& d = *impl_;
  out.resize(d.items.size());
  for (std::size_t i = 0; i < d.items.size(); ++i) {
    d.fields_into(i, out[i]);
    out[i].holders.clear();
  }
  // Every item's holders in one pass over the fingers (ascending), then the robot: each item's list in
  // holders_into's order.
  for (int f = 1; f <= kMaxTouches; ++f) {
    const auto& finger = d.fingers[static_cast<std::size_t>(f)];
    if (finger.down && finger.mode == Impl::FingerMode::Item) {
      out[static_cast<std::size_t>(finger.item)].holders.push_back(Holder{Holder::Kind::Finger, f});
    }
  }
  if (d.robot.item >= 0) out[static_cast<std::size_t>(d.robot.item)].holders.push_back(Holder{Holder::Kind::Robot, 0});
  for (ItemState& s : out) s.holder = s.holders.empty() ? Holder{} : s.holders.front();
}

ItemState Sandtray::item(const std::string& name) const {
  ItemState s;
  impl_->state_into(impl_->catalogue->index_of(name), s);
  return s;
}

std::vector<TouchState> Sandtray::touches() const {
  std::vector<TouchState> out;
  touches(out);
  return out;
}

void Sandtray::touches(std::vector<TouchState>& out) const {
  out.clear();
  for (int f = 1; f <= kMaxTouches; ++f) {
    const auto& finger = impl_->fingers[static_cast<std::size_t>(f)];
    if (!finger.down) continue;
    TouchState& t = out.emplace_back();
    t.finger = f;
    t.position = finger.position;
    if (finger.mode == Impl::FingerMode::Item) t.item = impl_->items[static_cast<std::size_t>(finger.item)].spec->name;
  }
}

std::optional<std::string> Sandtray::item_at(const Vec2& p) const {
  if (!finite(p)) throw InputError("point is not finite", "point", "finite x, y in metres");
  const int hit = impl_->item_index_at(p);
  if (hit < 0) return std::nullopt;
  return impl_->items[static_cast<std::size_t>(hit)].spec->name;
}

Polygon2 Sandtray::footprint(const std::string& name) const {
  const auto& item = impl_->items[impl_->catalogue->index_of(name)];
  return transformed(item.spec->polygon, impl_->pose_of(item));
}

std::vector<std::pair<std::string, Polygon2>> Sandtray::published_footprints() const {
  std::vector<std::pair<std::string, Polygon2>> out;
  for (const auto& spec : impl_->catalogue->items()) {
    const Vec2 mean = vertex_mean(spec.polygon);
    Polygon2 centred;
    for (const auto& v : spec.polygon) centred.push_back(v - mean);
    out.emplace_back(spec.name, std::move(centred));
  }
  return out;
}

FrameTree Sandtray::frames() const {
  FrameTree tree;
  const double t = impl_->seconds();
  tree.set("sandtray", "", Eigen::Isometry3d::Identity(), t);
  for (const auto& item : impl_->items) tree.set(item.spec->name, "sandtray", impl_->pose_of(item).isometry(), t);
  for (int f = 1; f <= kMaxTouches; ++f) {
    const auto& finger = impl_->fingers[static_cast<std::size_t>(f)];
    if (finger.down && finger.mode != Impl::FingerMode::Idle) {
      tree.set(touch_frame(f), "sandtray", Pose2{finger.position.x(), finger.position.y(), 0.0}.isometry(), t);
    }
  }
  return tree;
}

const cv::Mat& Sandtray::background() const { return impl_->published_background; }

double Sandtray::drawing_coverage() const { return impl_->canvas.coverage(); }

std::uint64_t Sandtray::background_version() const { return impl_->background_version; }

const ZoneMap& Sandtray::zones() const { return impl_->zone_map; }

const ZoneSegmenterCounters& Sandtray::zone_counters() const { return impl_->segmenter.counters(); }

cv::Mat Sandtray::render_screen(int width_px) const {
  const Impl& d = *impl_;
  const bool shown = d.state != GameState::Blank;
  std::vector<ItemView> views;
  views.reserve(d.items.size());
  for (const auto& item : d.items) views.push_back(ItemView{item.spec, d.pose_of(item), item.z, shown && item.visible});
  ScreenOverlay overlay;
  for (const auto& touch : touches()) overlay.touches.push_back(touch.position);
  overlay.robot_hand = d.robot.hand;
  overlay.stash_visible = shown && d.state != GameState::ItemsPlacement;
  overlay.palette_visible = d.drawing;
  return d.renderer.render(d.canvas.image(), views, overlay, width_px);
}

std::vector<Event> Sandtray::drain_events() {
  std::vector<Event> out;
  out.swap(impl_->events);
  return out;
}

std::uint64_t Sandtray::state_hash() const {
  Hasher h;
  impl_->hash_into(h);
  return h.value();
}

const ItemCatalogue& Sandtray::catalogue() const { return *impl_->catalogue; }

const SandtrayConfig& Sandtray::config() const { return impl_->config; }

}  // namespace freeplay::sim
