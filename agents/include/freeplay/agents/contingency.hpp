#pragma once
// How a child detects whether its partner — a child or the robot, by one mechanism — responds to it
// (docs/agents.md, "Contingency").
//
// A partner's act answers me only when it is contingent on something I did: it follows my act or bid within a
// short window AND is about it (my item or area, my utterance, my gaze). The detector keeps Watson's two
// conditional rates as running, forgetting counts, for each kind of bid: how often my bids were followed by an act
// that could answer them, and the base rate of the same acts while I had no such bid open. Its contingency estimate
// is the normalised difference of the two (Cheng's causal power of ΔP), averaged over the kinds of bid by how often
// I make them: a partner who does a lot regardless of me scores as low as one who does nothing.
// It also tracks habituation to non-contingent attention and how often the partner interrupts the child's play.

#include <array>
#include <cstdint>

#include "freeplay/agents/params.hpp"
#include "freeplay/core/geometry.hpp"

namespace freeplay::agents {

/// What kind of bid a child makes (what a response has to be about).
enum class BidKind : std::uint8_t {
  Play,  ///< an act on the tray: a drag, a stroke, a tap (about: my item, my area)
  Look,  ///< a glance at the partner's face (about: my gaze — the partner looks back)
  Talk,  ///< an utterance to the partner (about: my utterance — a reply, a look at the speaker, taking it up)
};

/// What kind of act of the partner's the child notices as possibly about it.
enum class PartnerActKind : std::uint8_t {
  LookAtMe,      ///< the partner's gaze lands on my face
  LookAtMyPlay,  ///< the partner's gaze lands on my item or my area (joint attention)
  TalkToMe,      ///< the partner speaks to me
  TouchMyPlay,   ///< the partner's finger lands on my item or in my area
};

/// How the detector classified a partner's act.
enum class ActClass : std::uint8_t {
  Response,     ///< follows an open bid of mine within the window and is about it: contingent
  Spontaneous,  ///< answers no bid of mine: on my play (the partner joining it unasked), or while I had no bid open
  Unrelated,    ///< came during an open bid but is not about it (or is not about me or my play at all)
};

/// The running contingency estimate of one child about its partner.
class ContingencyDetector {
 public:
  /// A detector with `params` (response window, memory, priors, habituation, interruptions).
  explicit ContingencyDetector(const ContingencyParams& params);

  /// Advances the clock to `t` by `dt`: forgets, closes expired bids, accumulates exposure, recovers habituation.
  void advance(double t, double dt);
  /// I make a bid at `t` that lasts `duration_s` (a drag's movement) before its response window opens; `item` and
  /// `point` say what a response must be about (−1 and my area for looks and talk); `seeking` when I want an answer
  /// (a look, words, an act while playing together), so that its going unanswered counts (take_unanswered).
  void on_my_bid(double t, BidKind kind, int item, const Vec2& point, double duration_s, bool seeking);
  /// I act on `item` / at `point` without seeking an answer: what a partner's act on the tray may be about.
  void on_my_play(int item, const Vec2& point);
  /// The partner did `kind` at `t` on `item` / at `point` (when relevant); returns whether it answered a bid of mine.
  ActClass on_partner_act(double t, PartnerActKind kind, int item, const Vec2& point);
  /// Notes a directed act of the partner (a look at me or words to me) that did not answer me, while I was busy
  /// with my own play; returns the interruption level after it (interruptions within the last
  /// `interruption_tau_s`, decaying).
  double on_interruption();

  /// Contingency estimate in [0, 1]: how likely the partner responds to me at all (`link_probability`) times how
  /// strongly, (P(act | bid) − P(act | no bid)) / (1 − P(act | no bid)), clamped.
  double contingency() const;
  /// P(the partner's acts depend on my bids | the counts): the prior odds times the Bayes factor of "my bids raise
  /// its acts" against "its acts come at one rate, bids or not" (causal support), summed over the kinds of bid.
  double link_probability() const;
  /// The share of the answers to my bids that the partner's base rate does not explain, (p₁ − p₀) / p₁ in [0, 1]
  /// (averaged over the kinds of bid): how likely an act that followed my bid was a response to it.
  double attributable_share() const;
  /// P(a bid of mine was answered within the window), with the prior (averaged over the kinds of bid).
  double answered_share() const;
  /// P(at least one act of the kinds that could answer a bid in a window of the same length while no such bid of
  /// mine was open): the base rate (averaged over the kinds of bid).
  double base_share() const;
  /// Salience of non-contingent attention in [0, 1]: 1 when fresh, lower after repetition (habituation).
  double salience() const { return salience_; }
  /// Notes one non-contingent stimulus: salience falls by the habituation rate.
  void habituate();
  /// True while a bid of mine is open (made and not yet answered or expired).
  bool bid_open() const { return open_count_ > 0; }
  /// Seeking bids that closed without an answer since the last call (the unanswered-bid reaction); resets the count.
  int take_unanswered();
  /// Bids answered since the last call; resets the count.
  int take_answered();

