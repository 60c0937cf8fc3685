#pragma once
// The coder: assigns the three coding-scheme labels (task engagement, social engagement, social attitude) to the
// children of a session from what they visibly did, as the human annotator of PInSoRo did while watching the
// recording (docs/agents.md, "The coder").
//
// It never sees a child's drives or intentions: only touches (where, on which item, with which colour), gaze
// targets and speech (kind, addressee), tick by tick. Both players are coded together, as one coder annotated
// both children.

#include <array>
#include <limits>
#include <cmath>
#include <cstdint>
#include <optional>

#include "freeplay/agents/annotations.hpp"
#include "freeplay/agents/params.hpp"
#include "freeplay/agents/perception.hpp"

namespace freeplay::agents {

/// What one player (a child or the robot) visibly did during one tick.
struct ObservedPlayer {
  bool touching = false;                   ///< a finger (or the robot's virtual finger) is on the screen
  Vec2 touch_point{0.0, 0.0};              ///< where (sandtray frame), when touching
  int touch_item = -1;                     ///< the item under that finger (index into kItemNames), −1 for none
  bool touch_started = false;              ///< a new touch began this tick
  GazeTarget gaze;                         ///< where the player looks (PartnerFace / Robot: at the other player)
  std::optional<SpeechEvent> speech;       ///< an utterance that started this tick
  std::optional<PaletteColour> stroke_colour;  ///< a colour picked on the palette this tick (a drawing begins)
};

/// True for the palette colours that draw the game's landscape (water, grass, sand): blue, green and yellow.
bool draws_landscape(PaletteColour colour);

/// What a child visibly did this tick: its actions, and its fingers on the screen (`touches`, first `touch_count`).
ObservedPlayer observed_child(const ChildActions& actions, const std::array<SeenTouch, 6>& touches, int touch_count);

/// Codes both players of one session on the three axes, tick by tick, each from its own observable behaviour
/// towards the other (docs/agents.md, "The coder": every rule beside the scheme sentence it implements).
class PairCoder {
 public:
  /// A coder with `params`; `second_is_robot` when the second player is the robot (it is not coded then).
  PairCoder(const CoderParams& params, bool second_is_robot);

  /// Adds one tick at time `t` (s): what the first (purple) and the second (yellow or robot) player did.
  void observe(double t, const ObservedPlayer& first, const ObservedPlayer& second);
  /// Closes the open bouts at `t`; the timelines are complete afterwards.
  void finish(double t);

  /// The coded bouts of every axis of player 0 (purple) or 1 (yellow; empty when it is the robot), sorted by start.
  ChildTimeline timeline(int player) const;
  /// The coded bouts of one axis of player 0 or 1, in time order.
  const ChildTimeline& timeline(int player, Axis axis) const {
    return coded_[static_cast<std::size_t>(player)][static_cast<std::size_t>(axis)].timeline;
  }
  /// The label player 0 or 1 is coded with now on `axis` (the bout in progress).
  std::uint8_t current(int player, Axis axis) const {
    return coded_[static_cast<std::size_t>(player)][static_cast<std::size_t>(axis)].label;
  }

