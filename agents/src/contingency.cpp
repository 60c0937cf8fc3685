#include "freeplay/agents/contingency.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace freeplay::agents {

ContingencyDetector::ContingencyDetector(const ContingencyParams& params) : params_(&params) {}

void ContingencyDetector::advance(double t, double dt) {
  const ContingencyParams& p = *params_;
  const double keep = p.memory_s > 0.0 ? std::exp(-dt / p.memory_s) : 0.0;
  bids_ *= keep;
  answered_ *= keep;
  time_s_ *= keep;
  acts_ *= keep;
  interruptions_ *= p.interruption_tau_s > 0.0 ? std::exp(-dt / p.interruption_tau_s) : 0.0;
  salience_ += (1.0 - salience_) * (p.habituation_recovery_s > 0.0 ? 1.0 - std::exp(-dt / p.habituation_recovery_s) : 1.0);
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
  time_s_ += dt;
}

void ContingencyDetector::close(const OpenBid& bid) {
  bids_ += 1.0;
  if (bid.answered) {
    answered_ += 1.0;
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

bool ContingencyDetector::about_my_play(int item, const Vec2& point) const {
  if (!have_play_) return false;
  return (item >= 0 && item == my_item_) || (point - my_point_).norm() < params_->about_distance_m;
}

bool ContingencyDetector::about(const OpenBid& bid, PartnerActKind kind, int item, const Vec2& point) const {
  switch (kind) {
    case PartnerActKind::LookAtMe:  // looking back at me, or at me while I speak
      return bid.kind == BidKind::Look || bid.kind == BidKind::Talk;
    case PartnerActKind::LookAtMyPlay:  // joint attention to what I just did
      return bid.kind == BidKind::Play &&
             ((item >= 0 && item == bid.item) || (point - bid.point).norm() < params_->about_distance_m);
    case PartnerActKind::TalkToMe:  // a reply, or a comment on what I just did
      return true;
    case PartnerActKind::TouchMyPlay:  // joining my act, or taking up what I said
      return bid.kind == BidKind::Talk ||
             (bid.kind == BidKind::Play &&
              ((item >= 0 && item == bid.item) || (point - bid.point).norm() < params_->about_distance_m));
  }
  return false;
}

ActClass ContingencyDetector::on_partner_act(double t, PartnerActKind kind, int item, const Vec2& point) {
  const bool on_play = kind == PartnerActKind::LookAtMyPlay || kind == PartnerActKind::TouchMyPlay;
  // The base rate counts every act of the kinds that could answer me, whenever it comes (Watson's unconditional
  // probability of the stimulus); acts on the tray count only where they are about my play.
  if (!on_play || about_my_play(item, point)) acts_ += 1.0;
  for (int i = 0; i < open_count_; ++i) {
    OpenBid& bid = open_[static_cast<std::size_t>(i)];
    if (bid.answered || t < bid.opened || !about(bid, kind, item, point)) continue;
    bid.answered = true;
    ++answered_new_;
    return ActClass::Response;
  }
  if (open_count_ > 0 || (on_play && !about_my_play(item, point))) return ActClass::Unrelated;
  return ActClass::Spontaneous;
}

double ContingencyDetector::on_interruption() {
  interruptions_ += 1.0;
  return interruptions_;
}

void ContingencyDetector::habituate() { salience_ *= 1.0 - params_->habituation_rate; }

double ContingencyDetector::answered_share() const {
  const ContingencyParams& p = *params_;
  return (answered_ + p.prior_bids * p.prior_answered_share) / (bids_ + p.prior_bids);
}

double ContingencyDetector::base_share() const {
  const ContingencyParams& p = *params_;
  const double rate_per_s = (acts_ + p.prior_free_time_s * p.prior_base_rate_per_min / 60.0) /
                            (time_s_ + p.prior_free_time_s);
  return 1.0 - std::exp(-rate_per_s * p.response_window_s);
}

double ContingencyDetector::contingency() const {
  const double p0 = base_share();
  return std::clamp((answered_share() - p0) / std::max(1.0 - p0, 1e-6), 0.0, 1.0);
}

int ContingencyDetector::take_unanswered() { return std::exchange(unanswered_new_, 0); }

int ContingencyDetector::take_answered() { return std::exchange(answered_new_, 0); }

}  // namespace freeplay::agents
