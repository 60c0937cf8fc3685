#include "freeplay/agents/child_agent.hpp"

#include <algorithm>
#include <cmath>

#include "min_jerk.hpp"

namespace freeplay::agents {
namespace {

constexpr double kScreenW = sim::kScreenWidthM;
constexpr double kScreenH = sim::kScreenHeightM;
constexpr double kMargin = 0.02;
constexpr double kNever = 1e18;
/// Comments among the utterances to the partner that are not proposals (the rest are questions).
constexpr double kCommentShareOfTheRest = 5.0 / 7.0;

double ema_weight(double dt, double tau) { return tau > 0.0 ? 1.0 - std::exp(-dt / tau) : 1.0; }

/// Habitat colours of an item (the real play policy's HABITATS; purple/white kept for the early map).
int habitat_colours(int item, std::array<PaletteColour, 4>& out) {
  const std::string_view name = (item >= 0 && item < static_cast<int>(kItemNames.size()))
                                    ? kItemNames[static_cast<std::size_t>(item)]
                                    : std::string_view{};
  if (name == "zebra" || name == "giraffe") {
    out[0] = PaletteColour::Yellow;
    out[1] = PaletteColour::Green;
    return 2;
  }
  if (name == "elephant") {
    out[0] = PaletteColour::Green;
    return 1;
  }
  if (name == "lion") {
    out[0] = PaletteColour::Yellow;
    return 1;
  }
  if (name == "crocodile" || name == "hippo") {
    out[0] = PaletteColour::Blue;
    return 1;
  }
  out[0] = PaletteColour::Yellow;
  out[1] = PaletteColour::Green;
  out[2] = PaletteColour::Purple;
  out[3] = PaletteColour::White;
  return 4;
}

}  // namespace

ChildAgent::ChildAgent(const ChildModelParams& params, const ChildProfile& profile, Seat seat, Rng rng)
    : params_(&params), profile_(profile), seat_(seat), rng_(rng) {
  profile_.validate();
  const DriveParams& d = params_->drives;
  motivation_ = std::clamp(rng_.normal(d.initial_motivation_mean, d.initial_motivation_sd), 0.05, 1.0);
  decay_scale_ = std::exp(-d.attention_effect * (2.0 * profile_.attention_span - 1.0));
  expectation_ = params_->partnership.expectation_prior;
  prev_holder_.fill(HolderView::Nobody);
  mine_until_.fill(-1.0);
  timeline_.reserve(256);
}

double ChildAgent::feature(Feature f) const {
  switch (f) {
    case Feature::Motivation: return motivation_ - 0.5;
    case Feature::Age: return (profile_.age_years - 6.0) / 2.0;
    case Feature::Sociability: return 2.0 * profile_.sociability - 1.0;
    case Feature::Assertiveness: return 2.0 * profile_.assertiveness - 1.0;
    case Feature::Tablet:
      return profile_.tablet == TabletFamiliarity::Unknown ? 0.0 : static_cast<double>(profile_.tablet) - 1.0;
    case Feature::PartnerActive: return partner_active_;
    case Feature::PartnerJoint: return partner_joint_;
    case Feature::PartnerAttention: return partner_attention_;
    case Feature::PartnerRobot: return 0.0;  // set through partner_robot_ below
    case Feature::Grievance: return grievance_;
    case Feature::TaskNoPlay: return labels_.task == TaskEngagement::NoPlay ? 1.0 : 0.0;
    case Feature::Together:
      return (labels_.social == SocialEngagement::Associative || labels_.social == SocialEngagement::Cooperative)
                 ? 1.0
                 : 0.0;
    case Feature::Count: break;
  }
  return 0.0;
}

ChildActions ChildAgent::step(double t, double dt, const ChildPerception& seen) {
  ChildActions out;
  if (!started_) {
    started_ = true;
    bout_start_.fill(t);
    for (const Axis axis : kAxes) next_switch_[static_cast<std::size_t>(axis)] = t + draw_dwell(axis, labels_.index(axis));
    next_action_t_ = t + rng_.uniform(1.0, 4.0);
    next_glance_t_ = t;
  }
  last_t_ = t;
  partner_robot_ = seen.partner.is_robot;
  observe(t, dt, seen);
  update_drives(t, dt);
  maybe_quit(t, dt);
  advance_labels(t);
  if (motor_.kind == MotorKind::None && !quit_ && t >= next_action_t_) plan_action(t, seen, out);
  run_motor(t, out);
  update_gaze(t, seen, out);
  answer_partner(t, out);
  update_speech(t, dt, out);
  out.gaze = gaze_;
  out.quit = quit_;
  return out;
}

void ChildAgent::observe(double t, double dt, const ChildPerception& seen) {
  const ReactionParams& r = params_->reactions;
  const PartnerView& partner = seen.partner;
  const double w_att = ema_weight(dt, params_->drives.attention_tau_s);

  int taken_item = -1;
  // Items: who holds what; an item I placed recently that the partner grabs counts as taken from me.
  for (int i = 0; i < seen.item_count && i < static_cast<int>(kMaxSeenItems); ++i) {
    const SeenItem& item = seen.items[static_cast<std::size_t>(i)];
    if (item.item < 0 || item.item >= static_cast<int>(kMaxSeenItems)) continue;
    const auto k = static_cast<std::size_t>(item.item);
    const HolderView before = prev_holder_[k];
    const bool other_holds = item.holder == HolderView::Partner || item.holder == HolderView::Robot;
    const bool other_held = before == HolderView::Partner || before == HolderView::Robot;
    // Sharing is part of playing together: a recently placed item only feels taken outside joint play.
    const bool joint_play = labels_.social == SocialEngagement::Cooperative;
    if (other_holds && !other_held && (before == HolderView::Me || (mine_until_[k] > t && !joint_play))) {
      mine_until_[k] = -1.0;
      on_item_taken(t);
      taken_item = item.item;
    }
    if (item.holder == HolderView::Me) mine_until_[k] = t + r.ownership_memory_s;
    prev_holder_[k] = item.holder;
  }

  // Partner's touches: activity level and onsets near my play.
  partner_active_ += w_att * ((partner.touch_count > 0 ? 1.0 : 0.0) - partner_active_);
  partner_joint_ -= w_att * partner_joint_;
  partner_attention_ -= w_att * partner_attention_;
  if (partner.touch_count > prev_partner_touches_ && partner.touch_count > 0) {
    const SeenTouch& touch = partner.touches[static_cast<std::size_t>(partner.touch_count - 1)];
    const bool near_my_play = (touch.point - my_last_point_).norm() < r.react_distance_m;
    const bool on_my_item = touch.item >= 0 && touch.item == my_last_item_;
    const bool taken = touch.item >= 0 && touch.item == taken_item;
    if (!taken && (near_my_play || on_my_item) && t - my_last_action_t_ < r.react_window_s) {
      // A joint act answers me only from a partner who attends to me; an indifferent one merely plays nearby.
      if (partner_attention_ > 0.1) last_answered_t_ = t;
      on_contingent(r.act_weight);
      on_partner_bid(t, /*joint=*/true, /*spoken=*/false);
      partner_joint_ = std::min(1.0, partner_joint_ + 0.35);
    } else if ((touch.point - my_last_point_).norm() < 2.0 * r.react_distance_m) {
      partner_joint_ = std::min(1.0, partner_joint_ + 0.15);
    }
    partner_last_item_ = touch.item;
    partner_last_point_ = touch.point;
    partner_last_t_ = t;
    partner_last_was_stroke_ = touch.item < 0;
  }
  if (partner.touch_count > 0) {
    partner_last_touch_t_ = t;
    const SeenTouch& touch = partner.touches[0];
    partner_last_point_ = touch.point;
    partner_last_t_ = t;
    if (touch.item >= 0) partner_last_item_ = touch.item;
  }
  prev_partner_touches_ = partner.touch_count;

  const bool looking = partner.gaze.kind == GazeKind::PartnerFace;
  if (looking && !prev_partner_looking_) {
    last_answered_t_ = t;
    on_contingent(r.look_weight);
    on_partner_bid(t, /*joint=*/false, /*spoken=*/false);
    partner_attention_ = std::min(1.0, partner_attention_ + 0.25);
  }
  prev_partner_looking_ = looking;
  if (partner.speech && partner.speech->to == Addressee::Partner) {
    last_answered_t_ = t;
    on_contingent(r.talk_weight);
    on_partner_bid(t, /*joint=*/partner.speech->kind == Utterance::Proposal, /*spoken=*/true);
    partner_attention_ = std::min(1.0, partner_attention_ + 0.35);
  }
  if (partner.wants_to_stop) partner_quit_ = true;

  if (bid_pending_ && t >= bid_deadline_) {
    bid_pending_ = false;
    ++counters_.unanswered_bids;
    motivation_ -= params_->drives.unanswered_bid_drop * motivation_;
    expectation_ -= params_->partnership.expectation_rate * expectation_;
  }
}

void ChildAgent::on_contingent(double weight) {
  ++counters_.contingent_responses;
  if (bid_pending_) {
    ++counters_.bids_answered;
    expectation_ += params_->partnership.expectation_rate * (1.0 - expectation_);
  }
  bid_pending_ = false;
  motivation_ += params_->drives.contingency_gain * weight * (1.0 - motivation_);
}

void ChildAgent::on_item_taken(double t) {
  ++counters_.items_taken;
  const DriveParams& d = params_->drives;
  const ReactionParams& r = params_->reactions;
  motivation_ -= d.unfairness_drop * motivation_;
  grievance_ = std::min(1.0, grievance_ + 0.5);
  if (quit_) return;
  protest_pending_ = true;
  if (rng_.bernoulli(r.take_reaction_probability)) {
    const double a = std::exp(feature(Feature::Assertiveness));
    // The fitted entry biases of the attitude axis scale the reactions too, so the label fit governs them.
    const auto& bias = params_->axis(Axis::SocialAttitude).bias;
    const double weights[3] = {r.frustrated_weight * std::exp(bias[3]), r.adversarial_weight * a * std::exp(bias[1]),
                               r.assertive_weight * a * std::exp(bias[2])};
    const double total = weights[0] + weights[1] + weights[2];
    double u = rng_.uniform() * total;
    SocialAttitude next = SocialAttitude::Frustrated;
    if ((u -= weights[0]) >= 0.0) next = (u - weights[1] < 0.0) ? SocialAttitude::Adversarial : SocialAttitude::Assertive;
    ++counters_.reactions_to_taking;
    if (next == SocialAttitude::Adversarial && rng_.bernoulli(r.retaliation_probability)) retaliation_pending_ = true;
    if (next != labels_.attitude) switch_label(Axis::SocialAttitude, static_cast<std::size_t>(next), t);
  }
}

void ChildAgent::update_drives(double t, double dt) {
  const DriveParams& d = params_->drives;
  const double dt_min = dt / 60.0;
  double stimulation = 0.0;
  if (labels_.task == TaskEngagement::GoalOriented) stimulation += d.play_gain_per_min;
  if (partner_robot_) stimulation += d.novelty_gain_per_min * std::exp(-t / (60.0 * d.novelty_tau_min));
  motivation_ += dt_min * (stimulation * (1.0 - motivation_) - d.decay_per_min * decay_scale_ * motivation_);
  motivation_ = std::clamp(motivation_, 0.0, 1.0);
  boredom_ += dt_min * d.boredom_rate_per_min * decay_scale_ * (1.0 - motivation_);
  grievance_ -= ema_weight(dt, d.grievance_tau_s) * grievance_;
}

void ChildAgent::maybe_quit(double t, double dt) {
  if (quit_) return;
  const DriveParams& d = params_->drives;
  double hazard_per_min = d.quit_hazard_per_min * std::exp(d.quit_boredom_slope * boredom_ -
                                                           d.quit_motivation_slope * (motivation_ - 0.5));
  if (partner_quit_) hazard_per_min *= d.partner_quit_factor;
  if (!rng_.bernoulli(std::min(1.0, hazard_per_min * dt / 60.0))) return;
  quit_ = true;
  quit_time_ = t;
  motor_.kind = MotorKind::None;  // run_motor lifts a finger that is down
  if (labels_.task != TaskEngagement::NoPlay) switch_label(Axis::TaskEngagement, 3, t);
  if (labels_.social != SocialEngagement::Solitary) switch_label(Axis::SocialEngagement, 0, t);
  if (labels_.attitude != SocialAttitude::Passive) switch_label(Axis::SocialAttitude, 4, t);
}

void ChildAgent::advance_labels(double t) {
  if (quit_) return;
  sustain_joint_play(t);
  for (const Axis axis : kAxes) {
    const auto a = static_cast<std::size_t>(axis);
    if (t >= next_switch_[a]) switch_label(axis, draw_next_label(axis), t);
  }
}

void ChildAgent::switch_label(Axis axis, std::size_t label, double t) {
  const auto a = static_cast<std::size_t>(axis);
  const std::size_t current = labels_.index(axis);
  if (t > bout_start_[a]) timeline_.push_back({axis, static_cast<std::uint8_t>(current), bout_start_[a], t});
  labels_.set(axis, label);
  bout_start_[a] = t;
  // A child that becomes frustrated says so.
  if (axis == Axis::SocialAttitude && label == static_cast<std::size_t>(SocialAttitude::Frustrated)) {
    protest_pending_ = true;
  }
  next_switch_[a] = quit_ ? kNever : t + draw_dwell(axis, label);
}

std::size_t ChildAgent::draw_next_label(Axis axis) {
  const AxisModel& m = params_->axis(axis);
  const std::size_t n = label_count(axis);
  const std::size_t current = labels_.index(axis);
  std::array<double, kFeatureCount> f{};
  for (std::size_t k = 0; k < kFeatureCount; ++k) f[k] = feature(static_cast<Feature>(k));
  f[static_cast<std::size_t>(Feature::PartnerRobot)] = partner_robot_ ? 1.0 : 0.0;
  std::array<double, kMaxLabels> w{};
  double total = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    if (j == current) continue;
    double log_w = m.bias[j];
    for (std::size_t k = 0; k < kFeatureCount; ++k) log_w += m.coupling[j][k] * f[k];
    w[j] = m.transition[current][j] * std::exp(std::clamp(log_w, -30.0, 30.0));
    if (axis == Axis::SocialEngagement) {
      // Joint play is sought only from a partner expected to answer; onlooking needs play worth watching.
      const auto label = static_cast<SocialEngagement>(j);
      if (label == SocialEngagement::Associative || label == SocialEngagement::Cooperative) {
        w[j] *= std::pow(expectation_, params_->partnership.expectation_exponent);
      } else if (label == SocialEngagement::Onlooker) {
        w[j] *= std::min(1.0, 2.0 * partner_active_);
      }
    }
    total += w[j];
  }
  if (!(total > 0.0)) return current;
  double u = rng_.uniform() * total;
  for (std::size_t j = 0; j < n; ++j) {
    if (j == current) continue;
    u -= w[j];
    if (u < 0.0) return j;
  }
  for (std::size_t j = n; j-- > 0;) {
    if (j != current && w[j] > 0.0) return j;
  }
  return current;
}

