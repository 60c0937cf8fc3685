#include "freeplay/agents/session.hpp"

#include <algorithm>
#include <cmath>

#include "min_jerk.hpp"

namespace freeplay::agents {
namespace {

constexpr int kItems = static_cast<int>(kItemNames.size());
constexpr int kRobot = 2;
constexpr int kNobody = -1;

/// Approximate colour zones of the free-play map (res/map.svg layout, free-play-sandbox.md §3.7) as discs.
constexpr struct {
  PaletteColour colour;
  double x, y, r;
} kMapZones[] = {
    {PaletteColour::White, 0.10, -0.08, 0.07},  {PaletteColour::Black, 0.03, -0.02, 0.02},
    {PaletteColour::Black, 0.17, -0.02, 0.02},  {PaletteColour::Blue, 0.12, -0.26, 0.07},
    {PaletteColour::Blue, 0.27, -0.10, 0.04},   {PaletteColour::Blue, 0.42, -0.17, 0.04},
    {PaletteColour::Yellow, 0.45, -0.06, 0.07}, {PaletteColour::Yellow, 0.24, -0.28, 0.04},
    {PaletteColour::Yellow, 0.30, -0.14, 0.02}, {PaletteColour::Green, 0.45, -0.28, 0.06},
    {PaletteColour::Green, 0.30, -0.21, 0.08},  {PaletteColour::Green, 0.20, -0.16, 0.06},
};

/// How often the real asocial robot moved each item (pinsoro-targets §6), in kItemNames order.
constexpr std::array<double, 10> kRobotItemCounts = {164, 399, 151, 170, 198, 270, 391, 417, 155, 225};

/// Habitat colours of the real play policy, as bit masks over PaletteColour.
unsigned habitat_mask(int item) {
  const auto bit = [](PaletteColour c) { return 1U << static_cast<unsigned>(c); };
  switch (item) {
    case 0: case 4: return bit(PaletteColour::Yellow) | bit(PaletteColour::Green);  // zebra, giraffe
    case 1: return bit(PaletteColour::Green);                                       // elephant
    case 3: return bit(PaletteColour::Yellow);                                      // lion
    case 6: case 7: return bit(PaletteColour::Blue);                                // crocodile, hippo
    default:
      return bit(PaletteColour::Yellow) | bit(PaletteColour::Green) | bit(PaletteColour::Purple) |
             bit(PaletteColour::White);
  }
}

/// Log-normal with different σ below and above the median, matching published p10 / p50 / p90.
double split_lognormal(Rng& rng, double median, double p10, double p90) {
  const double z = rng.normal();
  const double sigma = z < 0.0 ? std::log(median / p10) / 1.2815515655 : std::log(p90 / median) / 1.2815515655;
  return median * std::exp(z * sigma);
}

struct Finger {
  bool active = false;
  Vec2 point{0.0, 0.0};
  int item = -1;
  // stroke geometry (fills become zones)
  double length = 0.0;
  Vec2 lo{0.0, 0.0};
  Vec2 hi{0.0, 0.0};
};

/// The kinematic stand-in of the sandtray: items follow fingers; no collisions, no physics.
class StandInTray {
 public:
  explicit StandInTray(Rng& rng) {
    for (int i = 0; i < kItems; ++i) {
      positions_[static_cast<std::size_t>(i)] = {rng.uniform(sim::kStashMinX + 0.0031, sim::kStashMinX + 0.036),
                                                 -rng.uniform(0.05, 0.95) * sim::kScreenHeightM};
      holder_[static_cast<std::size_t>(i)] = kNobody;
    }
    for (const auto& z : kMapZones) add_zone(z.colour, {z.x, z.y}, z.r);
  }

  void apply(int who, const TouchCommand& c) {
    Finger& f = fingers_[static_cast<std::size_t>(who)][static_cast<std::size_t>(std::clamp(c.finger, 1, kFingersPerChild))];
    switch (c.phase) {
      case TouchPhase::Down: {
        release(f);
        f = Finger{};
        f.active = true;
        f.point = c.point;
        f.item = item_at(c.point);
        if (f.item >= 0) {
          take(f.item, who);
        } else {
          f.lo = f.hi = c.point;
        }
        break;
      }
      case TouchPhase::Move:
        if (!f.active) break;
        if (f.item >= 0 && holder_[static_cast<std::size_t>(f.item)] == who) {
          positions_[static_cast<std::size_t>(f.item)] = clamp_screen(c.point);
        } else if (f.item < 0) {
          f.length += (c.point - f.point).norm();
          f.lo = f.lo.cwiseMin(c.point);
          f.hi = f.hi.cwiseMax(c.point);
        }
        f.point = c.point;
        break;
      case TouchPhase::Up:
        if (!f.active) break;
        if (f.item < 0) {
          const double diagonal = (f.hi - f.lo).norm();
          if (diagonal > 0.02 && f.length > 3.0 * diagonal) add_zone(colour_, 0.5 * (f.lo + f.hi), 0.5 * diagonal);
        }
        release(f);
        f.active = false;
        break;
    }
  }

