#include "freeplay/agents/coder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "freeplay/core/error.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::agents {
namespace {

/// Words about the play within the interaction hold that show a prosocial attitude.
constexpr int kProsocialWords = 2;

bool looks_at_other(const GazeTarget& gaze) {
  return gaze.kind == GazeKind::PartnerFace || gaze.kind == GazeKind::Robot;
}

}  // namespace

ObservedPlayer observed_child(const ChildActions& actions, const std::array<SeenTouch, 6>& touches, int touch_count) {
  ObservedPlayer o;
  o.touching = touch_count > 0;
  if (o.touching) {
    o.touch_point = touches[0].point;
    o.touch_item = touches[0].item;
  }
  for (int i = 0; i < actions.touch_count; ++i) {
    if (actions.touches[static_cast<std::size_t>(i)].phase == TouchPhase::Down) o.touch_started = true;
  }
  o.gaze = actions.gaze;
  o.speech = actions.speech;
  o.stroke_colour = actions.select_colour;
  return o;
}

bool draws_landscape(PaletteColour colour) {
  return colour == PaletteColour::Blue || colour == PaletteColour::Green || colour == PaletteColour::Yellow;
}

PairCoder::PairCoder(const CoderParams& params, bool second_is_robot)
    : params_(params), second_is_robot_(second_is_robot) {}

void PairCoder::RecentActs::add(double time) {
  t[count % kRecentActs] = time;
  ++count;
}

int PairCoder::RecentActs::since(double from) const {
  int n = 0;
  for (std::size_t k = 0; k < std::min(count, kRecentActs); ++k) n += t[k] >= from ? 1 : 0;
  return n;
}

double PairCoder::RecentActs::first_since(double from) const {
  double first = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < std::min(count, kRecentActs); ++k) {
    if (t[k] >= from) first = std::min(first, t[k]);
  }
  return first;
}

double PairCoder::cooperation_opened(double t, int who) const {
  const Track& me = tracks_[static_cast<std::size_t>(who)];
  const double from = t - params_.cooperation_window_s;
  return me.follows.first_since(from);
}

void PairCoder::track(double t, double dt, int who, const ObservedPlayer& self) {
  Track& me = tracks_[static_cast<std::size_t>(who)];
  const Track& them = tracks_[static_cast<std::size_t>(1 - who)];
  track_touch(t, who, self);
  track_words(t, who, self);
  track_task_and_attitude(t, dt, who, self);
  // A look that lands on the other (not a gaze resting on it all along) is attention paid to it.
  if (looks_at_other(self.gaze) && !looks_at_other(prev_gaze_[static_cast<std::size_t>(who)])) {
    me.last_look_at_other_t = t;
  }
  // Onlooker — "looking at the other for a prolonged period, without engaging": the gaze rests on the other's
  // finger, on the item it moves, or on the other itself while it plays.
  bool watching = false;
  if (t - them.last_touch_t <= params_.active_window_s) {
    watching = (self.gaze.kind == GazeKind::Item && self.gaze.item >= 0 && self.gaze.item == them.last_item) ||
               (self.gaze.kind == GazeKind::Tray && (self.gaze.point - them.last_touch_point).norm() < 0.08) ||
               looks_at_other(self.gaze);
  }
  const double w = 1.0 - std::exp(-dt / params_.watch_window_s);
  me.watch += w * ((watching ? 1.0 : 0.0) - me.watch);
  prev_gaze_[static_cast<std::size_t>(who)] = self.gaze;
}

bool PairCoder::on_own_half(int who, const Vec2& point) {
  return who == 0 ? point.y() < -0.5 * sim::kScreenHeightM : point.y() >= -0.5 * sim::kScreenHeightM;
}