double ChildAgent::draw_dwell(Axis axis, std::size_t label) {
  const AxisModel& m = params_->axis(axis);
  return std::max(0.5, rng_.lognormal(std::log(m.dwell_median_s[label]), m.dwell_sigma[label]));
}

double ChildAgent::reach_depth() const {
  const MotorParams& m = params_->motor;
  return std::clamp(m.reach_depth_m + m.reach_per_year_m * (profile_.age_years - 6), 0.08, kScreenH);
}

bool ChildAgent::reachable(const Vec2& p) const { return depth_from_seat(seat_, p) <= reach_depth(); }

Vec2 ChildAgent::clamp_reachable(const Vec2& p) const {
  const double x = std::clamp(p.x(), kMargin, kScreenW - kMargin);
  const double depth = std::clamp(depth_from_seat(seat_, p), kMargin, reach_depth());
  const double y = seat_ == Seat::Bottom ? -kScreenH + depth : -depth;
  return {x, y};
}

Vec2 ChildAgent::random_own_point() {
  const double x = rng_.uniform(kMargin + 0.03, sim::kStashMinX - 0.03);
  const double depth = rng_.uniform(0.04, reach_depth());
  return {x, seat_ == Seat::Bottom ? -kScreenH + depth : -depth};
}

double ChildAgent::fitts_duration(double distance, double width) const {
  const MotorParams& m = params_->motor;
  const double index = std::max(0.5, std::log2(2.0 * distance / std::max(width, 1e-3)));
  const double age_factor = std::max(0.6, 1.0 + m.age_slowdown_per_year * (6.0 - profile_.age_years));
  return age_factor * (m.fitts_a_s + m.fitts_b_s_per_bit * index);
}

