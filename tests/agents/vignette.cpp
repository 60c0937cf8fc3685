#include "vignette.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

#include <fmt/format.h>

#include "freeplay/agents/params.hpp"

namespace freeplay::agents::vignette {
namespace {

constexpr double kTick = 0.1;      // the coder's sampling period (s)
constexpr double kEpsilon = 1e-6;  // time comparisons on the tick grid

// Scripts are written in seconds; acts start on the 10 Hz tick grid.
double on_tick(double t) { return std::round(t / kTick) * kTick; }

bool in_progress(const Act& act, double t) {
  return act.start <= t + kEpsilon && t < act.start + act.duration - kEpsilon;
}

// Strokes begin one tick after the palette pick, as a finger moves from the palette to the tray.
double finger_down(const Act& act) { return act.kind == Act::Kind::Draw && act.colour ? act.start + kTick : act.start; }

Vec2 finger_point(const Act& act, double t) {
  const double down = finger_down(act);
  const double span = act.start + act.duration - down;
  const double u = span > 0.0 ? std::clamp((t - down) / span, 0.0, 1.0) : 1.0;
  return act.from + u * (act.to - act.from);
}

SpeechEvent utterance(Utterance kind, Addressee to, double seconds) {
  return {kind, to, seconds, std::max(1, static_cast<int>(std::lround(4.0 * seconds)))};
}

GazeTarget looking_at(GazeKind kind) {
  GazeTarget g;
  g.kind = kind;
  return g;
}

GazeTarget looking_at_tray(Vec2 point, int item = -1) {
  GazeTarget g;
  g.kind = item >= 0 ? GazeKind::Item : GazeKind::Tray;
  g.item = item;
  g.point = point;
  return g;
}

// Where a player's eyes are at `t`: a gaze act in progress directs them; else they follow the own finger; else
// they rest on the addressee of an utterance in progress; else on the spot the player last touched.
GazeTarget gaze_of(const Player& self, const ObservedPlayer& own_touch, const ObservedPlayer& partner_touch,
                   const Player& partner, double t, Vec2 own_middle, Vec2 partner_middle) {
  const GazeTarget at_partner = looking_at(self.talks_to_robot() ? GazeKind::Robot : GazeKind::PartnerFace);
  if (const Act* look = self.act_in_progress(t, true)) {
    switch (look->kind) {
      case Act::Kind::LookAtPartner: return at_partner;
      case Act::Kind::LookAtExperimenter: return looking_at(GazeKind::Experimenter);
      case Act::Kind::LookAway: return looking_at(GazeKind::Away);
      case Act::Kind::WatchPartner:
        if (partner_touch.touching) return looking_at_tray(partner_touch.touch_point, partner_touch.touch_item);
        return looking_at_tray(partner.last_touch_point(t, partner_middle));
      default: break;
    }
  }
  if (own_touch.touching) return looking_at_tray(own_touch.touch_point, own_touch.touch_item);
  if (const Act* say = self.act_in_progress(t, false)) {
    return say->speech.to == Addressee::Experimenter ? looking_at(GazeKind::Experimenter) : at_partner;
  }
  return looking_at_tray(self.last_touch_point(t, own_middle));
}

const Vec2 kPurpleMiddle{0.30, -0.28};  // where the purple child's eyes rest before it has touched anything
const Vec2 kSecondMiddle{0.30, -0.05};  // the same for the other player

}  // namespace

Player& PendingAct::at(double t) {
  Act act = act_;
  act.start = on_tick(t);
  player_.add(act);
  return player_;
}

Player& PendingAct::at(std::initializer_list<double> times) {
  for (const double t : times) at(t);
  return player_;
}

Player& PendingAct::every(double period, double from, double until) {
  if (!(period > 0.0)) throw std::invalid_argument("a vignette act repeats with a positive period");
  for (double t = from; t < until - kEpsilon; t += period) at(t);
  return player_;
}

PendingAct Player::drag(std::string_view item, Vec2 from, Vec2 to, double seconds) {
  Act act;
  act.kind = Act::Kind::Drag;
  act.item = item_index(item);
  if (act.item < 0) throw std::invalid_argument(fmt::format("vignette: no item named '{}'", item));
  act.from = from;
  act.to = to;
  act.duration = seconds;
  return {*this, act};
}

PendingAct Player::draw(PaletteColour colour, Vec2 from, Vec2 to, double seconds) {
  Act act;
  act.kind = Act::Kind::Draw;
  act.colour = colour;
  act.from = from;
  act.to = to;
  act.duration = seconds;
  return {*this, act};
}

PendingAct Player::stroke(Vec2 from, Vec2 to, double seconds) {
  Act act;
  act.kind = Act::Kind::Draw;
  act.from = from;
  act.to = to;
  act.duration = seconds;
  return {*this, act};
}

PendingAct Player::tap(Vec2 where) {
  Act act;
  act.kind = Act::Kind::Tap;
  act.from = act.to = where;
  act.duration = 0.2;
  return {*this, act};
}

PendingAct Player::say(Utterance kind, double seconds) {
  Act act;
  act.kind = Act::Kind::Say;
  act.duration = seconds;
  act.speech = utterance(kind, Addressee::Partner, seconds);
  return {*this, act};
}

PendingAct Player::ask_experimenter(Utterance kind, double seconds) {
  Act act;
  act.kind = Act::Kind::Say;
  act.duration = seconds;
  act.speech = utterance(kind, Addressee::Experimenter, seconds);
  return {*this, act};
}

PendingAct Player::look_at_partner(double seconds) {
  Act act;
  act.kind = Act::Kind::LookAtPartner;
  act.duration = seconds;
  return {*this, act};
}

PendingAct Player::look_at_experimenter(double seconds) {
  Act act;
  act.kind = Act::Kind::LookAtExperimenter;
  act.duration = seconds;
  return {*this, act};
}

PendingAct Player::look_away(double seconds) {
  Act act;
  act.kind = Act::Kind::LookAway;
  act.duration = seconds;
  return {*this, act};
}

PendingAct Player::watch_partner(double seconds) {
  Act act;
  act.kind = Act::Kind::WatchPartner;
  act.duration = seconds;
  return {*this, act};
}

ObservedPlayer Player::touch_at(double t) const {
  ObservedPlayer o;
  const Act* touch = nullptr;  // the latest-starting touch in progress
  for (const Act& act : acts_) {
    if (act.kind == Act::Kind::Draw && act.colour && std::abs(act.start - t) < kEpsilon) o.stroke_colour = act.colour;
    if (!act.touches() || !(finger_down(act) <= t + kEpsilon && in_progress(act, t))) continue;
    if (touch == nullptr || act.start >= touch->start) touch = &act;
  }
  if (touch != nullptr) {
    o.touching = true;
    o.touch_point = finger_point(*touch, t);
    o.touch_item = touch->item;
    o.touch_started = t < finger_down(*touch) + kTick - kEpsilon;
  }
  return o;
}

Vec2 Player::last_touch_point(double t, Vec2 seat_middle) const {
  const Act* last = nullptr;
  for (const Act& act : acts_) {
    if (act.touches() && finger_down(act) <= t + kEpsilon && (last == nullptr || act.start >= last->start)) last = &act;
  }
  return last != nullptr ? finger_point(*last, t) : seat_middle;
}

const Act* Player::act_in_progress(double t, bool looks) const {
  const Act* found = nullptr;
  for (const Act& act : acts_) {
    const bool wanted = looks ? act.looks() : act.kind == Act::Kind::Say;
    if (wanted && in_progress(act, t) && (found == nullptr || act.start >= found->start)) found = &act;
  }
  return found;
}

Player& Script::yellow() {
  if (second_is_robot_) throw std::logic_error("vignette: the second player is the robot, not the yellow child");
  return second_;
}

Player& Script::robot() {
  if (!second_is_robot_) throw std::logic_error("vignette: the second player is the yellow child, not the robot");
  return second_;
}

std::array<ObservedPlayer, 2> Script::observe(double t) const {
  std::array<ObservedPlayer, 2> o = {purple_.touch_at(t), second_.touch_at(t)};
  o[0].gaze = gaze_of(purple_, o[0], o[1], second_, t, kPurpleMiddle, kSecondMiddle);
  o[1].gaze = gaze_of(second_, o[1], o[0], purple_, t, kSecondMiddle, kPurpleMiddle);
  const std::array<const Player*, 2> players = {&purple_, &second_};
  for (std::size_t who = 0; who < 2; ++who) {
    for (const Act& act : players[who]->acts()) {
      if (act.kind == Act::Kind::Say && std::abs(act.start - t) < kEpsilon) o[who].speech = act.speech;
    }
  }
  return o;
}

std::string Expectation::describe() const {
  std::string names;
  for (const std::uint8_t l : labels) {
    if (!names.empty()) names += '/';
    names += label_name(axis, l);
  }
  return fmt::format("{} {} over {}–{} s: share in [{:.2f}, {:.2f}]", player == kPurple ? "purple" : "yellow", names,
                     from, to, min_share, max_share);
}

std::string sentences(std::initializer_list<std::string_view> parts) {
  std::string out;
  for (const std::string_view part : parts) {
    if (!out.empty()) out += " | ";
    out += part;
  }
  return out;
}

double coded_share(const ChildTimeline& timeline, const std::vector<std::uint8_t>& labels, double from, double to) {
  int samples = 0;
  int hits = 0;
  for (double t = from + 0.5 * kTick; t < to; t += kTick) {
    ++samples;
    const auto bout = std::find_if(timeline.begin(), timeline.end(),
                                   [t](const LabelInterval& b) { return b.start <= t && t < b.stop; });
    if (bout != timeline.end() && std::find(labels.begin(), labels.end(), bout->label) != labels.end()) ++hits;
  }
  return samples > 0 ? static_cast<double>(hits) / samples : 0.0;
}

std::string bouts_between(const ChildTimeline& timeline, double from, double to) {
  std::string out;
  for (const LabelInterval& b : timeline) {
    if (b.stop <= from || b.start >= to) continue;
    out += fmt::format("{}{} {:.1f}–{:.1f}", out.empty() ? "" : ", ", b.name(), b.start, b.stop);
  }
  return out;
}

namespace {

// One line of a trace: the tick, what each player visibly does, and the labels the coder gives now.
std::string trace_line(double t, const std::array<ObservedPlayer, 2>& seen, const PairCoder& coder, int coded) {
  std::string line = fmt::format("{:6.1f}", t);
  for (std::size_t who = 0; who < 2; ++who) {
    const ObservedPlayer& o = seen[who];
    line += fmt::format(" | {} {}", who == 0 ? "P" : "2", gaze_kind_name(o.gaze.kind));
    if (o.touching) line += fmt::format(" touch({:.2f},{:.2f}) item {}", o.touch_point.x(), o.touch_point.y(), o.touch_item);
    if (o.touch_started) line += " down";
    if (o.stroke_colour) line += fmt::format(" colour {}", static_cast<int>(*o.stroke_colour));
    if (o.speech) line += fmt::format(" says {} to {}", utterance_name(o.speech->kind), addressee_name(o.speech->to));
  }
  for (int who = 0; who < coded; ++who) {
    line += " ||";
    for (const Axis axis : kAxes) line += fmt::format(" {}", label_name(axis, coder.current(who, axis)));
  }
  return line;
}

}  // namespace

void PrintTo(const Vignette& vignette, std::ostream* out) { *out << vignette.name; }

PairCoder run(const Vignette& vignette, std::ostream* trace) {
  static const ChildModelParams params = default_child_model_params();
  Script script(vignette.second_is_robot);
  vignette.write(script);
  PairCoder coder(params.coder, vignette.second_is_robot);
  for (long tick = 0; static_cast<double>(tick) * kTick < vignette.length_s - kEpsilon; ++tick) {
    const double t = static_cast<double>(tick) * kTick;
    const auto seen = script.observe(t);
    coder.observe(t, seen[0], seen[1]);
    if (trace != nullptr) *trace << trace_line(t, seen, coder, vignette.second_is_robot ? 1 : 2) << '\n';
  }
  coder.finish(vignette.length_s);
  return coder;
}

void arrange(Player& player, std::initializer_list<std::string_view> items, Vec2 area, double from, double until,
             double period) {
  // Small moves around the area, as a child tries an animal here, then there.
  static const std::array<Vec2, 5> offsets = {Vec2{-0.04, 0.01}, Vec2{0.03, -0.01}, Vec2{0.0, 0.02},
                                              Vec2{0.05, 0.015}, Vec2{-0.02, -0.015}};
  const std::vector<std::string_view> names(items);
  std::size_t k = 0;
  for (double t = from; t < until - kEpsilon; t += period, ++k) {
    const Vec2 a = area + offsets[k % offsets.size()];
    const Vec2 b = area + offsets[(k + 2) % offsets.size()];
    player.drag(names[k % names.size()], a, b).at(t);
  }
}

void draw_strokes(Player& player, PaletteColour colour, Vec2 area, double from, double until, double period,
                  double stroke_s) {
  std::size_t k = 0;
  for (double t = from; t < until - kEpsilon; t += period, ++k) {
    const double dy = 0.01 * static_cast<double>(k % 3);
    player.draw(colour, area + Vec2{-0.05, dy}, area + Vec2{0.05, dy}, stroke_s).at(t);
  }
}

std::string vignette_name(const ::testing::TestParamInfo<Vignette>& info) { return info.param.name; }

TEST_P(CoderVignette, APersonApplyingTheSchemeAgrees) {
  const Vignette& v = GetParam();
  RecordProperty("situation", v.situation);
  RecordProperty("scheme", v.scheme);
  // VIGNETTE_TRACE=<name> prints the vignette tick by tick: what each player does and the labels coded.
  const char* traced = std::getenv("VIGNETTE_TRACE");
  const PairCoder coder = run(v, traced != nullptr && v.name == traced ? &std::cout : nullptr);
  for (const Expectation& e : v.expected) {
    if (e.player == kYellow && v.second_is_robot) {
      ADD_FAILURE() << v.name << ": " << e.describe() << ": the robot is not coded";
      continue;
    }
    const ChildTimeline& timeline = coder.timeline(e.player, e.axis);
    const double share = coded_share(timeline, e.labels, e.from, e.to);
    const bool holds = share >= e.min_share - kEpsilon && share <= e.max_share + kEpsilon;
    EXPECT_TRUE(holds) << v.name << ": " << e.describe() << ", coded " << fmt::format("{:.2f}", share)
                       << "\n  situation: " << v.situation << "\n  scheme: " << v.scheme
                       << "\n  coded bouts: " << bouts_between(timeline, e.from, e.to);
  }
}

}  // namespace freeplay::agents::vignette