void PairCoder::track_touch(double t, int who, const ObservedPlayer& self) {
  Track& me = tracks_[static_cast<std::size_t>(who)];
  Track& them = tracks_[static_cast<std::size_t>(1 - who)];
  const double recent = t - params_.follow_window_s;
  if (self.touch_started || (self.touching && !me.was_touching)) {
    me.touch_item = self.touch_item;
    me.touch_start = self.touch_point;
    me.touch_start_t = t;
    const bool taken = takes(t, who, self.touch_item);
    // Associative — "follows the partner's activity": taking up the item the other just moved (taking turns on
    // one item), or drawing where the other just drew; taking it from the other is no following.
    const bool their_item = self.touch_item >= 0 && self.touch_item == them.last_moved_item &&
                            them.last_release_t >= recent && !taken;
    const bool their_drawing = self.touch_item < 0 && them.last_stroke_t >= recent &&
                               (self.touch_point - them.last_stroke_point).norm() < params_.joint_distance_m;
    me.touch_followed = their_item || their_drawing;
    if (me.touch_followed) me.follows.add(t);
  }
  if (self.touching) {
    me.last_touch_t = t;
    me.last_touch_point = self.touch_point;
    if (self.touch_item >= 0) me.last_item = self.touch_item;
    if (self.touch_item < 0) {
      me.last_stroke_t = t;
      me.last_stroke_point = self.touch_point;
    }
  } else if (me.was_touching && me.touch_item >= 0) {
    // A drag ended. Cooperative — "building one scene": bringing an item from elsewhere to the spot where the other
    // just put one (when that spot is not where I was playing anyway).
    const Vec2& end = me.last_touch_point;
    const Vec2& spot = them.last_release_point;
    const bool to_their_spot = them.last_release_t >= recent && (end - spot).norm() < params_.joint_distance_m &&
                               (me.touch_start - spot).norm() >= params_.joint_distance_m &&
                               (me.last_release_point - spot).norm() >= params_.joint_distance_m;
    if (to_their_spot && !me.touch_followed) me.follows.add(t);
    me.last_release_t = t;
    me.last_release_point = end;
    me.last_moved_item = me.touch_item;
    if (static_cast<std::size_t>(me.touch_item) < me.placed_at.size()) {
      me.placed_at[static_cast<std::size_t>(me.touch_item)] = end;
    }
  }
  me.was_touching = self.touching;
}

void PairCoder::track_words(double t, int who, const ObservedPlayer& self) {
  Track& me = tracks_[static_cast<std::size_t>(who)];
  Track& them = tracks_[static_cast<std::size_t>(1 - who)];
  if (!self.speech || self.speech->to != Addressee::Partner) return;
  const Utterance kind = self.speech->kind;
  if (kind == Utterance::Protest || kind == Utterance::AnnounceStop) return;
  // Associative — "talks about it": words to the other while play is going on are about the play.
  const bool about_play = plays(t, who, params_.talk_play_window_s) || plays(t, 1 - who, params_.talk_play_window_s);
  if (about_play) me.interaction.add(t);
  // A remark that answers the other's (within the answer window) is a turn of a conversation between the two.
  if (about_play && t - them.last_talk_t <= params_.answer_window_s) replies_.add(t);
  // Cooperative — "the two children discuss what to do next": a proposal, answered in words by the other, and a
  // further word from either (three turns, each within the answer window of the one before) is a discussion,
  // and both speakers take part in it. A remark that happens to follow a proposal is not yet a discussion.
  const bool answers = t - them.last_talk_t <= params_.answer_window_s;
  if (answers && them.last_proposal_t > me.last_talk_t && t - them.last_proposal_t <= params_.answer_window_s) {
    proposal_answered_t_ = t;
  } else if (t > proposal_answered_t_ && t - proposal_answered_t_ <= params_.answer_window_s) {
    me.last_discussion_t = t;
    them.last_discussion_t = t;
  }
  me.last_talk_t = t;
  if (kind == Utterance::Proposal) me.last_proposal_t = t;
}

bool PairCoder::takes(double t, int who, int item) {
  Track& me = tracks_[static_cast<std::size_t>(who)];
  const Track& them = tracks_[static_cast<std::size_t>(1 - who)];
  if (item < 0 || static_cast<std::size_t>(item) >= me.held_t.size() || item == me.holding) return false;
  const auto k = static_cast<std::size_t>(item);
  // Adversarial: grabbing what the other was just playing with, while the two are not playing together. An item
  // the other put down on my half was passed to me, not taken; asking first and then taking it is "gentle
  // grabbing", which the scheme counts as assertive.
  const bool theirs = them.held_t[k] > me.held_t[k] && t - them.held_t[k] <= params_.take_window_s &&
                      !(them.holding != item && on_own_half(who, them.placed_at[k]));
  const bool together = interacting(t, who) && interacting(t, 1 - who);
  if (!theirs || together) return false;
  (t - me.last_directive_t <= params_.assertive_hold_s ? me.last_directive_t : me.last_take_t) = t;
  return true;
}