int ChildAgent::pick_item(const ChildPerception& seen, const Vec2& near, bool partner_items, bool any_reachable) {
  int best = -1;
  double best_score = 1e9;
  for (int i = 0; i < seen.item_count; ++i) {
    const SeenItem& item = seen.items[static_cast<std::size_t>(i)];
    if (!reachable(item.position)) continue;
    if (item.holder == HolderView::Me) continue;
    if (item.holder != HolderView::Nobody && !partner_items) continue;
    double score = (item.position - near).norm() + 0.05 * rng_.uniform();
    if (partner_items && item.item == partner_last_item_) score -= 1.0;
    if (any_reachable) score = rng_.uniform();
    if (score < best_score) {
      best_score = score;
      best = i;
    }
  }
  return best;
}

Vec2 ChildAgent::habitat_destination(const ChildPerception& seen, int item) {
  std::array<PaletteColour, 4> colours{};
  const int n = habitat_colours(item, colours);
  const PaletteColour wanted = colours[static_cast<std::size_t>(rng_.uniform_int(0, n - 1))];
  Vec2 best = random_own_point();
  double best_d = 1e9;
  for (int z = 0; z < seen.zone_count; ++z) {
    const SeenZone& zone = seen.zones[static_cast<std::size_t>(z)];
    if (zone.colour != wanted) continue;
    const double d = depth_from_seat(seat_, zone.centroid);
    if (d > reach_depth() + 0.5 * zone.radius_m) continue;
    const double score = d + 0.1 * rng_.uniform();
    if (score < best_d) {
      best_d = score;
      const double spread = std::min(zone.radius_m, 0.04);
      best = zone.centroid + Vec2(rng_.normal(0.0, spread), rng_.normal(0.0, spread));
    }
  }
  return clamp_reachable(best);
}

