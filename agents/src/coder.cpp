#include "freeplay/agents/coder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "freeplay/core/error.hpp"

namespace freeplay::agents {
namespace {

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

void PairCoder::track(double t, double dt, int who, const ObservedPlayer& self) {
  Track& me = tracks_[static_cast<std::size_t>(who)];
  const Track& them = tracks_[static_cast<std::size_t>(1 - who)];
  // Attention to the other player: speaking to it, or a gaze that lands on it.
  const bool spoke = self.speech && self.speech->to == Addressee::Partner;
  const bool glanced = looks_at_other(self.gaze) && !looks_at_other(prev_gaze_[static_cast<std::size_t>(who)]);
  const bool answered = (spoke || glanced) && t - them.last_attend_t <= params_.answer_window_s;
  track_task_and_attitude(t, dt, who, self, answered);
  if (spoke || glanced) {
    // An act of attention that answers the other's recent one is an exchange when one of the two was spoken (an
    // exchange of glances alone is not yet playing together); both players are in it.
    if (answered && (spoke || them.last_attend_spoken)) {
      if (t - last_exchange_t_ > params_.exchange_hold_s) exchange_start_t_ = t;
      last_exchange_t_ = t;
      // A proposal taken up is working on a shared goal: cooperation.
      if (them.last_attend_proposal) me.last_joint_t = t;
    }
    me.last_attend_t = t;
    me.last_attend_spoken = spoke;
    me.last_attend_proposal = spoke && self.speech->kind == Utterance::Proposal;
  }
  // A touch on the other's item or area while the two are in an exchange is joint play.
  if (self.touch_started) {
    const bool other_recent = t - them.last_touch_t <= params_.active_window_s;
    const bool on_their_item = self.touch_item >= 0 && self.touch_item == them.last_item && other_recent;
    const bool in_their_area = other_recent && (self.touch_point - them.last_touch_point).norm() <
                                                   params_.joint_distance_m;
    if ((on_their_item || in_their_area) && t - last_exchange_t_ <= params_.exchange_hold_s) {
      me.last_joint_t = t;
      if (on_their_item) me.last_directive_t = t;  // moving the other's item in joint work takes the lead
    }
  }
  if (self.touching) {
    me.last_touch_t = t;
    me.last_touch_point = self.touch_point;
    if (self.touch_item >= 0) me.last_item = self.touch_item;
  }
  // Watching the other's play: the gaze rests on the other's finger or on the item it moves.
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

void PairCoder::track_task_and_attitude(double t, double dt, int who, const ObservedPlayer& self, bool answered) {
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
    const bool constructive = self.touch_item >= 0 || (me.drawing && me.landscape_stroke);
    (constructive ? me.last_constructive_t : me.last_aimless_t) = t;
  } else if (me.stroke_touched) {
    me.drawing = me.stroke_touched = false;  // the drawing finger has left the screen
  }
  if (self.gaze.kind == GazeKind::Experimenter || (self.speech && self.speech->to == Addressee::Experimenter)) {
    me.last_adult_t = t;
  }
  // Social attitude.
  const int held = self.touching ? self.touch_item : -1;
  if (held >= 0 && static_cast<std::size_t>(held) < me.held_t.size()) {
    const auto item = static_cast<std::size_t>(held);
    // Grabbing what the other was just playing with, while the two are not playing together, is taking it.
    const bool theirs = them.held_t[item] > me.held_t[item] && t - them.held_t[item] <= params_.take_window_s;
    if (held != me.holding && theirs && t - last_exchange_t_ > params_.exchange_hold_s) me.last_take_t = t;
    me.held_t[item] = t;
  }
  me.holding = held;
  if (self.speech && self.speech->to == Addressee::Partner) {
    switch (self.speech->kind) {
      case Utterance::Protest: me.last_protest_t = t; break;
      case Utterance::Proposal:
      case Utterance::Request: me.last_directive_t = t; break;
      default: me.last_friendly_t = t; break;
    }
  }
  // Answering the other in words is friendly; a returned glance alone is not yet an attitude.
  if (answered && self.speech && self.speech->to == Addressee::Partner) me.last_friendly_t = t;
  // A coder judges the kind of play and the attitude over stretches of behaviour, not single acts: running shares
  // of the time with recent considered play, other play, and friendly acts.
  const auto recent = [&](double since) { return t - since <= params_.evidence_hold_s ? 1.0 : 0.0; };
  const double w = 1.0 - std::exp(-dt / params_.judgement_window_s);
  me.constructive += w * (recent(std::max(me.last_constructive_t, me.last_directive_t)) - me.constructive);
  me.aimless += w * (recent(std::max(me.last_aimless_t, me.last_friendly_t)) - me.aimless);
  me.friendly += w * (recent(std::max(me.last_friendly_t, me.last_joint_t)) - me.friendly);
}

TaskEngagement PairCoder::task_candidate(double t, int who) const {
  const Track& me = tracks_[static_cast<std::size_t>(who)];
  const Track& them = tracks_[static_cast<std::size_t>(1 - who)];
  if (t - me.last_adult_t <= params_.adult_hold_s) return TaskEngagement::AdultSeeking;
  if (std::max(me.constructive, me.aimless) < params_.play_share) return TaskEngagement::NoPlay;
  // Two children in an exchange are one activity to the coder: the kind of their play is judged together.
  // Discussing what to do next is part of the task; chatting without playing is being off task.
  if (!second_is_robot_ && t - last_exchange_t_ <= params_.exchange_hold_s) {
    return me.constructive + them.constructive >= me.aimless + them.aimless ? TaskEngagement::GoalOriented
                                                                            : TaskEngagement::Aimless;
  }
  return me.constructive >= me.aimless ? TaskEngagement::GoalOriented : TaskEngagement::Aimless;
}

SocialAttitude PairCoder::attitude_candidate(double t, int who) const {
  const Track& me = tracks_[static_cast<std::size_t>(who)];
  if (t - me.last_take_t <= params_.adversarial_hold_s) return SocialAttitude::Adversarial;
  if (t - me.last_protest_t <= params_.frustrated_hold_s) return SocialAttitude::Frustrated;
  // Taking part in an exchange, or friendly acts often enough, is prosocial, and directing the other's play
  // within it is assertive; a child keeping to itself is passive, even when it throws in a suggestion.
  const bool interacting = t - last_exchange_t_ <= params_.interaction_hold_s || me.friendly >= params_.friendly_share;
  if (!interacting) return SocialAttitude::Passive;
  return t - me.last_directive_t <= params_.assertive_hold_s ? SocialAttitude::Assertive : SocialAttitude::Prosocial;
}

SocialEngagement PairCoder::candidate(double t, int who) const {
  const Track& me = tracks_[static_cast<std::size_t>(who)];
  const Track& them = tracks_[static_cast<std::size_t>(1 - who)];
  if (t - last_exchange_t_ <= params_.exchange_hold_s) {
    // Joint work by either child makes the exchange cooperative for both, as a coder sees the pair.
    // A shared goal shows once the children have been interacting for a moment.
    const double joint = std::max(me.last_joint_t, them.last_joint_t);
    const bool settled = t - exchange_start_t_ >= 0.5 * params_.min_bout_s;
    return settled && t - joint <= params_.joint_act_hold_s ? SocialEngagement::Cooperative
                                                            : SocialEngagement::Associative;
  }
  const bool i_play = t - me.last_touch_t <= params_.active_window_s;
  // A partner pausing beside a child that plays is still seen as playing alongside for a while longer.
  const bool they_play = t - them.last_touch_t <= (i_play ? 3.0 : 1.0) * params_.active_window_s;
  // A child that has stopped and keeps its eyes on the other's play is looking on.
  const bool stopped = t - me.last_touch_t > 0.5 * params_.min_bout_s;
  if (they_play && stopped && me.watch >= params_.watch_share) return SocialEngagement::Onlooker;
  if (i_play) return they_play ? SocialEngagement::Parallel : SocialEngagement::Solitary;
  return SocialEngagement::Solitary;
}

void PairCoder::code(double t, int who, Axis axis, std::uint8_t label) {
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
  // The coder marks the new sequence from where it visibly began.
  const double start = std::max(c.candidate_since, c.bout_start);
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
  for (int who = 0; who < players; ++who) {
    code(t, who, Axis::TaskEngagement, static_cast<std::uint8_t>(task_candidate(t, who)));
    code(t, who, Axis::SocialEngagement, static_cast<std::uint8_t>(candidate(t, who)));
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