bool PairCoder::onlooking(double t, int who) const {
  // Onlooker — a child that has stopped and keeps its eyes on the other's play.
  const Track& me = tracks_[static_cast<std::size_t>(who)];
  const bool stopped = t - me.last_touch_t > 0.5 * params_.min_bout_s;
  return stopped && plays(t, 1 - who, params_.active_window_s) && me.watch >= params_.watch_share;
}

bool PairCoder::plays(double t, int who, double window) const {
  return t - tracks_[static_cast<std::size_t>(who)].last_touch_t <= window;
}

bool PairCoder::interacting(double t, int who) const {
  const Track& me = tracks_[static_cast<std::size_t>(who)];
  return t - me.interaction.last() <= params_.interaction_hold_s || t - me.last_discussion_t <= params_.discussion_hold_s;
}

void PairCoder::track_task_and_attitude(double t, double dt, int who, const ObservedPlayer& self) {
  Track& me = tracks_[static_cast<std::size_t>(who)];
  const Track& them = tracks_[static_cast<std::size_t>(1 - who)];
  // Task engagement: moving items and drawing the landscape are the game's considered actions; scribbles in other
  // colours and taps are play without a plan; a look or word to the adult is adult seeking.
  if (self.stroke_colour) {
    me.drawing = true;
    me.stroke_touched = false;
    me.landscape_stroke = draws_landscape(*self.stroke_colour);
  }
  if (self.touching) {
    me.stroke_touched = me.drawing;
    // The colour stays selected in the game: a finger that keeps drawing on the map draws in the last colour
    // picked, while a brief touch on the map is a tap.
    const bool stroke = me.drawing || (self.touch_item < 0 && t - me.touch_start_t >= params_.stroke_min_s);
    const bool constructive = self.touch_item >= 0 || (stroke && me.landscape_stroke);
    (constructive ? me.last_constructive_t : me.last_aimless_t) = t;
  } else if (me.stroke_touched) {
    me.drawing = me.stroke_touched = false;  // the drawing finger has left the screen
  }
  if (self.gaze.kind == GazeKind::Experimenter || (self.speech && self.speech->to == Addressee::Experimenter)) {
    me.last_adult_t = t;
  }
  // Social attitude.
  const int held = self.touching ? self.touch_item : -1;
  if (held >= 0 && static_cast<std::size_t>(held) < me.held_t.size()) me.held_t[static_cast<std::size_t>(held)] = t;
  me.holding = held;
  if (self.speech && self.speech->to == Addressee::Partner) {
    switch (self.speech->kind) {
      case Utterance::Protest: me.last_protest_t = t; break;
      case Utterance::Proposal:
      case Utterance::Request: me.last_directive_t = t; break;
      default: me.last_friendly_t = t; break;
    }
    // Answering the other in words is friendly; a returned glance alone is not yet an attitude.
    if (t - them.last_talk_t <= params_.answer_window_s && self.speech->kind != Utterance::Protest) me.last_friendly_t = t;
  }
  // A coder judges the kind of play and the attitude over stretches of behaviour, not single acts: running shares
  // of the time with recent considered play, other play, and friendly acts.
  const auto recent = [&](double since) { return t - since <= params_.evidence_hold_s ? 1.0 : 0.0; };
  const double w = 1.0 - std::exp(-dt / params_.judgement_window_s);
  me.constructive += w * (recent(std::max({me.last_constructive_t, me.last_directive_t, me.last_discussion_t})) -
                          me.constructive);
  // Discussing what to do next is planning the play; chatting otherwise is play without a plan.
  const bool discussing = t - me.last_discussion_t <= params_.discussion_hold_s;
  // Talking while playing with purpose is part of that play; chatting while not playing with purpose is off task.
  const bool chatting = !discussing && t - me.last_constructive_t > params_.judgement_window_s;
  me.aimless += w * (recent(std::max(me.last_aimless_t, chatting ? me.last_friendly_t : -1e9)) - me.aimless);
  me.friendly += w * (recent(std::max(me.last_friendly_t, me.follows.last())) - me.friendly);
}