void ChildAgent::plan_action(double t, const ChildPerception& seen, ChildActions& out) {
  const MotorParams& m = params_->motor;
  const auto task = static_cast<std::size_t>(labels_.task);
  const double gap_median = m.action_gap_median_s[task];
  const bool watching = labels_.social == SocialEngagement::Onlooker;
  if (gap_median <= 0.0 || watching) {
    next_action_t_ = t + 1.0;
    return;
  }
  next_action_t_ = t + rng_.lognormal(std::log(gap_median), m.action_gap_sigma);

  const bool partner_recent = t - partner_last_t_ < 20.0;
  const SocialEngagement social = labels_.social;
  const bool aimless = labels_.task == TaskEngagement::Aimless;

  // Which kind of action: drags, taps, strokes; parallel play copies the partner's kind of activity.
  // Silly play is mostly scribbles and taps; considered play mostly moves items into place.
  double p_drag = aimless ? 0.2 : 0.75;
  double p_stroke = aimless ? 0.5 : 0.15;
  if (social == SocialEngagement::Parallel && partner_recent &&
      rng_.bernoulli(params_->reactions.imitation_probability)) {
    p_drag = partner_last_was_stroke_ ? 0.0 : 1.0;
    p_stroke = 1.0 - p_drag;
  }
  const double u = rng_.uniform();

  // Where: together → at the partner's area; adversarial → the partner's items; else my own side.
  const bool adversarial = labels_.attitude == SocialAttitude::Adversarial || retaliation_pending_;
  const bool together = partner_recent && (social == SocialEngagement::Cooperative ||
                                           social == SocialEngagement::Associative);
  Vec2 focus = together ? clamp_reachable(partner_last_point_) : random_own_point();

  if (u < p_drag || adversarial) {
    int index = -1;
    Vec2 destination;
    if (adversarial) {
      index = pick_item(seen, partner_last_point_, true, false);
      destination = rng_.bernoulli(0.3) ? Vec2(rng_.uniform(sim::kStashMinX + 0.01, kScreenW - 0.02),
                                               seat_ == Seat::Bottom ? -kScreenH + 0.05 : -0.05)
                                        : random_own_point();
      retaliation_pending_ = false;
    } else if (social == SocialEngagement::Cooperative && partner_recent) {
      index = pick_item(seen, partner_last_point_, false, false);
      destination = clamp_reachable(partner_last_point_ + Vec2(rng_.normal(0.0, 0.04), rng_.normal(0.0, 0.04)));
    } else {
      index = pick_item(seen, focus, false, aimless);
      const bool tidy = rng_.bernoulli(0.03 + 0.1 * (1.0 - motivation_));
      if (tidy) {
        destination = clamp_reachable({rng_.uniform(sim::kStashMinX + 0.01, kScreenW - 0.02), -kScreenH / 2.0});
      } else if (together) {
        destination = clamp_reachable(partner_last_point_ + Vec2(rng_.normal(0.0, 0.08), rng_.normal(0.0, 0.06)));
      } else if (aimless || index < 0) {
        destination = random_own_point();
      } else {
        destination = habitat_destination(seen, seen.items[static_cast<std::size_t>(index)].item);
      }
    }
    if (index >= 0) {
      const SeenItem& item = seen.items[static_cast<std::size_t>(index)];
      start_drag(t, item.position, destination, item.item);
      return;
    }
  }
  if (u < p_drag + p_stroke) {
    const bool fill = !aimless && rng_.bernoulli(0.6);
    if (fill) {
      static constexpr std::array<PaletteColour, 3> kFillColours = {PaletteColour::Blue, PaletteColour::Green,
                                                                    PaletteColour::Yellow};
      colour_ = kFillColours[static_cast<std::size_t>(rng_.uniform_int(0, 2))];
    } else {
      colour_ = sim::kPalette[static_cast<std::size_t>(rng_.uniform_int(0, 7))];
    }
    // Children draw on free map areas: a press on an item would grab it instead of drawing.
    const auto near_item = [&seen](const Vec2& q) {
      for (int i = 0; i < seen.item_count; ++i) {
        const SeenItem& item = seen.items[static_cast<std::size_t>(i)];
        if ((item.position - q).norm() < 0.5 * item_size_m(item.item) + 0.045) return true;
      }
      return false;
    };
    for (int attempt = 0; attempt < 6 && near_item(clamp_reachable(focus)); ++attempt) focus = random_own_point();
    if (!near_item(clamp_reachable(focus))) {
      out.select_colour = colour_;
      start_stroke(t, focus, fill);
      return;
    }
  }
  // A tap on an item or on the map.
  motor_ = MotorProgram{};
  motor_.kind = MotorKind::Tap;
  motor_.t0 = t;
  motor_.duration = rng_.uniform(m.tap_min_s, m.tap_max_s);
  motor_.from = focus + Vec2(rng_.normal(0.0, m.endpoint_sd_m), rng_.normal(0.0, m.endpoint_sd_m));
  motor_.to = motor_.from;
  ++counters_.taps;
  my_last_point_ = focus;
  my_last_action_t_ = t;
}

