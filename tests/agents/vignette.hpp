#pragma once
// Coder vignettes (issue 27 part 3, docs/coder-vignettes.md): hand-made scripts of what two players visibly do, run
// through PairCoder, with the label a person applying the PInSoRo coding scheme would give the coded child over a
// stated stretch, and the sentence of the scheme that decides it.
//
// A script reads like stage directions, e.g.
//   s.purple().drag("lion", {0.20, -0.29}, {0.24, -0.26}).at(3.0);
//   s.robot().look_at_partner().every(4.0, 1.0, 90.0);
//   s.robot().say(Comment, 0.6).every(15.0, 5.0, 90.0);   // "Wow!"
// Times are seconds of free play; the coder sees the script tick by tick at 10 Hz through ObservedPlayer.

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/agents/coder.hpp"

namespace freeplay::agents::vignette {

/// The purple child (bottom edge, y = −0.335): always coded.
inline constexpr int kPurple = 0;
/// The yellow child or the robot (top edge, y = 0): coded only when it is a child.
inline constexpr int kYellow = 1;

/// One timed act of one player, as written in a script.
struct Act {
  /// What the act is.
  enum class Kind : std::uint8_t { Drag, Draw, Tap, Say, LookAtPartner, LookAtExperimenter, LookAway, WatchPartner };
  Kind kind = Kind::Drag;                         ///< what the player does
  double start = 0.0;                             ///< when it begins (s)
  double duration = 1.0;                          ///< how long it lasts (s)
  int item = -1;                                  ///< the dragged item (Drag), index into kItemNames
  Vec2 from{0.0, 0.0};                            ///< where the finger goes down (Drag, Draw, Tap)
  Vec2 to{0.0, 0.0};                              ///< where it lifts (Drag, Draw)
  std::optional<PaletteColour> colour;            ///< the palette colour picked before a stroke (Draw), if any
  SpeechEvent speech;                             ///< the utterance (Say)

  /// True for the acts that put a finger on the screen.
  bool touches() const { return kind == Kind::Drag || kind == Kind::Draw || kind == Kind::Tap; }
  /// True for the acts that direct the eyes.
  bool looks() const { return kind >= Kind::LookAtPartner; }
};

class Player;

/// An act being written: at() or every() places it in time and returns the player for the next act.
class PendingAct {
 public:
  /// An act of `player` not yet placed in time.
  PendingAct(Player& player, const Act& act) : player_(player), act_(act) {}
  /// Places the act once, starting at `t`.
  Player& at(double t);
  /// Places the act at each of `times`.
  Player& at(std::initializer_list<double> times);
  /// Places the act every `period` s, the first at `from`, none starting at or after `until`.
  Player& every(double period, double from, double until);

 private:
  Player& player_;
  Act act_;
};

/// What one player visibly does during a vignette: a list of timed acts.
class Player {
 public:
  /// A player; `talks_to_robot` when its partner is the robot (its looks at the partner land on the robot).
  explicit Player(bool talks_to_robot = false) : talks_to_robot_(talks_to_robot) {}

  /// Drags `item` (a name of kItemNames) from `from` to `to` in `seconds`.
  PendingAct drag(std::string_view item, Vec2 from, Vec2 to, double seconds = 1.5);
  /// Picks `colour` on the palette, then draws one stroke from `from` to `to` in `seconds`.
  PendingAct draw(PaletteColour colour, Vec2 from, Vec2 to, double seconds = 2.0);
  /// Draws one more stroke with the colour already picked (no palette tap).
  PendingAct stroke(Vec2 from, Vec2 to, double seconds = 2.0);
  /// Taps the tray at `where`, off any item.
  PendingAct tap(Vec2 where);
  /// Says an utterance of `kind` to the partner, lasting `seconds`; the eyes go to the partner unless a finger drags.
  PendingAct say(Utterance kind, double seconds = 1.5);
  /// Says an utterance of `kind` to the experimenter, looking at her.
  PendingAct ask_experimenter(Utterance kind = Utterance::Question, double seconds = 1.5);
  /// Looks at the partner (its face, or the robot) for `seconds`.
  PendingAct look_at_partner(double seconds = 1.0);
  /// Looks at the experimenter for `seconds`.
  PendingAct look_at_experimenter(double seconds = 1.5);
  /// Looks away from the screen and the partner for `seconds`.
  PendingAct look_away(double seconds);
  /// Keeps the eyes on the partner's play (its finger, the item it drags, else where it last touched) for `seconds`.
  PendingAct watch_partner(double seconds);

  /// Adds a placed act (used by PendingAct).
  void add(const Act& act) { acts_.push_back(act); }
  /// Every act written so far.
  const std::vector<Act>& acts() const { return acts_; }
  /// True when the partner is the robot.
  bool talks_to_robot() const { return talks_to_robot_; }

