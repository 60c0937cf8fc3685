#pragma once
// The coder: assigns social-engagement labels to both players of a session from what they visibly did, as the
// human annotator of PInSoRo did while watching the recording (docs/agents.md, "The coder").
//
// It never sees a child's drives or intentions: only touches (where, on which item), gaze targets and speech
// (kind, addressee), tick by tick. Both players are coded together, as one coder annotated both children.

#include <array>
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
};

/// What a child visibly did this tick: its actions, and its fingers on the screen (`touches`, first `touch_count`).
ObservedPlayer observed_child(const ChildActions& actions, const std::array<SeenTouch, 6>& touches, int touch_count);

/// Codes the social engagement of both players of one session, tick by tick.
class PairCoder {
 public:
  /// A coder with `params`; `second_is_robot` when the second player is the robot (it is not coded then).
  PairCoder(const CoderParams& params, bool second_is_robot);

  /// Adds one tick at time `t` (s): what the first (purple) and the second (yellow or robot) player did.
  void observe(double t, const ObservedPlayer& first, const ObservedPlayer& second);
  /// Closes the open bouts at `t`; the timelines are complete afterwards.
  void finish(double t);

  /// The social-engagement bouts of player 0 (purple) or 1 (yellow; empty when it is the robot).
  const ChildTimeline& timeline(int player) const { return coded_[static_cast<std::size_t>(player)].timeline; }

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
  };
  struct Coded {
    SocialEngagement label = SocialEngagement::Solitary;
    double bout_start = 0.0;
    SocialEngagement candidate = SocialEngagement::Solitary;
    double candidate_since = 0.0;
    ChildTimeline timeline;
  };

  void track(double t, double dt, int who, const ObservedPlayer& self);
  SocialEngagement candidate(double t, int who) const;
  void code(double t, int who, SocialEngagement label);

  CoderParams params_;
  bool second_is_robot_;
  bool started_ = false;
  double last_t_ = 0.0;
  std::array<Track, 2> tracks_{};
  std::array<GazeTarget, 2> prev_gaze_{};
  std::array<Coded, 2> coded_{};
  double last_exchange_t_ = -1e9;
  double exchange_start_t_ = -1e9;
};

/// `internal` with its social-engagement bouts replaced by `coded_social` (sorted by start, as annotations are).
ChildTimeline with_coded_social(const ChildTimeline& internal, const ChildTimeline& coded_social);

/// Share of the time in [0, end) where two timelines carry the same label on `axis` (sampled every `step` s).
double timeline_agreement(const ChildTimeline& a, const ChildTimeline& b, Axis axis, double end, double step = 1.0);

}  // namespace freeplay::agents