void ChildAgent::start_drag(double t, const Vec2& from, const Vec2& to, int item) {
  const MotorParams& m = params_->motor;
  motor_ = MotorProgram{};
  motor_.kind = MotorKind::Drag;
  motor_.t0 = t;
  motor_.item = item;
  motor_.from = from + Vec2(rng_.normal(0.0, m.endpoint_sd_m), rng_.normal(0.0, m.endpoint_sd_m));
  motor_.to = to + Vec2(rng_.normal(0.0, m.endpoint_sd_m), rng_.normal(0.0, m.endpoint_sd_m));
  motor_.duration = fitts_duration((motor_.to - motor_.from).norm(), 0.04);
  ++counters_.drags;
  my_last_item_ = item;
  my_last_point_ = to;
  my_last_action_t_ = t + motor_.duration;
  if (labels_.social == SocialEngagement::Cooperative || labels_.social == SocialEngagement::Associative) make_bid(t);
}

void ChildAgent::start_stroke(double t, const Vec2& centre, bool fill) {
  const MotorParams& m = params_->motor;
  motor_ = MotorProgram{};
  motor_.kind = MotorKind::Stroke;
  motor_.t0 = t;
  motor_.duration = rng_.lognormal(std::log(m.stroke_duration_s), 0.4);
  const Vec2 c = clamp_reachable(centre);
  if (fill) {  // boustrophedon rows 1.5 cm apart over a ~6 cm square
    motor_.path_len = 8;
    for (int row = 0; row < 4; ++row) {
      const double y = c.y() - 0.0225 + 0.015 * row;
      const bool left_first = row % 2 == 0;
      motor_.path[static_cast<std::size_t>(2 * row)] = {c.x() + (left_first ? -0.03 : 0.03), y};
      motor_.path[static_cast<std::size_t>(2 * row + 1)] = {c.x() + (left_first ? 0.03 : -0.03), y};
    }
  } else {  // scribble: a jittery random walk
    motor_.path_len = 10;
    Vec2 p = c;
    for (int i = 0; i < motor_.path_len; ++i) {
      motor_.path[static_cast<std::size_t>(i)] = clamp_reachable(p);
      p += Vec2(rng_.normal(0.0, 0.025), rng_.normal(0.0, 0.025));
    }
  }
  motor_.from = motor_.path[0];
  motor_.to = motor_.path[static_cast<std::size_t>(motor_.path_len - 1)];
  ++counters_.strokes;
  my_last_item_ = -1;
  my_last_point_ = c;
  my_last_action_t_ = t + motor_.duration;
}