  /// The touch of the player at `t`: finger, point, item, a new touch, a palette pick (gaze and speech left empty).
  ObservedPlayer touch_at(double t) const;
  /// Where the player last touched the screen at or before `t` (its seat's middle when it never did).
  Vec2 last_touch_point(double t, Vec2 seat_middle) const;
  /// The act of `kind`-class (`looks` true: gaze acts; false: Say) in progress at `t`, or nullptr.
  const Act* act_in_progress(double t, bool looks) const;

 private:
  bool talks_to_robot_ = false;
  std::vector<Act> acts_;
};

/// The two players of one vignette.
class Script {
 public:
  /// A script for a child–child pair, or a child–robot pair when `second_is_robot`.
  explicit Script(bool second_is_robot) : second_is_robot_(second_is_robot), purple_(second_is_robot) {}

  /// The purple child (player 0).
  Player& purple() { return purple_; }
  /// The yellow child (player 1 of a child–child pair).
  Player& yellow();
  /// The robot (player 1 of a child–robot pair).
  Player& robot();
  /// True when the second player is the robot.
  bool second_is_robot() const { return second_is_robot_; }

  /// What both players visibly do at tick time `t`.
  std::array<ObservedPlayer, 2> observe(double t) const;

 private:
  bool second_is_robot_;
  Player purple_;
  Player second_;
};

/// What a person applying the scheme says about one coded player over one stretch: the share of the time coded
/// with one of `labels` on `axis` lies in [min_share, max_share].
struct Expectation {
  int player = kPurple;               ///< kPurple or kYellow
  Axis axis = Axis::SocialEngagement; ///< the axis judged
  std::vector<std::uint8_t> labels;   ///< the labels counted
  double from = 0.0;                  ///< the stretch judged (s)
  double to = 0.0;                    ///< its end (s)
  double min_share = 0.0;             ///< least share of the stretch carrying one of the labels
  double max_share = 1.0;             ///< most share

