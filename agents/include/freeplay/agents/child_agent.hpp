#pragma once
// A synthetic child: semi-Markov states on the three PInSoRo axes, slow drives, a quit hazard, and behaviour
// (touches, gaze, speech) produced through the same channels as a real child.

#include <array>
#include <cstdint>
#include <vector>

#include "freeplay/agents/annotations.hpp"
#include "freeplay/agents/contingency.hpp"
#include "freeplay/agents/params.hpp"
#include "freeplay/agents/perception.hpp"
#include "freeplay/agents/profile.hpp"
#include "freeplay/core/rng.hpp"

namespace freeplay::agents {

/// Counts of what happened to and by one child (for tests, calibration and reports).
struct ChildCounters {
  int drags = 0;                 ///< item drags started
  int taps = 0;                  ///< taps
  int strokes = 0;               ///< drawing strokes (scribbles and fills)
  int utterances = 0;            ///< speech events
  int partner_glances = 0;       ///< fixations on the partner's face (or the robot)
  int contingent_responses = 0;  ///< partner acts that answered a bid of mine (contingent on it and about it)
  int non_contingent_attention = 0;  ///< partner looks at me / words to me that answered nothing of mine
  int interruptions = 0;         ///< of those, the ones that came while I was busy with my own play
  int unanswered_bids = 0;       ///< my seeking bids (looks, words, acts in joint play) the partner did not answer
  int items_taken = 0;           ///< items the partner took from me
  int reactions_to_taking = 0;   ///< immediate attitude switches after an item was taken
  int bids_answered = 0;         ///< my bids the partner answered in time
  int answers = 0;               ///< the partner's bids I answered
  int joins = 0;                 ///< times I joined the partner's joint play when answering
  int joint_play_lapses = 0;     ///< joint play I left because the partner stopped answering
  double contingency_s = 0.0;    ///< time integral of the contingency estimate (divide by the session length)
  double answered_share_s = 0.0; ///< time integral of P(a bid answered) as estimated
  double base_share_s = 0.0;     ///< time integral of the estimated base share of the partner's acts
};

/// One synthetic child. Mutable per-episode state; the parameters must outlive it.
class ChildAgent {
 public:
  /// A child with `profile` on `seat`, drawing every random decision from `rng`.
  ChildAgent(const ChildModelParams& params, const ChildProfile& profile, Seat seat, Rng rng);

  /// Advances the child to time `t` (s) by `dt` given what it perceives; returns what it does this tick.
  ChildActions step(double t, double dt, const ChildPerception& seen);
  /// Closes the open bouts at `t` (end of the session); the timeline is complete afterwards.
  void finish(double t);

  /// Current labels.
  const LabelState& labels() const { return labels_; }
  /// The ground-truth bouts so far (open bouts are added by finish()).
  const ChildTimeline& timeline() const { return timeline_; }
  /// How contingent the child finds its partner, in [0, 1] (ContingencyDetector::contingency).
  double answer_expectation() const { return contingency_.contingency(); }
  /// The child's contingency detector (estimates, habituation).
  const ContingencyDetector& contingency() const { return contingency_; }
  /// Motivation drive in [0, 1].
  double motivation() const { return motivation_; }
  /// Boredom drive (≥ 0).
  double boredom() const { return boredom_; }
  /// True once the child has decided to stop.
  bool wants_to_stop() const { return quit_; }
  /// Time the child decided to stop (negative when it has not).
  double quit_time() const { return quit_time_; }
  /// Fixed characteristics.
  const ChildProfile& profile() const { return profile_; }
  /// Seat side.
  Seat seat() const { return seat_; }
  /// What happened so far.
  const ChildCounters& counters() const { return counters_; }

 private:
  enum class MotorKind : std::uint8_t { None, Drag, Tap, Stroke };
  struct MotorProgram {
    MotorKind kind = MotorKind::None;
    double t0 = 0.0;
    double duration = 0.0;
    Vec2 from{0.0, 0.0};
    Vec2 to{0.0, 0.0};
    int item = -1;
    bool down_sent = false;
    std::array<Vec2, 12> path{};
    int path_len = 0;
  };