void ChildAgent::run_motor(double t, ChildActions& out) {
  if (motor_.kind == MotorKind::None) {
    if (motor_.down_sent) {  // interrupted (quit): lift the finger
      out.push_touch({1, TouchPhase::Up, motor_.to});
      motor_.down_sent = false;
    }
    return;
  }
  if (!motor_.down_sent) {
    out.push_touch({1, TouchPhase::Down, motor_.from});
    motor_.down_sent = true;
    return;
  }
  const double tau = (t - motor_.t0) / std::max(motor_.duration, 1e-3);
  if (tau >= 1.0) {
    out.push_touch({1, TouchPhase::Up, motor_.to});
    motor_ = MotorProgram{};
    return;
  }
  Vec2 p = motor_.from;
  if (motor_.kind == MotorKind::Drag) {
    p = motor_.from + min_jerk(tau) * (motor_.to - motor_.from);
  } else if (motor_.kind == MotorKind::Stroke) {
    const double s = tau * (motor_.path_len - 1);
    const int i = std::min(static_cast<int>(s), motor_.path_len - 2);
    const double f = s - i;
    p = (1.0 - f) * motor_.path[static_cast<std::size_t>(i)] + f * motor_.path[static_cast<std::size_t>(i + 1)];
  }
  out.push_touch({1, TouchPhase::Move, p});
}

void ChildAgent::make_bid(double t) {
  if (bid_pending_) return;
  bid_pending_ = true;
  bid_deadline_ = t + params_->drives.bid_response_window_s;
}