 private:
  /// Most recent acts of one kind kept per player (times, newest last).
  static constexpr std::size_t kRecentActs = 8;
  /// The times of a player's recent acts of one kind.
  struct RecentActs {
    std::array<double, kRecentActs> t{};
    std::size_t count = 0;
    void add(double time);
    int since(double from) const;
    /// The earliest kept act at or after `from` (+∞ when none).
    double first_since(double from) const;
    double last() const { return count == 0 ? -1e9 : t[(count - 1) % kRecentActs]; }
  };
  static std::array<Vec2, 10> unplaced() {
    std::array<Vec2, 10> out;
    out.fill(Vec2(std::nan(""), std::nan("")));
    return out;
  }
  struct Track {
    double last_touch_t = -1e9;
    Vec2 last_touch_point{0.0, 0.0};
    int last_item = -1;
    bool was_touching = false;
    int touch_item = -1;              // the item under the finger since its touch began (−1: drawing or nothing)
    Vec2 touch_start{0.0, 0.0};       // where that touch began
    double touch_start_t = -1e9;      // when
    bool touch_followed = false;      // that touch already counted as following the other's activity
    double last_release_t = -1e9;     // when the last drag of an item ended
    Vec2 last_release_point{0.0, 0.0};
    int last_moved_item = -1;         // the item that drag moved
    std::array<Vec2, 10> placed_at = unplaced();  // where this player last put each item down (NaN: never)
    double last_stroke_t = -1e9;      // when the last drawing touch was seen
    Vec2 last_stroke_point{0.0, 0.0};
    double last_look_at_other_t = -1e9;
    double last_talk_t = -1e9;        // words to the other (any kind but protests and stop announcements)
    double last_proposal_t = -1e9;
    RecentActs interaction;           // own acts of interaction about the play: talk while playing, follows, offers
    RecentActs follows;               // own acts that follow the other's activity (its item, its spot)
    double last_discussion_t = -1e9;  // took part in talk about what to do next (a proposal answered in words)
    double watch = 0.0;               // running share of time spent watching the other's play
    // Task engagement evidence.
    bool landscape_stroke = false;  // the current drawing uses a landscape colour
    bool drawing = false;           // a colour was picked and the drawing finger has not left the screen since
    bool stroke_touched = false;    // the drawing finger has been seen on the screen
    double last_constructive_t = -1e9;
    double last_aimless_t = -1e9;
    double last_adult_t = -1e9;
    // Social attitude evidence.
    std::array<double, 10> held_t{};  // when this player last held each item
    int holding = -1;                 // the item under this player's finger at the previous tick
    double last_take_t = -1e9;
    double last_protest_t = -1e9;
    double last_directive_t = -1e9;
    double last_friendly_t = -1e9;
    // Running shares (over `judgement_window_s`) of time with recent considered play, other play and friendly acts.
    double constructive = 0.0;
    double aimless = 0.0;
    double friendly = 0.0;
  };
  struct Coded {
    std::uint8_t label = 0;
    double bout_start = 0.0;
    std::uint8_t candidate = 0;
    double candidate_since = 0.0;
    ChildTimeline timeline;
  };

  void track(double t, double dt, int who, const ObservedPlayer& self);
  void track_touch(double t, int who, const ObservedPlayer& self);
  void track_words(double t, int who, const ObservedPlayer& self);
  void track_task_and_attitude(double t, double dt, int who, const ObservedPlayer& self);
  bool interacting(double t, int who) const;
  bool onlooking(double t, int who) const;
  bool takes(double t, int who, int item);
  static bool on_own_half(int who, const Vec2& point);
  bool plays(double t, int who, double window) const;
  SocialEngagement candidate(double t, int who) const;
  /// The pair rule: `who`'s social label given its own (`mine`) and the other's own (`theirs`) evidence.
  SocialEngagement joins_in(double t, int who, SocialEngagement mine, SocialEngagement theirs) const;
  TaskEngagement task_candidate(double t, int who) const;
  SocialAttitude attitude_candidate(double t, int who) const;
  /// Codes `label` for `who` on `axis` at `t` once it has held its minimum bout; the new bout starts where its
  /// sequence visibly began: when the label became the candidate, or `opened` when that is earlier (the opening
  /// move of a cooperation), never before the bout it ends.
  void code(double t, int who, Axis axis, std::uint8_t label, double opened = std::numeric_limits<double>::infinity());
  /// When the cooperation `who` is coded into at `t` visibly began: its own first act of following the other's
  /// activity within `cooperation_window_s`.
  double cooperation_opened(double t, int who) const;

  CoderParams params_;
  bool second_is_robot_;
  bool started_ = false;
  double last_t_ = 0.0;
  std::array<Track, 2> tracks_{};
  double proposal_answered_t_ = -1e9;  // when one player last answered the other's proposal in words
  RecentActs replies_;                 // remarks about the play that answered the other's, by either player
  std::array<GazeTarget, 2> prev_gaze_{};
  std::array<std::array<Coded, kAxisCount>, 2> coded_{};
};

/// Share of the time in [0, end) where two timelines carry the same label on `axis` (sampled every `step` s).
double timeline_agreement(const ChildTimeline& a, const ChildTimeline& b, Axis axis, double end, double step = 1.0);

}  // namespace freeplay::agents
