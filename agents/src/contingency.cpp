#include "freeplay/agents/contingency.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace freeplay::agents {

ContingencyDetector::ContingencyDetector(const ContingencyParams& params)
    : params_(&params),
      prior_log_odds_(std::log(params.prior_link_probability / (1.0 - params.prior_link_probability))) {}

ContingencyDetector::Decay ContingencyDetector::decay_over(double dt) const {
  const ContingencyParams& p = *params_;
  Decay d;
  d.dt = dt;
  d.keep = p.memory_s > 0.0 ? std::exp(-dt / p.memory_s) : 0.0;
  d.interruptions = p.interruption_tau_s > 0.0 ? std::exp(-dt / p.interruption_tau_s) : 0.0;
  d.recovery = p.habituation_recovery_s > 0.0 ? 1.0 - std::exp(-dt / p.habituation_recovery_s) : 1.0;
  return d;
}

void ContingencyDetector::advance(double t, double dt) {
  // The episode's tick is fixed, so the factors of the last step are those of this one (bit for bit).
  if (!(decay_.dt == dt)) decay_ = decay_over(dt);
  const double keep = decay_.keep;
  cached_.valid = false;
  priors_.valid = false;
  for (Rates& r : rates_) {
    r.bids *= keep;
    r.answered *= keep;
    r.window_s *= keep;
    r.probes *= keep;
    r.probe_hits *= keep;
  }
  interruptions_ *= decay_.interruptions;
  salience_ += (1.0 - salience_) * decay_.recovery;
  int kept = 0;
  for (int i = 0; i < open_count_; ++i) {
    const OpenBid& bid = open_[static_cast<std::size_t>(i)];
    if (t > bid.closes) {
      close(bid);
    } else {
      open_[static_cast<std::size_t>(kept++)] = bid;
    }
  }
  open_count_ = kept;
  // The base rate of each kind of bid is measured on probe windows, as long as my bids' windows, laid end to end
  // over the stretches where I had no such bid open: the share of them in which the partner did something that
  // could have answered such a bid. Counting windows, not a rate, keeps a partner acting on a fixed period as
  // "always there" as it is after my bids. A bid of mine cancels the running probe.
  for (std::size_t k = 0; k < kBidKinds; ++k) {
    Rates& r = rates_[k];
    if (open_of(static_cast<BidKind>(k))) {
      r.probing = false;
      continue;
    }
    if (r.probing && t >= r.probe_closes) {
      r.probes += 1.0;
      r.probe_hits += r.probe_hit ? 1.0 : 0.0;
      r.probing = false;
    }
    if (!r.probing) {
      r.probing = true;
      r.probe_hit = false;
      r.probe_closes = t + mean_window(r);
    }
  }
}

double ContingencyDetector::mean_window(const Rates& r) const {
  const ContingencyParams& p = *params_;
  return (r.window_s + p.prior_bids * p.response_window_s) / (r.bids + p.prior_bids);
}

bool ContingencyDetector::open_of(BidKind kind) const {
  for (int i = 0; i < open_count_; ++i) {
    if (open_[static_cast<std::size_t>(i)].kind == kind) return true;
  }
  return false;
}

void ContingencyDetector::close(const OpenBid& bid) {
  Rates& r = rates_[static_cast<std::size_t>(bid.kind)];
  cached_.valid = false;
  priors_.valid = false;
  r.bids += 1.0;
  r.window_s += bid.closes - bid.opened;
  if (bid.answered) {
    r.answered += 1.0;
  } else if (bid.seeking) {
    ++unanswered_new_;
  }
}

void ContingencyDetector::on_my_bid(double t, BidKind kind, int item, const Vec2& point, double duration_s,
                                    bool seeking) {
  if (kind == BidKind::Play) {
    my_item_ = item;
    my_point_ = point;
    have_play_ = true;
  }
  // A new bid of the same kind replaces an open, unanswered one: one question is one bid however often repeated.
  for (int i = 0; i < open_count_; ++i) {
    OpenBid& bid = open_[static_cast<std::size_t>(i)];
    if (bid.kind == kind && !bid.answered) {
      bid.opened = t;
      bid.closes = t + duration_s + params_->response_window_s;
      bid.item = item;
      bid.point = point;
      bid.seeking = bid.seeking || seeking;
      return;
    }
  }
  if (open_count_ == kMaxOpen) {  // the oldest open bid is closed early
    close(open_[0]);
    std::move(open_.begin() + 1, open_.end(), open_.begin());
    --open_count_;
  }
  open_[static_cast<std::size_t>(open_count_++)] = {kind, t, t + duration_s + params_->response_window_s, item, point,
                                                    false, seeking};
}