void ChildAgent::update_gaze(double t, const ChildPerception& seen, ChildActions& out) {
  (void)out;
  if (t < next_glance_t_) {
    if (motor_.kind != MotorKind::None) {  // eyes follow the hand
      gaze_.kind = GazeKind::Tray;
      gaze_.point = motor_.to;
    }
    return;
  }
  const ExpressionParams& e = params_->expression;
  next_glance_t_ = t + rng_.lognormal(std::log(e.glance_median_s), e.glance_sigma);
  const bool robot = seen.partner.is_robot;
  const GazeKind face = robot ? GazeKind::Robot : GazeKind::PartnerFace;
  gaze_ = GazeTarget{};
  if (quit_) {
    gaze_.kind = rng_.bernoulli(0.5) ? GazeKind::Experimenter : GazeKind::Away;
    return;
  }
  if (labels_.task == TaskEngagement::AdultSeeking && rng_.bernoulli(0.6)) {
    gaze_.kind = GazeKind::Experimenter;
    return;
  }
  if (motor_.kind != MotorKind::None && rng_.bernoulli(0.85)) {
    gaze_.kind = GazeKind::Tray;
    gaze_.point = motor_.to;
    return;
  }
  double p_face = e.partner_face_share[static_cast<std::size_t>(labels_.social)];
  if (robot) p_face += 0.3 * std::exp(-t / (60.0 * params_->drives.novelty_tau_min));
  p_face *= bid_scale();
  if (seen.partner.present && rng_.bernoulli(p_face)) {
    gaze_.kind = face;
    ++counters_.partner_glances;
    make_bid(t);
    return;
  }
  const bool onlooker = labels_.social == SocialEngagement::Onlooker;
  if (onlooker && seen.partner.touch_count == 0 && t - partner_last_t_ < params_->partnership.watch_window_s) {
    // An onlooker keeps its eyes on where the partner plays between the partner's touches.
    gaze_.point = partner_last_point_;
    gaze_.item = partner_last_item_;
    gaze_.kind = gaze_.item >= 0 ? GazeKind::Item : GazeKind::Tray;
    return;
  }
  if ((onlooker || rng_.bernoulli(0.3)) && seen.partner.touch_count > 0) {
    gaze_.kind = GazeKind::Tray;
    gaze_.point = seen.partner.touches[0].point;
    gaze_.item = seen.partner.touches[0].item;
    if (gaze_.item >= 0) gaze_.kind = GazeKind::Item;
    return;
  }
  if (labels_.task == TaskEngagement::NoPlay) {
    // A child out of the game often watches the partner play; otherwise it looks away half the time.
    if (t - partner_last_t_ < params_->partnership.watch_window_s && rng_.bernoulli(0.5)) {
      gaze_.point = partner_last_point_;
      gaze_.item = partner_last_item_;
      gaze_.kind = gaze_.item >= 0 ? GazeKind::Item : GazeKind::Tray;
      return;
    }
    if (rng_.bernoulli(0.5)) {
      gaze_.kind = GazeKind::Away;
      return;
    }
  }
  if (seen.item_count > 0) {
    const SeenItem& item = seen.items[static_cast<std::size_t>(rng_.uniform_int(0, seen.item_count - 1))];
    gaze_.kind = GazeKind::Item;
    gaze_.item = item.item;
    gaze_.point = item.position;
  } else {
    gaze_.kind = GazeKind::Tray;
    gaze_.point = my_last_point_;
  }
}

void ChildAgent::say(Utterance kind, Addressee to, ChildActions& out, double t) {
  const ExpressionParams& e = params_->expression;
  SpeechEvent speech;
  speech.kind = kind;
  speech.to = to;
  speech.syllables = 1 + static_cast<int>(rng_.exponential(1.0 / std::max(0.5, e.syllables_mean - 1.0)));
  const double rate = e.articulation_rate_at_3 + e.articulation_rate_per_year * (profile_.age_years - 3);
  speech.duration_s = speech.syllables / rate;
  speaking_until_ = t + speech.duration_s;
  out.speech = speech;
  ++counters_.utterances;
  if (to == Addressee::Partner) make_bid(t);
}

void ChildAgent::update_speech(double t, double dt, ChildActions& out) {
  if (t < speaking_until_) return;
  if (quit_) {
    if (!announced_stop_) {
      announced_stop_ = true;
      say(Utterance::AnnounceStop, Addressee::Experimenter, out, t);
    }
    return;
  }
  if (protest_pending_) {
    protest_pending_ = false;
    if (labels_.attitude != SocialAttitude::Passive) {
      say(Utterance::Protest, Addressee::Partner, out, t);
      return;
    }
  }
  const ExpressionParams& e = params_->expression;
  if (labels_.task == TaskEngagement::AdultSeeking && rng_.bernoulli(e.adult_speech_per_min * dt / 60.0)) {
    say(rng_.bernoulli(0.5) ? Utterance::Question : Utterance::Request, Addressee::Experimenter, out, t);
    return;
  }
  double rate = e.speech_per_min[static_cast<std::size_t>(labels_.social)] *
                std::exp(0.5 * feature(Feature::Sociability));
  if (partner_robot_) rate += e.robot_curiosity_per_min * std::exp(-t / (60.0 * params_->drives.novelty_tau_min));
  rate *= bid_scale();
  if (rng_.bernoulli(rate * dt / 60.0)) {
    // The attitude shows in what is said: an assertive child directs the play, a passive one hardly proposes.
    const double proposal = e.proposal_share[static_cast<std::size_t>(labels_.attitude)];
    const double u = rng_.uniform();
    const double comment = proposal + (1.0 - proposal) * kCommentShareOfTheRest;
    say(u < proposal ? Utterance::Proposal : (u < comment ? Utterance::Comment : Utterance::Question),
        Addressee::Partner, out, t);
  }
}

