// The contingency detector (agents/contingency.hpp): Watson's two conditional rates per kind of bid, the base rate
// on probe windows, Cheng's causal power, the attributable share and habituation.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "freeplay/agents/contingency.hpp"
#include "freeplay/core/rng.hpp"

namespace freeplay::agents {
namespace {

constexpr double kDt = 0.1;

/// The shipped detector parameters (assets/agents/child-model.yaml).
ContingencyParams shipped() { return default_child_model_params().contingency; }

/// What the partner does in one tick: given the time and whether the child just bid, it may act.
using PartnerScript = std::function<void(double t, bool child_bid, ContingencyDetector& detector)>;

/// A child that glances at the partner (a look bid, 1.5 s) at random about every 12 s and talks (2 s) about every
/// 40 s, for `minutes`; the partner acts by `partner`. Returns the detector at the end.
ContingencyDetector run(const ContingencyParams& params, const PartnerScript& partner, double minutes,
                        std::uint64_t seed = 7) {
  ContingencyDetector detector(params);
  Rng rng(seed);
  for (double t = 0.0; t < 60.0 * minutes; t += kDt) {
    detector.advance(t, kDt);
    bool bid = false;
    if (rng.bernoulli(kDt / 12.0)) {
      detector.on_my_bid(t, BidKind::Look, -1, {0.1, -0.2}, 1.5, true);
      bid = true;
    } else if (rng.bernoulli(kDt / 40.0)) {
      detector.on_my_bid(t, BidKind::Talk, -1, {0.1, -0.2}, 2.0, true);
      bid = true;
    }
    partner(t, bid, detector);
  }
  return detector;
}

TEST(Contingency, APartnerWhoAnswersMyBidsIsContingent) {
  const ContingencyParams params = shipped();
  double due = -1.0;
  const auto answers = [&due](double t, bool bid, ContingencyDetector& d) {
    if (bid) due = t + 1.0;  // looks back a second after each bid, and never otherwise
    if (due > 0.0 && t >= due) {
      d.on_partner_act(t, PartnerActKind::LookAtMe, -1, {0.0, 0.0});
      due = -1.0;
    }
  };
  const ContingencyDetector d = run(params, answers, 10.0);
  EXPECT_GT(d.answered_share(), 0.85);
  // Its looks back at my glances also fall in the probe windows of my talk: the base rate is low, not zero.
  EXPECT_LT(d.base_share(), 0.25);
  EXPECT_GT(d.contingency(), 0.75);
  EXPECT_GT(d.attributable_share(), 0.75);
}

TEST(Contingency, APartnerOnAFixedPeriodIsNotContingentThoughItAlwaysSeemsToAnswer) {
  // The timetable chatterer of the validity panel: a look at the child every 4 s, whatever it does.
  const ContingencyParams params = shipped();
  double next = 1.0;
  const auto periodic = [&next](double t, bool, ContingencyDetector& d) {
    if (t >= next) {
      d.on_partner_act(t, PartnerActKind::LookAtMe, -1, {0.0, 0.0});
      next += 4.0;
    }
  };
  const ContingencyDetector d = run(params, periodic, 10.0);
  EXPECT_GT(d.answered_share(), 0.8) << "each bid is followed by a look within its window";
  EXPECT_GT(d.base_share(), 0.8) << "and so is every probe window while the child did nothing";
  EXPECT_LT(d.contingency(), 0.15);
  EXPECT_LT(d.attributable_share(), 0.15);
}

TEST(Contingency, APartnerActingAtRandomIsNotContingent) {
  const ContingencyParams params = shipped();
  Rng rng(11);
  const auto random = [&rng](double t, bool, ContingencyDetector& d) {
    if (rng.bernoulli(kDt / 5.0)) d.on_partner_act(t, PartnerActKind::TalkToMe, -1, {0.0, 0.0});
  };
  const ContingencyDetector d = run(params, random, 20.0);
  EXPECT_LT(d.contingency(), 0.15);
}

TEST(Contingency, APartnerThatNeverActsIsNotContingent) {
  const ContingencyParams params = shipped();
  const ContingencyDetector d = run(params, [](double, bool, ContingencyDetector&) {}, 5.0);
  EXPECT_LT(d.answered_share(), 0.15);
  EXPECT_LT(d.contingency(), 0.1) << "only what is left of the prior's benefit of the doubt";
}

TEST(Contingency, EvidenceMakesAResponderSurelyResponsiveAndATimetableSurelyNot) {
  // Causal support (Griffiths & Tenenbaum 2005): the longer a child watches, the surer it is whether the partner
  // responds at all. Before any bid the prior holds; a responder's link probability rises towards 1, a partner on
  // a timetable's falls (the Occam penalty of a second answer rate that the counts do not need).
  const ContingencyParams params = shipped();
  EXPECT_DOUBLE_EQ(ContingencyDetector(params).link_probability(), params.prior_link_probability);
  double due = -1.0;
  const auto answers = [&due](double t, bool bid, ContingencyDetector& d) {
    if (bid) due = t + 1.0;
    if (due > 0.0 && t >= due) {
      d.on_partner_act(t, PartnerActKind::LookAtMe, -1, {0.0, 0.0});
      due = -1.0;
    }
  };
  EXPECT_GT(run(params, answers, 1.0).link_probability(), params.prior_link_probability);
  EXPECT_GT(run(params, answers, 5.0).link_probability(), 0.99);
  double next = 1.0;
  const auto periodic = [&next](double t, bool, ContingencyDetector& d) {
    if (t >= next) {
      d.on_partner_act(t, PartnerActKind::LookAtMe, -1, {0.0, 0.0});
      next += 4.0;
    }
  };
  const double after_2 = run(params, periodic, 2.0).link_probability();
  next = 1.0;
  const double after_10 = run(params, periodic, 10.0).link_probability();
  EXPECT_LT(after_2, params.prior_link_probability);
  EXPECT_LT(after_10, after_2);
  EXPECT_LT(after_10, 0.2);
}

TEST(Contingency, AnActElsewhereDoesNotAnswerAPlayBid) {
  const ContingencyParams params = shipped();
  ContingencyDetector d(params);
  d.advance(0.0, kDt);
  d.on_my_bid(0.0, BidKind::Play, 3, {0.10, -0.20}, 1.0, false);
  EXPECT_EQ(d.on_partner_act(0.5, PartnerActKind::TouchMyPlay, 5, {0.40, -0.05}), ActClass::Unrelated);
  EXPECT_EQ(d.on_partner_act(0.8, PartnerActKind::TouchMyPlay, 3, {0.11, -0.20}), ActClass::Response);
}

TEST(Contingency, NonContingentAttentionHabituatesAndRecoversSlowly) {
  const ContingencyParams params = shipped();
  ContingencyDetector d(params);
  for (int k = 0; k < 5; ++k) d.habituate();
  const double habituated = d.salience();
  EXPECT_NEAR(habituated, std::pow(1.0 - params.habituation_rate, 5), 1e-12);
  for (double t = 0.0; t < 60.0; t += kDt) d.advance(t, kDt);
  EXPECT_GT(d.salience(), habituated);
  EXPECT_LT(d.salience(), 0.5) << "a minute is not enough to recover (recovery time " << params.habituation_recovery_s
                               << " s)";
}

/// One step of a scripted session: advance by `dt`, then maybe a bid of mine (kind 0–2, or −1) and maybe a partner
/// act (kind 0–3, or −1), and seven of my play bids so that the oldest open bid is closed early now and then.
struct Step {
  double dt;
  int bid;
  int act;
};

std::vector<Step> scripted_steps(std::uint64_t seed, int count) {
  Rng rng(seed);
  std::vector<Step> steps;
  for (int i = 0; i < count; ++i) {
    const double dt = i % 7 == 3 ? 0.25 : (i % 11 == 5 ? 0.05 : kDt);  // mostly the tick, sometimes another length
    const int bid = rng.bernoulli(0.3) ? static_cast<int>(rng.uniform_int(0, 2)) : -1;
    const int act = rng.bernoulli(0.3) ? static_cast<int>(rng.uniform_int(0, 3)) : -1;
    steps.push_back({dt, bid, act});
  }
  return steps;
}

double apply(ContingencyDetector& d, const Step& step, double t) {
  t += step.dt;
  d.advance(t, step.dt);
  if (step.bid >= 0) d.on_my_bid(t, static_cast<BidKind>(step.bid), step.bid == 0 ? 2 : -1, {0.1, -0.2}, 0.5, true);
  if (step.act >= 0) d.on_partner_act(t, static_cast<PartnerActKind>(step.act), 2, {0.12, -0.2});
  return t;
}

/// Everything the detector estimates, read in one order.
std::vector<double> estimates(const ContingencyDetector& d) {
  return {d.contingency(), d.link_probability(), d.attributable_share(), d.answered_share(), d.base_share(),
          d.salience()};
}

TEST(Contingency, CachedEstimatesAndDecayFactorsEqualAFreshDetectorsAfterEveryStep) {
  // A detector read after every step (its estimates, priors and per-step factors cached and reused) against, at
  // each step, a new detector that replays the same steps and is read only then (nothing cached yet): equal to
  // the bit. Steps of three lengths make the kept decay factors change; a missing invalidation would show here.
  const ContingencyParams params = shipped();
  const auto steps = scripted_steps(11, 160);
  ContingencyDetector read_always(params);
  double t = 0.0;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    t = apply(read_always, steps[i], t);
    const auto cached = estimates(read_always);
    ContingencyDetector fresh(params);
    double t_fresh = 0.0;
    for (std::size_t j = 0; j <= i; ++j) t_fresh = apply(fresh, steps[j], t_fresh);
    EXPECT_EQ(cached, estimates(fresh)) << "step " << i;
  }
}

TEST(Contingency, DecayFactorsFollowTheStepLength) {
  // Salience recovers by 1 − exp(−dt / recovery) of what is missing, for each step's own dt (a factor kept from a
  // step of another length would not).
  const ContingencyParams params = shipped();
  ContingencyDetector d(params);
  double expected = 1.0;
  double t = 0.0;
  for (const double dt : {0.1, 0.1, 0.5, 0.1, 2.0, 2.0, 0.1}) {
    d.habituate();
    expected *= 1.0 - params.habituation_rate;
    t += dt;
    d.advance(t, dt);
    expected += (1.0 - expected) * (1.0 - std::exp(-dt / params.habituation_recovery_s));
    EXPECT_EQ(d.salience(), expected) << "dt " << dt;
  }
}

}  // namespace
}  // namespace freeplay::agents