// The script language itself: what a written act looks like to the coder.
namespace freeplay::agents::vignette {
namespace {

TEST(VignetteScript, ADragTouchesItsItemForItsDurationAndStartsOnce) {
  Script s(false);
  s.purple().drag("lion", {0.2, -0.3}, {0.3, -0.3}, 1.0).at(2.0);
  int started = 0;
  int touching = 0;
  for (int tick = 0; tick < 50; ++tick) {
    const ObservedPlayer o = s.observe(tick * 0.1)[0];
    started += o.touch_started ? 1 : 0;
    touching += o.touching ? 1 : 0;
    if (o.touching) {
      EXPECT_EQ(o.touch_item, item_index("lion"));
      EXPECT_EQ(o.gaze.kind, GazeKind::Item);  // the eyes follow the dragging finger
    }
  }
  EXPECT_EQ(started, 1);
  EXPECT_EQ(touching, 10);
  EXPECT_NEAR(s.observe(2.5)[0].touch_point.x(), 0.25, 1e-9);
}

TEST(VignetteScript, ADrawingPicksItsColourThenTouchesOffItemsAndAStrokePicksNothing) {
  Script s(true);
  s.purple().draw(sim::PaletteColour::Green, {0.1, -0.2}, {0.2, -0.2}, 1.0).at(1.0);
  s.purple().stroke({0.1, -0.25}, {0.2, -0.25}, 1.0).at(3.0);
  const ObservedPlayer pick = s.observe(1.0)[0];
  EXPECT_EQ(pick.stroke_colour, sim::PaletteColour::Green);
  EXPECT_FALSE(pick.touching);
  const ObservedPlayer down = s.observe(1.1)[0];
  EXPECT_TRUE(down.touching && down.touch_started);
  EXPECT_EQ(down.touch_item, -1);
  const ObservedPlayer stroke = s.observe(3.0)[0];
  EXPECT_FALSE(stroke.stroke_colour.has_value());
  EXPECT_TRUE(stroke.touching && stroke.touch_started);
}

TEST(VignetteScript, SpeakingIsOneUtteranceLookingAtTheAddressee) {
  Script s(true);
  s.purple().say(Utterance::Proposal, 1.5).at(1.0);
  s.robot().say(Utterance::Comment, 1.0).at(1.0);
  s.purple().ask_experimenter().at(5.0);
  int utterances = 0;
  for (int tick = 0; tick < 30; ++tick) utterances += s.observe(tick * 0.1)[0].speech ? 1 : 0;
  EXPECT_EQ(utterances, 1);
  const auto seen = s.observe(1.0);
  EXPECT_EQ(seen[0].speech->to, Addressee::Partner);
  EXPECT_EQ(seen[0].gaze.kind, GazeKind::Robot);        // a child talking to the robot looks at the robot
  EXPECT_EQ(seen[1].gaze.kind, GazeKind::PartnerFace);  // the robot looks at the child's face
  EXPECT_EQ(s.observe(2.6)[0].gaze.kind, GazeKind::Tray);
  EXPECT_EQ(s.observe(5.0)[0].speech->to, Addressee::Experimenter);
  EXPECT_EQ(s.observe(5.5)[0].gaze.kind, GazeKind::Experimenter);
}

TEST(VignetteScript, WatchingThePartnerFollowsItsFingerAndRestsWhereItLastTouched) {
  Script s(false);
  s.yellow().drag("giraffe", {0.4, -0.05}, {0.5, -0.05}, 1.0).at(1.0);
  s.purple().watch_partner(5.0).at(0.0);
  const GazeTarget during = s.observe(1.5)[0].gaze;
  EXPECT_EQ(during.kind, GazeKind::Item);
  EXPECT_EQ(during.item, item_index("giraffe"));
  EXPECT_NEAR(during.point.x(), 0.45, 1e-9);
  const GazeTarget after = s.observe(3.0)[0].gaze;
  EXPECT_EQ(after.kind, GazeKind::Tray);
  EXPECT_NEAR(after.point.x(), 0.5, 1e-9);
}

TEST(VignetteScript, TheCodedShareCountsTheStretchOnly) {
  const ChildTimeline timeline = {{Axis::SocialEngagement, 2, 0.0, 10.0}, {Axis::SocialEngagement, 4, 10.0, 20.0}};
  EXPECT_NEAR(coded_share(timeline, {4}, 5.0, 15.0), 0.5, 1e-9);
  EXPECT_NEAR(coded_share(timeline, {2, 4}, 0.0, 20.0), 1.0, 1e-9);
  EXPECT_NEAR(coded_share(timeline, {4}, 20.0, 30.0), 0.0, 1e-9);
  EXPECT_THROW(Script(false).robot(), std::logic_error);
  EXPECT_THROW(Script(false).purple().drag("unicorn", {0, 0}, {0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace freeplay::agents::vignette
