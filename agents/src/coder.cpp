#include "freeplay/agents/coder.hpp"

#include <algorithm>
#include <cmath>

namespace freeplay::agents {
namespace {

bool looks_at_other(const GazeTarget& gaze) {
  return gaze.kind == GazeKind::PartnerFace || gaze.kind == GazeKind::Robot;
}

/// The label a timeline carries on `axis` at time `t` (sorted or not); nullopt when unlabelled.
std::optional<std::uint8_t> label_at(const ChildTimeline& timeline, Axis axis, double t) {
  for (const auto& bout : timeline) {
    if (bout.axis == axis && t >= bout.start && t < bout.stop) return bout.label;
  }
  return std::nullopt;
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
  return o;
}

PairCoder::PairCoder(const CoderParams& params, bool second_is_robot)
    : params_(params), second_is_robot_(second_is_robot) {}

void PairCoder::track(double t, double dt, int who, const ObservedPlayer& self) {
  Track& me = tracks_[static_cast<std::size_t>(who)];
  const Track& them = tracks_[static_cast<std::size_t>(1 - who)];
  // Attention to the other player: speaking to it, or a gaze that lands on it.
  const bool spoke = self.speech && self.speech->to == Addressee::Partner;
  const bool glanced = looks_at_other(self.gaze) && !looks_at_other(prev_gaze_[static_cast<std::size_t>(who)]);
  if (spoke || glanced) {
    // An act of attention that answers the other's recent one is an exchange when one of the two was spoken (an
    // exchange of glances alone is not yet playing together); both players are in it.
    if (t - them.last_attend_t <= params_.answer_window_s && (spoke || them.last_attend_spoken)) {
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
    if ((on_their_item || in_their_area) && t - last_exchange_t_ <= params_.exchange_hold_s) me.last_joint_t = t;
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

void PairCoder::code(double t, int who, SocialEngagement label) {
  Coded& c = coded_[static_cast<std::size_t>(who)];
  if (label == c.label) {
    c.candidate = label;
    return;
  }
  if (label != c.candidate) {
    c.candidate = label;
    c.candidate_since = t;
  }
  if (t - c.candidate_since < params_.min_bout_s) return;
  // The coder marks the new sequence from where it visibly began.
  const double start = std::max(c.candidate_since, c.bout_start);
  if (start > c.bout_start) {
    c.timeline.push_back({Axis::SocialEngagement, static_cast<std::uint8_t>(c.label), c.bout_start, start});
  }
  c.label = label;
  c.bout_start = start;
}

void PairCoder::observe(double t, const ObservedPlayer& first, const ObservedPlayer& second) {
  if (!started_) {
    started_ = true;
    for (auto& c : coded_) c.bout_start = c.candidate_since = t;
    last_t_ = t;
  }
  const double dt = std::max(t - last_t_, 0.0);
  last_t_ = t;
  track(t, dt, 0, first);
  track(t, dt, 1, second);
  code(t, 0, candidate(t, 0));
  if (!second_is_robot_) code(t, 1, candidate(t, 1));
}

void PairCoder::finish(double t) {
  const int players = second_is_robot_ ? 1 : 2;
  for (int who = 0; who < players; ++who) {
    Coded& c = coded_[static_cast<std::size_t>(who)];
    if (t > c.bout_start) c.timeline.push_back({Axis::SocialEngagement, static_cast<std::uint8_t>(c.label), c.bout_start, t});
    c.bout_start = t;
  }
}

ChildTimeline with_coded_social(const ChildTimeline& internal, const ChildTimeline& coded_social) {
  ChildTimeline out;
  out.reserve(internal.size() + coded_social.size());
  for (const auto& bout : internal) {
    if (bout.axis != Axis::SocialEngagement) out.push_back(bout);
  }
  out.insert(out.end(), coded_social.begin(), coded_social.end());
  std::stable_sort(out.begin(), out.end(), [](const LabelInterval& a, const LabelInterval& b) { return a.start < b.start; });
  return out;
}

double timeline_agreement(const ChildTimeline& a, const ChildTimeline& b, Axis axis, double end, double step) {
  int same = 0;
  int both = 0;
  for (double t = 0.5 * step; t < end; t += step) {
    const auto la = label_at(a, axis, t);
    const auto lb = label_at(b, axis, t);
    if (!la || !lb) continue;
    ++both;
    if (*la == *lb) ++same;
  }
  return both > 0 ? static_cast<double>(same) / both : 0.0;
}

}  // namespace freeplay::agents