  /// A sentence for failure messages, e.g. "purple cooperative over 15–90 s: share in [0.70, 1.00]".
  std::string describe() const;
};

/// The axis of a task engagement label.
constexpr Axis axis_of(TaskEngagement) { return Axis::TaskEngagement; }
/// The axis of a social engagement label.
constexpr Axis axis_of(SocialEngagement) { return Axis::SocialEngagement; }
/// The axis of a social attitude label.
constexpr Axis axis_of(SocialAttitude) { return Axis::SocialAttitude; }

/// Share of a person's label that counts as "mostly": the coder may lag a few seconds and split a bout.
inline constexpr double kMostly = 0.7;
/// Share that counts as "never": room for one switching lag of the coder, not for a bout.
inline constexpr double kNever = 0.05;

/// `player` is coded `label` for at least `share` of [from, to).
template <typename Label>
Expectation mostly(int player, Label label, double from, double to, double share = kMostly) {
  return {player, axis_of(label), {static_cast<std::uint8_t>(label)}, from, to, share, 1.0};
}
/// `player` is coded one of `labels` (one axis) for at least `share` of [from, to).
template <typename Label>
Expectation mostly_one_of(int player, std::initializer_list<Label> labels, double from, double to,
                          double share = kMostly) {
  Expectation e{player, axis_of(*labels.begin()), {}, from, to, share, 1.0};
  for (const Label l : labels) e.labels.push_back(static_cast<std::uint8_t>(l));
  return e;
}
/// `player` is (almost) never coded `label` in [from, to): at most `share` of it.
template <typename Label>
Expectation never(int player, Label label, double from, double to, double share = kNever) {
  return {player, axis_of(label), {static_cast<std::uint8_t>(label)}, from, to, 0.0, share};
}

/// The sentences of the coding scheme that decide the vignettes' labels: the seed paper's coding-scheme section,
/// the PInSoRo website's wording (free-play-sandbox.md §5), and issue 27's reading of Parten's stages.
namespace scheme {
/// Social engagement: solitary play.
inline constexpr std::string_view kSolitary =
    "solitary: playing alone (paper: 'one child is drawing and the other is observing is labelled as solitary play "
    "for the former child')";
/// Social engagement: onlooker.
inline constexpr std::string_view kOnlooker =
    "onlooker: 'looking at the other for a prolonged period, without engaging' (website); paper: 'one child is "
    "drawing and the other is observing is labelled ... on-looker behaviour for the latter'";
/// Social engagement: parallel play.
inline constexpr std::string_view kParallel =
    "parallel: similar materials or activity near the partner, without interacting";
/// Social engagement: associative play.
inline constexpr std::string_view kAssociative =
    "associative: the child itself initiates or responds to interaction about the play (talks about it, offers or "
    "shares items, follows the partner's activity), no shared goal";
/// Social engagement: cooperative play.
inline constexpr std::string_view kCooperative =
    "cooperative: the child's own acts are coordinated with the partner's towards a shared product over a sustained "
    "stretch (complementary roles, building one scene, taking turns on one item)";
/// Social engagement: the paper's example of cooperation.
inline constexpr std::string_view kDiscussing =
    "paper: 'the two children discuss what to do next: this sequence is annotated as a cooperative behaviour'";
/// Social engagement: the partner's acts alone do not code the child.
inline constexpr std::string_view kNotMe = "the partner's act near my item does not make ME cooperative";
/// Social engagement: a child's answer to a partner engaged in associative play with it is part of that play.
inline constexpr std::string_view kResponds =
    "associative: 'the child itself initiates or RESPONDS to interaction about the play' (issue 27's reading of "
    "Parten): answering in words a partner that talks about the play";
/// Social engagement: the scheme has no label for a child that is not playing at all.
inline constexpr std::string_view kNoUnoccupied =
    "social engagement: Parten's play stages minus 'unoccupied' (the scheme's label set): a pause of both children "
    "is not coded as a new kind of play";
/// Social engagement: a returned glance is not play.
inline constexpr std::string_view kGlance = "a glance that answers a comment is not associative play";
/// Task engagement: goal oriented.
inline constexpr std::string_view kGoalOriented =
    "goal oriented: 'considered, planned actions (that might be social or not)' (paper); 'purposeful/structured "
    "play' (website)";
/// Task engagement: aimless.
inline constexpr std::string_view kAimless =
    "aimless: 'being silly, chatting about unrelated matters, having a good laugh' (paper); 'unstructured, silly "
    "play' (website)";
/// Task engagement: adult seeking.
inline constexpr std::string_view kAdultSeeking = "adult seeking: 'ask question, seek approval' (website)";
/// Task engagement: no play.
inline constexpr std::string_view kNoPlay = "no play: the child does not play with the game";
/// Social attitude: adversarial.
inline constexpr std::string_view kAdversarial =
    "adversarial: the SCCS 'hostile' construct, broadened (paper); taking what the other is playing with";
/// Social attitude: assertive.
inline constexpr std::string_view kAssertive = "assertive: 'i.e. dominant' (paper); 'incl. bossy/manipulative' (website)";
/// Social attitude: frustrated.
inline constexpr std::string_view kFrustrated =
    "frustrated: 'children who are reluctant or refuse to engage ... because of a perceived lack of fairness or "
    "attention from their peer' (paper)";
/// Social attitude: prosocial.
inline constexpr std::string_view kProsocial = "pro-social: the SCCS construct (paper): friendly, helpful acts";
/// Social attitude: passive.
inline constexpr std::string_view kPassive = "passive: 'passive/bored' (the paper's figure)";
}  // namespace scheme

/// One vignette: a situation, the scheme sentence that decides its label, a script and a person's labels.
struct Vignette {
  std::string name;                     ///< test name, after the situation
  std::string situation;                ///< what happens, in words
  std::string scheme;                   ///< the sentence of the coding scheme that decides the label
  bool second_is_robot = false;         ///< the second player is the robot
  double length_s = 60.0;               ///< how long the script runs (s)
  std::function<void(Script&)> write;   ///< writes the script
  std::vector<Expectation> expected;    ///< a person's labels
};

/// The scheme sentences that decide a vignette, joined with " | ".
std::string sentences(std::initializer_list<std::string_view> parts);

/// Share of [from, to) (sampled every 0.1 s) that `timeline` codes with one of `labels`.
double coded_share(const ChildTimeline& timeline, const std::vector<std::uint8_t>& labels, double from, double to);
/// The bouts of `timeline` that overlap [from, to), as "label a–b s" separated by commas.
std::string bouts_between(const ChildTimeline& timeline, double from, double to);

/// Runs `vignette` through a PairCoder with the shipped coder parameters at 10 Hz and returns the coder; with
/// `trace`, writes one line per tick on which something is seen or a label changes (for debugging a coder).
PairCoder run(const Vignette& vignette, std::ostream* trace = nullptr);
/// Prints a vignette as its name (gtest's parameter printer).
void PrintTo(const Vignette& vignette, std::ostream* out);

/// Arranges `items` in turn in the area around `area`, one drag of 1.5 s every `period` s from `from` on, none
/// starting at or after `until` (a child playing on its own with the animals).
void arrange(Player& player, std::initializer_list<std::string_view> items, Vec2 area, double from, double until,
             double period = 4.0);
/// Draws strokes of `colour` around `area`, one of `stroke_s` every `period` s, picking the colour before each.
void draw_strokes(Player& player, PaletteColour colour, Vec2 area, double from, double until, double period = 4.0,
                  double stroke_s = 2.0);

/// The vignette test: each expectation of the vignette holds for the coder's timelines.
class CoderVignette : public ::testing::TestWithParam<Vignette> {};

/// The test name of a vignette (its `name`).
std::string vignette_name(const ::testing::TestParamInfo<Vignette>& info);

}  // namespace freeplay::agents::vignette