TaskEngagement PairCoder::task_candidate(double t, int who) const {
  const Track& me = tracks_[static_cast<std::size_t>(who)];
  const Track& them = tracks_[static_cast<std::size_t>(1 - who)];
  if (t - me.last_adult_t <= params_.adult_hold_s) return TaskEngagement::AdultSeeking;
  if (std::max(me.constructive, me.aimless) < params_.play_share) return TaskEngagement::NoPlay;
  // Two children playing together are one activity to the coder: the kind of their play is judged together.
  // Discussing what to do next is part of the task; chatting without playing is being off task.
  if (!second_is_robot_ && interacting(t, who) && interacting(t, 1 - who)) {
    return me.constructive + them.constructive >= me.aimless + them.aimless ? TaskEngagement::GoalOriented
                                                                            : TaskEngagement::Aimless;
  }
  return me.constructive >= me.aimless ? TaskEngagement::GoalOriented : TaskEngagement::Aimless;
}

SocialAttitude PairCoder::attitude_candidate(double t, int who) const {
  const Track& me = tracks_[static_cast<std::size_t>(who)];
  if (t - me.last_take_t <= params_.adversarial_hold_s) return SocialAttitude::Adversarial;
  if (t - me.last_protest_t <= params_.frustrated_hold_s) return SocialAttitude::Frustrated;
  // Assertive — "bossy, manipulative, gentle grabbing": the child directs the other's play (tells it what to do,
  // asks for its item, or takes an item after asking). Pro-social: the child's own interaction about the play, or
  // friendly acts often enough; a child keeping to itself is passive.
  if (t - me.last_directive_t <= params_.assertive_hold_s) return SocialAttitude::Assertive;
  // One remark is not an attitude: the child keeps the interaction up (words about the play, or a discussion).
  const bool keeps_talking = me.interaction.since(t - params_.interaction_hold_s) >= kProsocialWords ||
                             t - me.last_discussion_t <= params_.discussion_hold_s;
  const bool friendly = keeps_talking || me.friendly >= params_.friendly_share;
  return friendly ? SocialAttitude::Prosocial : SocialAttitude::Passive;
}

SocialEngagement PairCoder::candidate(double t, int who) const {
  const Track& me = tracks_[static_cast<std::size_t>(who)];
  const Track& them = tracks_[static_cast<std::size_t>(1 - who)];
  const bool i_play = plays(t, who, params_.active_window_s);
  const bool they_play = plays(t, 1 - who, params_.active_window_s);
  // Interaction is addressed to the other: the child's own words to it about the play (offering an item, asking,
  // commenting, answering) within the window. Acting near the other or on its items without a word can be play
  // alongside it, and a glance that answers a comment is not associative play.
  const double from = t - params_.interaction_window_s;
  const int my_words = me.interaction.since(from);
  const bool i_talk = my_words >= 1;
  // Cooperative — "the two children discuss what to do next: this sequence is annotated as a cooperative
  // behaviour" (the paper), and "the child's own acts are coordinated with the partner's towards a shared product
  // over a sustained stretch (building one scene, taking turns on one item)": while interacting, the child
  // followed the other's activity (took up the item it just moved, brought an item to the spot where it just put
  // one, drew where it drew) at least twice within the window and the other followed the child's at least once.
  // The other's acts near my items alone never make me cooperative: my own following acts are required.
  const double coop_from = t - params_.cooperation_window_s;
  const int my_follows = me.follows.since(coop_from);
  const int their_follows = them.follows.since(coop_from);
  const bool turn_taking = my_follows >= 1 && their_follows >= 1 && my_follows + their_follows >= 3;
  if (t - me.last_discussion_t <= params_.discussion_hold_s || (i_talk && turn_taking)) {
    return SocialEngagement::Cooperative;
  }
  // A coder codes the stretch, not each act: cooperation once seen goes on while both keep working on the shared
  // scene (each followed the other or spoke to it within `cooperation_hold_s`).
  const bool coded_cooperative =
      coded_[static_cast<std::size_t>(who)][static_cast<std::size_t>(Axis::SocialEngagement)].label ==
      static_cast<std::uint8_t>(SocialEngagement::Cooperative);
  const double hold_from = t - params_.cooperation_hold_s;
  const bool still_together = (me.interaction.since(hold_from) >= 1 || me.follows.since(hold_from) >= 1) &&
                              (them.follows.since(hold_from) >= 1 || them.interaction.since(hold_from) >= 1);
  if (coded_cooperative && still_together) return SocialEngagement::Cooperative;
  // Associative — "the child itself initiates or responds to interaction about the play (talks about it, offers or
  // shares items, follows the partner's activity), no shared goal": the child's own interaction, taken up by the
  // other (its words back, or its attention: it looks at the child), or accompanied by following the other's
  // activity, while play goes on. Anything the other does alone never makes me associative.
  const bool taken_up = them.interaction.since(from) >= 1 || them.last_look_at_other_t >= from ||
                        me.follows.since(from) >= 1;
  // One remark is not yet an interaction: the child keeps it up (two or more within the window), or takes part in
  // a conversation about the play (its own remark among two or more answers to each other within the window).
  const bool conversation = i_talk && replies_.since(from) >= 2;
  if (((my_words >= 2 && taken_up) || conversation) && (i_play || they_play)) return SocialEngagement::Associative;
  // Parallel — "similar materials or activity near the partner, without interacting": both play on the tray; a
  // partner pausing beside a child that plays is still seen as playing alongside for a while longer. A partner who
  // has stopped to watch me is not playing alongside me.
  const bool they_played = plays(t, 1 - who, (i_play ? 3.0 : 1.0) * params_.active_window_s) && !onlooking(t, 1 - who);
  if (onlooking(t, who)) return SocialEngagement::Onlooker;
  if (i_play) return they_played ? SocialEngagement::Parallel : SocialEngagement::Solitary;
  // Neither child plays: the scheme has no label for it (Parten's stages "minus unoccupied"), so a coder leaves the
  // child's social engagement as it was until one of them plays again: a pause of both is not solitary play.
  if (!they_play) {
    return static_cast<SocialEngagement>(
        coded_[static_cast<std::size_t>(who)][static_cast<std::size_t>(Axis::SocialEngagement)].label);
  }
  return SocialEngagement::Solitary;
}