  void observe(double t, double dt, const ChildPerception& seen);
  void observe_partner_acts(double t, const PartnerView& partner, int taken_item);
  void on_response(double t, double weight);
  void on_attention(double weight);
  bool busy_with_own_play() const;
  void on_item_taken(double t);
  void become_frustrated(double t);
  void update_drives(double t, double dt);
  void maybe_quit(double t, double dt);
  void advance_labels(double t);
  void switch_label(Axis axis, std::size_t label, double t);
  std::size_t draw_next_label(Axis axis);
  double draw_dwell(Axis axis, std::size_t label);
  double feature(Feature f) const;
  void plan_action(double t, const ChildPerception& seen, ChildActions& out);
  void run_motor(double t, ChildActions& out);
  void update_gaze(double t, const ChildPerception& seen, ChildActions& out);
  void update_speech(double t, double dt, ChildActions& out);
  bool playing_together() const;
  void make_bid(double t, BidKind kind, int item, const Vec2& point, double duration_s, bool seeking);
  void on_partner_bid(double t, bool joint, bool spoken);
  void answer_partner(double t, ChildActions& out);
  double answer_probability() const;
  double bid_scale() const;
  double reciprocity_window() const;
  void sustain_joint_play(double t);
  /// Makes a child that has watched the partner's play for `onlooking_after_s` without acting an onlooker.
  void start_onlooking_when_watching(double t);
  /// Where joint play that lapsed for want of answers goes (the children's exits from it, never up).
  std::size_t lapse_destination(bool partner_playing);
  double reach_depth() const;
  bool reachable(const Vec2& p) const;
  Vec2 clamp_reachable(const Vec2& p) const;
  Vec2 random_own_point();
  double fitts_duration(double distance, double width) const;
  int pick_item(const ChildPerception& seen, const Vec2& near, bool partner_items, bool any_reachable,
                int respected_item = -1);
  Vec2 habitat_destination(const ChildPerception& seen, int item);
  void start_drag(double t, const Vec2& from, const Vec2& to, int item);
  void start_stroke(double t, const Vec2& centre, bool fill);
  void say(Utterance kind, Addressee to, ChildActions& out, double t);

  const ChildModelParams* params_;
  ChildProfile profile_;
  Seat seat_;
  Rng rng_;

  LabelState labels_;
  std::array<double, kAxisCount> bout_start_{};
  std::array<double, kAxisCount> next_switch_{};
  ChildTimeline timeline_;

  double motivation_ = 0.8;
  double boredom_ = 0.0;
  double grievance_ = 0.0;
  double partner_active_ = 0.0;
  double partner_joint_ = 0.0;
  double partner_attention_ = 0.0;
  double decay_scale_ = 1.0;
  bool quit_ = false;
  bool partner_robot_ = false;
  ContingencyDetector contingency_;
  bool partner_quit_ = false;
  bool started_ = false;
  bool announced_stop_ = false;
  double quit_time_ = -1.0;
  double last_t_ = 0.0;

  // Memory of what was seen.
  int prev_partner_touches_ = 0;
  bool prev_partner_looking_ = false;
  int prev_partner_gaze_item_ = -1;
  std::array<HolderView, kMaxSeenItems> prev_holder_{};
  std::array<double, kMaxSeenItems> mine_until_{};
  int my_last_item_ = -1;
  Vec2 my_last_point_{0.0, 0.0};
  int partner_last_item_ = -1;
  Vec2 partner_last_point_{0.3, -0.17};
  double partner_last_t_ = -1e9;
  bool partner_last_was_stroke_ = false;
  double last_answered_t_ = -1e9;
  double partner_last_touch_t_ = -1e9;
  bool eyes_on_partner_play_ = false;  // the current glance rests on the partner's play
  double watched_s_ = 0.0;             // time spent watching the partner's play since my own last act
  struct PendingAnswer {
    bool active = false;
    double due = 0.0;
    bool spoken = false;
    bool join = false;
    SocialEngagement mode = SocialEngagement::Associative;
  } answer_;
  bool retaliation_pending_ = false;
  bool protest_pending_ = false;

  // Behaviour.
  MotorProgram motor_;
  double next_action_t_ = 0.0;
  GazeTarget gaze_;
  double next_glance_t_ = 0.0;
  double speaking_until_ = 0.0;
  PaletteColour colour_ = PaletteColour::Green;

  ChildCounters counters_;
};

}  // namespace freeplay::agents