double ChildAgent::bid_scale() const {
  const double floor = params_->partnership.bid_floor;
  return floor + (1.0 - floor) * expectation_;
}

double ChildAgent::answer_probability() const {
  const PartnershipParams& pa = params_->partnership;
  const double p = std::clamp(pa.answer_probability[static_cast<std::size_t>(labels_.social)], 1e-6, 1.0 - 1e-6);
  const double logit = std::log(p / (1.0 - p)) + pa.answer_age_logit * feature(Feature::Age) +
                       pa.answer_sociability_logit * feature(Feature::Sociability) + feature(Feature::Motivation);
  return 1.0 / (1.0 + std::exp(-logit));
}

double ChildAgent::reciprocity_window() const {
  const PartnershipParams& pa = params_->partnership;
  return pa.reciprocity_window_s * std::max(0.3, 1.0 + pa.window_per_year * (profile_.age_years - 6.0));
}

void ChildAgent::on_partner_bid(double t, bool joint, bool spoken) {
  if (answer_.active || quit_ || !rng_.bernoulli(answer_probability())) return;
  const PartnershipParams& pa = params_->partnership;
  answer_.active = true;
  answer_.due = t + rng_.lognormal(std::log(pa.answer_delay_median_s), 0.5);
  answer_.spoken = spoken;
  // A glance is answered with a glance; only a spoken or joint bid can draw the child into joint play.
  answer_.join = (joint || spoken) && rng_.bernoulli(pa.join_probability);
  answer_.mode = joint ? SocialEngagement::Cooperative : SocialEngagement::Associative;
}

void ChildAgent::answer_partner(double t, ChildActions& out) {
  if (!answer_.active || t < answer_.due) return;
  answer_.active = false;
  if (quit_) return;
  ++counters_.answers;
  // Answering is visible: the child looks back at the partner, and replies when it was spoken to.
  gaze_ = GazeTarget{};
  gaze_.kind = partner_robot_ ? GazeKind::Robot : GazeKind::PartnerFace;
  next_glance_t_ = t + rng_.lognormal(std::log(params_->expression.glance_median_s), params_->expression.glance_sigma);
  if (answer_.spoken && t >= speaking_until_) say(Utterance::Comment, Addressee::Partner, out, t);
  // Taking up a joint bid joins the partner's joint play (a proposal or a joint act: cooperation).
  const bool together = labels_.social == SocialEngagement::Associative ||
                        labels_.social == SocialEngagement::Cooperative;
  const bool upgrade = answer_.mode == SocialEngagement::Cooperative && labels_.social != SocialEngagement::Cooperative;
  if (answer_.join && (!together || upgrade)) {
    ++counters_.joins;
    last_answered_t_ = t;
    switch_label(Axis::SocialEngagement, static_cast<std::size_t>(answer_.mode), t);
  }
}

void ChildAgent::sustain_joint_play(double t) {
  const auto s = static_cast<std::size_t>(Axis::SocialEngagement);
  const bool partner_playing = t - partner_last_touch_t_ < params_->coder.active_window_s;
  if (labels_.social == SocialEngagement::Associative || labels_.social == SocialEngagement::Cooperative) {
    if (t - std::max(last_answered_t_, bout_start_[s]) <= reciprocity_window()) return;
    ++counters_.joint_play_lapses;
    const auto next = partner_playing ? SocialEngagement::Parallel : SocialEngagement::Solitary;
    switch_label(Axis::SocialEngagement, static_cast<std::size_t>(next), t);
  } else if (labels_.social == SocialEngagement::Onlooker) {
    const double watch = params_->partnership.watch_window_s;
    if (t - bout_start_[s] > watch && t - partner_last_touch_t_ > watch) {
      switch_label(Axis::SocialEngagement, static_cast<std::size_t>(SocialEngagement::Solitary), t);
    }
  }
}

void ChildAgent::finish(double t) {
  for (const Axis axis : kAxes) {
    const auto a = static_cast<std::size_t>(axis);
    if (t > bout_start_[a]) {
      timeline_.push_back({axis, static_cast<std::uint8_t>(labels_.index(axis)), bout_start_[a], t});
      bout_start_[a] = t;
    }
  }
  std::stable_sort(timeline_.begin(), timeline_.end(),
                   [](const LabelInterval& a, const LabelInterval& b) { return a.start < b.start; });
}

}  // namespace freeplay::agents