SocialEngagement PairCoder::joins_in(double t, int who, SocialEngagement mine, SocialEngagement theirs) const {
  // "The child itself initiates or responds to interaction": when the other child's own behaviour is joint play
  // with me, my own response to it is that play too. Only the other's own evidence counts (not a label it got from
  // me), so two children cannot hold each other in it; the robot is not coded, so with a robot this never applies.
  const Track& me = tracks_[static_cast<std::size_t>(who)];
  if (mine == SocialEngagement::Cooperative) return mine;
  // Cooperative: my own acts follow the cooperating partner's (its shared scene) within the window.
  if (theirs == SocialEngagement::Cooperative && me.follows.since(t - params_.cooperation_window_s) >= 1) {
    return SocialEngagement::Cooperative;
  }
  // Associative: I answer in words a partner engaged in play with me (a glance alone is no answer).
  const bool answers = me.interaction.since(t - params_.interaction_window_s) >= 1;
  if (answers && (theirs == SocialEngagement::Associative || theirs == SocialEngagement::Cooperative)) {
    return SocialEngagement::Associative;
  }
  return mine;
}

void PairCoder::code(double t, int who, Axis axis, std::uint8_t label, double opened) {
  Coded& c = coded_[static_cast<std::size_t>(who)][static_cast<std::size_t>(axis)];
  if (label == c.label) {
    c.candidate = label;
    return;
  }
  if (label != c.candidate) {
    c.candidate = label;
    c.candidate_since = t;
  }
  // Frustration and hostility are salient: a coder marks them even when brief.
  const bool salient = axis == Axis::SocialAttitude && (label == static_cast<std::uint8_t>(SocialAttitude::Frustrated) ||
                                                        label == static_cast<std::uint8_t>(SocialAttitude::Adversarial));
  const double min_bout = axis == Axis::TaskEngagement   ? params_.task_min_bout_s
                          : salient                      ? params_.salient_min_bout_s
                          : axis == Axis::SocialAttitude ? params_.attitude_min_bout_s
                                                         : params_.min_bout_s;
  if (t - c.candidate_since < min_bout) return;
  // A long bout anchors the coder: a new (not salient) label must also last a share of the bout it would end.
  if (!salient && t - c.candidate_since < params_.anchoring * (c.candidate_since - c.bout_start)) return;
  // The coder marks the new sequence from where it visibly began: a cooperation from its opening move (the child
  // joining the other's activity), which a coder recognises only in retrospect; a short bout that lies wholly
  // after it is part of the cooperation.
  const double start = std::max(std::min(c.candidate_since, opened), c.bout_start);
  if (start > c.bout_start) c.timeline.push_back({axis, c.label, c.bout_start, start});
  c.label = label;
  c.bout_start = start;
}