 private:
  struct OpenBid {
    BidKind kind = BidKind::Play;
    double opened = 0.0;
    double closes = 0.0;
    int item = -1;
    Vec2 point{0.0, 0.0};
    bool answered = false;
    bool seeking = false;
  };

  /// Watson's counts for one kind of bid (forgetting).
  struct Rates {
    double bids = 0.0;      // closed bids
    double answered = 0.0;  // … of those answered
    double window_s = 0.0;  // summed length of the closed bids' windows (the act's duration + the response window)
    double probes = 0.0;    // windows of that length that passed while no bid of this kind was open
    double probe_hits = 0.0;// … of those, windows in which an act came that could have answered such a bid
    bool probing = false;   // a probe window is running
    double probe_closes = 0.0;
    bool probe_hit = false;
  };
  static constexpr std::size_t kBidKinds = 3;

  bool about(const OpenBid& bid, PartnerActKind kind, int item, const Vec2& point) const;
  bool about_my_play(int item, const Vec2& point) const;
  static bool could_answer(BidKind bid, PartnerActKind act);
  bool open_of(BidKind kind) const;
  void close(const OpenBid& bid);
  double answered_share(const Rates& r) const;
  double mean_window(const Rates& r) const;
  /// `measure`(p₁, p₀) of one kind of bid: the counts' value shrunk towards the priors' by the evidence held.
  double shrunk(const Rates& r, double (*measure)(double p1, double p0)) const;
  double base_share(const Rates& r) const;
  /// The bid-weighted mean of `share` over the kinds of bid.
  template <typename Share>
  double weighted(Share share) const;

  const ContingencyParams* params_;
  double prior_log_odds_;  ///< log(prior / (1 − prior)) of `prior_link_probability`, computed once
  /// The forgetting, interruption decay and habituation recovery factors of one step of `dt` seconds, kept for the
  /// next step of the same length (the exp calls of every tick).
  struct Decay {
    double dt = -1.0;  ///< the step they belong to (−1: none yet)
    double keep = 0.0;
    double interruptions = 0.0;
    double recovery = 0.0;
  };
  Decay decay_;
  /// The factors of a step of `dt` seconds.
  Decay decay_over(double dt) const;
  static constexpr int kMaxOpen = 6;
  std::array<OpenBid, kMaxOpen> open_{};
  int open_count_ = 0;
  std::array<Rates, kBidKinds> rates_{};  ///< per BidKind
  double salience_ = 1.0;
  double interruptions_ = 0.0;
  int my_item_ = -1;
  Vec2 my_point_{0.0, 0.0};
  bool have_play_ = false;
  int unanswered_new_ = 0;
  int answered_new_ = 0;
  /// The estimates computed from the counts, kept until the counts change (advance, close): they are read
  /// several times per tick and each costs 27 lgamma calls.
  struct Estimates {
    bool valid = false;
    double link = 0.0;
    double contingency = 0.0;
  };
  mutable Estimates cached_;
  /// The base rate's prior of each kind of bid, 1 − exp(−rate × mean window), kept like the estimates: the
  /// estimates and base_share() both read it every tick.
  struct Priors {
    bool valid = false;
    std::array<double, kBidKinds> base_share{};
  };
  mutable Priors priors_;
  /// The base rate's prior of `r` (one of rates_).
  double prior_base_share(const Rates& r) const;
  /// link_probability() computed from the counts (causal support).
  double causal_support_link() const;
  /// Computes link_probability() and contingency() from the counts.
  Estimates estimate() const;
};

}  // namespace freeplay::agents