  void select_colour(PaletteColour colour) { colour_ = colour; }

  int item_at(const Vec2& p) const {
    int best = -1;
    double best_d = 1e9;
    for (int i = 0; i < kItems; ++i) {
      const double d = (positions_[static_cast<std::size_t>(i)] - p).norm();
      if (d < 0.5 * item_size_m(i) + 0.005 && d < best_d) {
        best_d = d;
        best = i;
      }
    }
    return best;
  }

  /// `who` grabs item `i`, detaching whoever held it (both joints would fight; the newer grab wins here).
  void take(int i, int who) {
    const int before = holder_[static_cast<std::size_t>(i)];
    if (before >= 0 && before != who && before != kRobot) {
      for (auto& f : fingers_[static_cast<std::size_t>(before)]) {
        if (f.item == i) f.item = -1;
      }
    }
    holder_[static_cast<std::size_t>(i)] = who;
  }

  void release(Finger& f) {
    if (f.item >= 0 && holder_[static_cast<std::size_t>(f.item)] != kRobot) holder_[static_cast<std::size_t>(f.item)] = kNobody;
    f.item = -1;
  }

  static Vec2 clamp_screen(const Vec2& p) {
    return {std::clamp(p.x(), 0.0, sim::kScreenWidthM), std::clamp(p.y(), -sim::kScreenHeightM, 0.0)};
  }

  void add_zone(PaletteColour colour, const Vec2& centre, double radius) {
    if (zone_count_ >= static_cast<int>(kMaxSeenZones)) {  // the oldest drawn zone is painted over
      for (int i = static_cast<int>(std::size(kMapZones)); i + 1 < zone_count_; ++i) {
        zones_[static_cast<std::size_t>(i)] = zones_[static_cast<std::size_t>(i + 1)];
      }
      --zone_count_;
    }
    zones_[static_cast<std::size_t>(zone_count_++)] = SeenZone{colour, centre, radius};
  }

  bool in_habitat(int i) const {
    const unsigned mask = habitat_mask(i);
    const Vec2& p = positions_[static_cast<std::size_t>(i)];
    for (int z = 0; z < zone_count_; ++z) {
      const SeenZone& zone = zones_[static_cast<std::size_t>(z)];
      if ((mask & (1U << static_cast<unsigned>(zone.colour))) && (zone.centroid - p).norm() < zone.radius_m) return true;
    }
    return false;
  }

  /// Fills the world part of `who`'s perception (items and zones).
  void perceive(int who, bool partner_is_robot, ChildPerception& out) const {
    out.item_count = kItems;
    for (int i = 0; i < kItems; ++i) {
      SeenItem& s = out.items[static_cast<std::size_t>(i)];
      s.item = i;
      s.position = positions_[static_cast<std::size_t>(i)];
      s.in_stash = sim::in_stash(s.position);
      const int h = holder_[static_cast<std::size_t>(i)];
      s.holder = h == kNobody ? HolderView::Nobody
                 : h == who   ? HolderView::Me
                 : h == kRobot ? HolderView::Robot
                               : (partner_is_robot ? HolderView::Robot : HolderView::Partner);
    }
    out.zone_count = zone_count_;
    std::copy_n(zones_.begin(), zone_count_, out.zones.begin());
  }

  /// Active fingers of `who` as its partner sees them.
  int touches_of(int who, std::array<SeenTouch, 6>& out) const {
    int n = 0;
    for (const Finger& f : fingers_[static_cast<std::size_t>(who)]) {
      if (f.active && n < 6) out[static_cast<std::size_t>(n++)] = {f.point, f.item};
    }
    return n;
  }

  std::array<Vec2, kItems> positions_{};
  std::array<int, kItems> holder_{};