void PairCoder::observe(double t, const ObservedPlayer& first, const ObservedPlayer& second) {
  if (!started_) {
    started_ = true;
    for (auto& player : coded_) {
      for (const Axis axis : kAxes) {
        Coded& c = player[static_cast<std::size_t>(axis)];
        c.bout_start = c.candidate_since = t;
        // Before anything is seen the coder starts from the annotator's reset values.
        LabelState reset;
        c.label = c.candidate = static_cast<std::uint8_t>(reset.index(axis));
      }
    }
    last_t_ = t;
  }
  const double dt = std::max(t - last_t_, 0.0);
  last_t_ = t;
  track(t, dt, 0, first);
  track(t, dt, 1, second);
  const int players = second_is_robot_ ? 1 : 2;
  const std::array<SocialEngagement, 2> own = {candidate(t, 0),
                                               second_is_robot_ ? SocialEngagement::Solitary : candidate(t, 1)};
  for (int who = 0; who < players; ++who) {
    code(t, who, Axis::TaskEngagement, static_cast<std::uint8_t>(task_candidate(t, who)));
    const SocialEngagement social =
        joins_in(t, who, own[static_cast<std::size_t>(who)], own[static_cast<std::size_t>(1 - who)]);
    code(t, who, Axis::SocialEngagement, static_cast<std::uint8_t>(social),
         social == SocialEngagement::Cooperative ? cooperation_opened(t, who) : std::numeric_limits<double>::infinity());
    code(t, who, Axis::SocialAttitude, static_cast<std::uint8_t>(attitude_candidate(t, who)));
  }
}

void PairCoder::finish(double t) {
  const int players = second_is_robot_ ? 1 : 2;
  for (int who = 0; who < players; ++who) {
    for (const Axis axis : kAxes) {
      Coded& c = coded_[static_cast<std::size_t>(who)][static_cast<std::size_t>(axis)];
      if (t > c.bout_start) c.timeline.push_back({axis, c.label, c.bout_start, t});
      c.bout_start = t;
    }
  }
}

ChildTimeline PairCoder::timeline(int player) const {
  ChildTimeline out;
  for (const Coded& c : coded_[static_cast<std::size_t>(player)]) out.insert(out.end(), c.timeline.begin(), c.timeline.end());
  std::stable_sort(out.begin(), out.end(), [](const LabelInterval& a, const LabelInterval& b) { return a.start < b.start; });
  return out;
}

namespace {

// The label `timeline` carries on `axis` at each of the increasing sample `times` (-1 where none): the first bout in
// the timeline's order whose [start, stop) holds the time, as a scan of the bouts per sample finds it. The bouts are
// painted last to first, each over the samples from the first at or after its start to the first at or after its
// stop, so an earlier bout paints over a later one.
void labels_at(const ChildTimeline& timeline, Axis axis, const std::vector<double>& times,
               std::vector<std::int16_t>& out) {
  out.assign(times.size(), -1);
  for (auto bout = timeline.rbegin(); bout != timeline.rend(); ++bout) {
    if (bout->axis != axis || std::isnan(bout->start) || std::isnan(bout->stop)) continue;  // NaN holds no time
    const auto first = std::lower_bound(times.begin(), times.end(), bout->start);
    const auto last = std::lower_bound(first, times.end(), bout->stop);
    std::fill(out.begin() + (first - times.begin()), out.begin() + (last - times.begin()),
              static_cast<std::int16_t>(bout->label));
  }
}

}  // namespace

double timeline_agreement(const ChildTimeline& a, const ChildTimeline& b, Axis axis, double end, double step) {
  if (!(step > 0.0) || !std::isfinite(step) || end == std::numeric_limits<double>::infinity()) {
    throw InputError(fmt::format("sampling every {} s up to {} s does not end", step, end), "step",
                     "a positive, finite step and a finite end");
  }
  thread_local std::vector<double> times;  // reused: no allocation once a long session has been compared
  thread_local std::vector<std::int16_t> labels_a;
  thread_local std::vector<std::int16_t> labels_b;
  times.clear();
  for (double t = 0.5 * step; t < end; t += step) times.push_back(t);
  labels_at(a, axis, times, labels_a);
  labels_at(b, axis, times, labels_b);
  int same = 0;
  int both = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (labels_a[k] < 0 || labels_b[k] < 0) continue;
    ++both;
    if (labels_a[k] == labels_b[k]) ++same;
  }
  return both > 0 ? static_cast<double>(same) / both : 0.0;
}

}  // namespace freeplay::agents