void ContingencyDetector::on_my_play(int item, const Vec2& point) {
  my_item_ = item;
  my_point_ = point;
  have_play_ = true;
}

bool ContingencyDetector::about_my_play(int item, const Vec2& point) const {
  if (!have_play_) return false;
  return (item >= 0 && item == my_item_) || (point - my_point_).norm() < params_->about_distance_m;
}

bool ContingencyDetector::could_answer(BidKind bid, PartnerActKind act) {
  switch (act) {
    case PartnerActKind::LookAtMe: return bid == BidKind::Look || bid == BidKind::Talk;  // looking back at me
    case PartnerActKind::LookAtMyPlay: return bid == BidKind::Play;  // joint attention to what I just did
    case PartnerActKind::TalkToMe: return true;  // a reply, or a comment on what I just did
    case PartnerActKind::TouchMyPlay: return bid == BidKind::Play || bid == BidKind::Talk;  // joining it, taking it up
  }
  return false;
}

bool ContingencyDetector::about(const OpenBid& bid, PartnerActKind kind, int item, const Vec2& point) const {
  if (!could_answer(bid.kind, kind)) return false;
  if (kind != PartnerActKind::LookAtMyPlay && kind != PartnerActKind::TouchMyPlay) return true;
  // An act on the tray is about my play act (its item, its spot), or, answering my words, about what I play with.
  if (bid.kind != BidKind::Play) return about_my_play(item, point);
  return (item >= 0 && item == bid.item) || (point - bid.point).norm() < params_->about_distance_m;
}

ActClass ContingencyDetector::on_partner_act(double t, PartnerActKind kind, int item, const Vec2& point) {
  const bool on_play = kind == PartnerActKind::LookAtMyPlay || kind == PartnerActKind::TouchMyPlay;
  // The base rate of each kind of bid counts the acts that could answer it that come while no such bid of mine is
  // open: how often the partner does such things when I did nothing (Watson's probability of the stimulus given
  // no response); acts on the tray count only where they are about my play. A partner acting on a timetable does
  // so as often in these stretches as after my bids; a partner that answers me does so mostly after them.
  if (!on_play || about_my_play(item, point)) {
    for (std::size_t k = 0; k < kBidKinds; ++k) {
      Rates& r = rates_[k];
      if (r.probing && could_answer(static_cast<BidKind>(k), kind)) r.probe_hit = true;
    }
  }
  for (int i = 0; i < open_count_; ++i) {
    OpenBid& bid = open_[static_cast<std::size_t>(i)];
    if (bid.answered || t < bid.opened || !about(bid, kind, item, point)) continue;
    bid.answered = true;
    ++answered_new_;
    return ActClass::Response;
  }
  if (on_play) return about_my_play(item, point) ? ActClass::Spontaneous : ActClass::Unrelated;
  return open_count_ > 0 ? ActClass::Unrelated : ActClass::Spontaneous;
}

double ContingencyDetector::on_interruption() {
  interruptions_ += 1.0;
  return interruptions_;
}

void ContingencyDetector::habituate() { salience_ *= 1.0 - params_->habituation_rate; }

double ContingencyDetector::prior_base_share(const Rates& r) const {
  if (!priors_.valid) {
    const ContingencyParams& p = *params_;
    for (std::size_t k = 0; k < kBidKinds; ++k) {
      priors_.base_share[k] = 1.0 - std::exp(-p.prior_base_rate_per_min / 60.0 * mean_window(rates_[k]));
    }
    priors_.valid = true;
  }
  return priors_.base_share[static_cast<std::size_t>(&r - rates_.data())];
}

double ContingencyDetector::answered_share(const Rates& r) const {
  const ContingencyParams& p = *params_;
  return (r.answered + p.prior_bids * p.prior_answered_share) / (r.bids + p.prior_bids);
}