 private:
  std::array<std::array<Finger, kFingersPerChild + 1>, 2> fingers_{};
  std::array<SeenZone, kMaxSeenZones> zones_{};
  int zone_count_ = 0;
  PaletteColour colour_ = PaletteColour::Green;
};

/// The asocial `play` policy of the real study, reduced to its visible behaviour: it moves items that are not
/// in a habitat to the nearest zone of a random habitat colour, on the observed schedule, and never reacts.
class StandInRobot {
 public:
  explicit StandInRobot(Rng rng, bool takes_items) : rng_(rng), takes_items_(takes_items) {
    next_goal_t_ = split_lognormal(rng_, 4.3, 2.4, 15.6);
  }

  void step(double t, StandInTray& tray) {
    if (item_ >= 0) {
      const double tau = (t - t0_) / duration_;
      tray.positions_[static_cast<std::size_t>(item_)] = from_ + min_jerk(tau) * (to_ - from_);
      if (tau >= 1.0) {
        tray.holder_[static_cast<std::size_t>(item_)] = kNobody;
        item_ = -1;
      }
      return;
    }
    if (t < next_goal_t_) return;
    next_goal_t_ = t + 0.3;  // the real policy retries after 0.3 s when no item needs moving
    std::array<double, kItems> weights{};
    double total = 0.0;
    for (int i = 0; i < kItems; ++i) {
      const Vec2& p = tray.positions_[static_cast<std::size_t>(i)];
      const bool held_by_child = tray.holder_[static_cast<std::size_t>(i)] >= 0;
      if ((p - kShoulder).norm() > kReach || tray.in_habitat(i) || (held_by_child && !takes_items_)) continue;
      weights[static_cast<std::size_t>(i)] = kRobotItemCounts[static_cast<std::size_t>(i)];
      total += weights[static_cast<std::size_t>(i)];
    }
    if (total <= 0.0) return;
    double u = rng_.uniform() * total;
    int chosen = 0;
    for (int i = 0; i < kItems; ++i) {
      u -= weights[static_cast<std::size_t>(i)];
      if (u < 0.0) {
        chosen = i;
        break;
      }
    }
    // A random habitat colour, then its zone nearest to the item.
    const unsigned mask = habitat_mask(chosen);
    std::array<PaletteColour, 8> colours{};
    int n = 0;
    for (unsigned c = 0; c < 8; ++c) {
      if (mask & (1U << c)) colours[static_cast<std::size_t>(n++)] = static_cast<PaletteColour>(c);
    }
    const PaletteColour wanted = colours[static_cast<std::size_t>(rng_.uniform_int(0, n - 1))];
    const Vec2 p = tray.positions_[static_cast<std::size_t>(chosen)];
    double best = 1e9;
    Vec2 target = p;
    for (const auto& z : kMapZones) {
      const Vec2 c{z.x, z.y};
      if (z.colour != wanted || (c - kShoulder).norm() > kReach) continue;
      if ((c - p).norm() < best) {
        best = (c - p).norm();
        target = c;
      }
    }
    if (best >= 1e9) return;
    next_goal_t_ = t + split_lognormal(rng_, 4.3, 2.4, 15.6);
    tray.take(chosen, kRobot);
    item_ = chosen;
    from_ = p;
    to_ = target;
    t0_ = t;
    duration_ = std::min(12.2, split_lognormal(rng_, 1.63, 0.50, 4.77));
    ++moves_;
  }

  /// The robot's virtual finger as a child sees it.
  int touches(std::array<SeenTouch, 6>& out, const StandInTray& tray) const {
    if (item_ < 0) return 0;
    out[0] = {tray.positions_[static_cast<std::size_t>(item_)], item_};
    return 1;
  }

  int moving_item() const { return item_; }
  int moves() const { return moves_; }

