#pragma once
// The coder: assigns the three coding-scheme labels (task engagement, social engagement, social attitude) to the
// children of a session from what they visibly did, as the human annotator of PInSoRo did while watching the
// recording (docs/agents.md, "The coder").
//
// It never sees a child's drives or intentions: only touches (where, on which item, with which colour), gaze
// targets and speech (kind, addressee), tick by tick. Both players are coded together, as one coder annotated
// both children.

#include <array>
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

/// Codes both players of one session on the three axes (task engagement, social engagement, social attitude), tick
/// by tick.
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
  struct Track {
    double last_touch_t = -1e9;
    Vec2 last_touch_point{0.0, 0.0};
    int last_item = -1;
    double last_attend_t = -1e9;
    bool last_attend_proposal = false;
    bool last_attend_spoken = false;
    double last_joint_t = -1e9;
    double watch = 0.0;  // running share of time spent watching the other's play
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
  void track_task_and_attitude(double t, double dt, int who, const ObservedPlayer& self, bool answered);
  SocialEngagement candidate(double t, int who) const;
  TaskEngagement task_candidate(double t, int who) const;
  SocialAttitude attitude_candidate(double t, int who) const;
  void code(double t, int who, Axis axis, std::uint8_t label);

  CoderParams params_;
  bool second_is_robot_;
  bool started_ = false;
  double last_t_ = 0.0;
  std::array<Track, 2> tracks_{};
  std::array<GazeTarget, 2> prev_gaze_{};
  std::array<std::array<Coded, kAxisCount>, 2> coded_{};
  double last_exchange_t_ = -1e9;
  double exchange_start_t_ = -1e9;
};


/// Share of the time in [0, end) where two timelines carry the same label on `axis` (sampled every `step` s).
double timeline_agreement(const ChildTimeline& a, const ChildTimeline& b, Axis axis, double end, double step = 1.0);

}  // namespace freeplay::agents