double ContingencyDetector::base_share(const Rates& r) const {
  const ContingencyParams& p = *params_;
  // The prior: the partner acting at `prior_base_rate_per_min` at random, worth `prior_free_time_s` of probing.
  const double prior = prior_base_share(r);
  const double prior_probes = p.prior_free_time_s / std::max(mean_window(r), 1e-3);
  return (r.probe_hits + prior_probes * prior) / (r.probes + prior_probes);
}

template <typename Share>
double ContingencyDetector::weighted(Share share) const {
  double sum = 0.0;
  double weight = 0.0;
  for (const Rates& r : rates_) {
    const double w = r.bids + 1e-3;  // the kinds of bid I make; before any, the priors alike
    sum += w * share(r);
    weight += w;
  }
  return sum / weight;
}

double ContingencyDetector::answered_share() const {
  return weighted([this](const Rates& r) { return answered_share(r); });
}

double ContingencyDetector::base_share() const {
  return weighted([this](const Rates& r) { return base_share(r); });
}

double ContingencyDetector::shrunk(const Rates& r, double (*measure)(double p1, double p0)) const {
  const ContingencyParams& p = *params_;
  // What the priors alone say (a new partner gets the benefit of the doubt) …
  const double prior = measure(p.prior_answered_share, prior_base_share(r));
  if (r.bids <= 0.0 || r.probes <= 0.0) return prior;
  // … moved towards what the counts say, by as much evidence as the scarcer of the two counts holds.
  const double observed = measure(r.answered / r.bids, r.probe_hits / r.probes);
  const double evidence = r.bids * r.probes / (r.bids + r.probes);
  return (evidence * observed + p.prior_bids * prior) / (evidence + p.prior_bids);
}

double ContingencyDetector::attributable_share() const {
  return weighted([this](const Rates& r) {
    return shrunk(r, [](double p1, double p0) { return p1 > 0.0 ? std::clamp((p1 - p0) / p1, 0.0, 1.0) : 0.0; });
  });
}

double ContingencyDetector::contingency() const {
  if (!cached_.valid) cached_ = estimate();
  return cached_.contingency;
}

double ContingencyDetector::link_probability() const {
  if (!cached_.valid) cached_ = estimate();
  return cached_.link;
}

ContingencyDetector::Estimates ContingencyDetector::estimate() const {
  Estimates e;
  e.valid = true;
  e.link = causal_support_link();
  e.contingency = e.link * weighted([this](const Rates& r) {
    return shrunk(r, [](double p1, double p0) { return p0 < 1.0 ? std::clamp((p1 - p0) / (1.0 - p0), 0.0, 1.0) : 0.0; });
  });
  return e;
}

namespace {

/// log B(a, b), the Beta function.
double log_beta(double a, double b) { return std::lgamma(a) + std::lgamma(b) - std::lgamma(a + b); }

}  // namespace

double ContingencyDetector::causal_support_link() const {
  // Causal support (Griffiths & Tenenbaum 2005): the log Bayes factor of two answer rates (after my bids, and in
  // the probe windows without them), each with a uniform prior, against one rate for both. The Occam penalty of
  // the second rate makes a partner whose acts are as frequent after my bids as without them *less* likely to be
  // responsive the more it is observed; an answer rate below the base rate is evidence against a response too.
  double support = 0.0;
  for (const Rates& r : rates_) {
    if (r.bids <= 0.0 || r.probes <= 0.0) continue;
    const double a = r.answered;
    const double h = r.probe_hits;
    const double log_bf = log_beta(a + 1.0, r.bids - a + 1.0) + log_beta(h + 1.0, r.probes - h + 1.0) -
                          log_beta(a + h + 1.0, r.bids + r.probes - a - h + 1.0);
    support += a / r.bids > h / r.probes ? log_bf : -std::fabs(log_bf);
  }
  const double log_odds = std::clamp(support + prior_log_odds_, -30.0, 30.0);
  return 1.0 / (1.0 + std::exp(-log_odds));
}

int ContingencyDetector::take_unanswered() { return std::exchange(unanswered_new_, 0); }

int ContingencyDetector::take_answered() { return std::exchange(answered_new_, 0); }

}  // namespace freeplay::agents