 private:
  static constexpr double kReach = 0.38;
  inline static const Vec2 kShoulder{0.30, 0.05};
  Rng rng_;
  bool takes_items_;
  double next_goal_t_ = 0.0;
  int item_ = -1;
  Vec2 from_{0.0, 0.0};
  Vec2 to_{0.0, 0.0};
  double t0_ = 0.0;
  double duration_ = 1.0;
  int moves_ = 0;
};

void fill_partner_from_child(const ChildActions& last, const StandInTray& tray, int partner, PartnerView& view) {
  view.present = true;
  view.is_robot = false;
  view.touch_count = tray.touches_of(partner, view.touches);
  view.gaze = last.gaze;
  view.speech = last.speech;
  view.wants_to_stop = last.quit;
}

ChildOutcome outcome_of(const ChildAgent& child, ChildTimeline coded) {
  return {child.profile(), std::move(coded), child.timeline(), child.quit_time(), child.counters()};
}

}  // namespace

SessionResult simulate_session(const ChildModelParams& params, const SessionConfig& config, std::uint64_t seed) {
  const SeedSequence seeds(seed);
  const bool cc = config.condition == Condition::ChildChild;
  const Population population = config.population.value_or(cc ? Population::pinsoro_child_child()
                                                              : Population::pinsoro_child_robot());
  Rng profile_rng = seeds.stream("profile.purple");
  const ChildProfile purple_profile = config.purple_profile.value_or(population.sample(params.traits, profile_rng));
  profile_rng = seeds.stream("profile.yellow");
  const ChildProfile yellow_profile = config.yellow_profile.value_or(population.sample(params.traits, profile_rng));

  Rng tray_rng = seeds.stream("tray");
  StandInTray tray(tray_rng);
  ChildAgent purple(params, purple_profile, Seat::Bottom, seeds.stream("child.purple"));
  std::optional<ChildAgent> yellow;
  std::optional<StandInRobot> robot;
  if (cc) {
    yellow.emplace(params, yellow_profile, Seat::Top, seeds.stream("child.yellow"));
  } else {
    robot.emplace(seeds.stream("robot"), config.robot_takes_items);
  }

  ChildPerception seen_purple;
  ChildPerception seen_yellow;
  ChildActions last_purple;
  ChildActions last_yellow;
  PairCoder coder(params.coder, !cc);
  std::array<SeenTouch, 6> touches{};
  int last_robot_item = -1;
  const double dt = config.tick_s;
  const double cap = params.session_cap_s;
  double t = 0.0;
  SessionResult result;
  for (long tick = 0;; ++tick) {
    t = static_cast<double>(tick) * dt;
    if (t >= cap) {
      result.hit_cap = true;
      break;
    }
    tray.perceive(0, !cc, seen_purple);
    if (cc) {
      fill_partner_from_child(last_yellow, tray, 1, seen_purple.partner);
      tray.perceive(1, false, seen_yellow);
      fill_partner_from_child(last_purple, tray, 0, seen_yellow.partner);
    } else {
      PartnerView& view = seen_purple.partner;
      view.present = true;
      view.is_robot = true;
      view.touch_count = robot->touches(view.touches, tray);
      view.gaze = GazeTarget{};
      view.gaze.kind = robot->moving_item() >= 0 ? GazeKind::Item : GazeKind::Tray;
      view.gaze.item = robot->moving_item();
      view.speech.reset();
      view.wants_to_stop = false;
    }
    last_purple = purple.step(t, dt, seen_purple);
    if (cc) last_yellow = yellow->step(t, dt, seen_yellow);

    if (last_purple.select_colour) tray.select_colour(*last_purple.select_colour);
    for (int i = 0; i < last_purple.touch_count; ++i) tray.apply(0, last_purple.touches[static_cast<std::size_t>(i)]);
    if (cc) {
      if (last_yellow.select_colour) tray.select_colour(*last_yellow.select_colour);
      for (int i = 0; i < last_yellow.touch_count; ++i) tray.apply(1, last_yellow.touches[static_cast<std::size_t>(i)]);
    } else {
      robot->step(t, tray);
    }

    const ObservedPlayer seen_a = observed_child(last_purple, touches, tray.touches_of(0, touches));
    ObservedPlayer seen_b;
    if (cc) {
      seen_b = observed_child(last_yellow, touches, tray.touches_of(1, touches));
    } else {
      const int n = robot->touches(touches, tray);
      seen_b.touching = n > 0;
      if (n > 0) {
        seen_b.touch_point = touches[0].point;
        seen_b.touch_item = touches[0].item;
      }
      seen_b.touch_started = robot->moving_item() >= 0 && robot->moving_item() != last_robot_item;
      last_robot_item = robot->moving_item();
      seen_b.gaze.kind = robot->moving_item() >= 0 ? GazeKind::Item : GazeKind::Tray;
      seen_b.gaze.item = robot->moving_item();
    }
    coder.observe(t, seen_a, seen_b);

    const bool ended = cc ? (purple.wants_to_stop() && yellow->wants_to_stop()) : purple.wants_to_stop();
    if (ended) break;
  }
  result.duration_s = t;
  purple.finish(t);
  coder.finish(t);
  result.purple = outcome_of(purple, coder.timeline(0));
  if (cc) {
    yellow->finish(t);
    result.yellow = outcome_of(*yellow, coder.timeline(1));
  } else {
    result.robot_moves = robot->moves();
  }
  return result;
}

}  // namespace freeplay::agents
