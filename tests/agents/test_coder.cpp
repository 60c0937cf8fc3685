// The coder's rules on hand-made behaviour (docs/agents.md, "The coder"), and the partnership mechanism of the
// synthetic children on the logic-only simulator: reciprocity, pair coding, age.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "freeplay/agents/calibration.hpp"
#include "freeplay/agents/coder.hpp"
#include "freeplay/agents/session.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"

using namespace freeplay;
using namespace freeplay::agents;

namespace {

const ChildModelParams& params() {
  static const ChildModelParams p = default_child_model_params();
  return p;
}

/// Behaviour of one player at time t (s), written by a test.
using Script = std::function<ObservedPlayer(double t)>;

/// Runs the coder over `seconds` at 10 Hz and returns each coded player's shares of the labels of `axis`.
std::array<std::array<double, kMaxLabels>, 2> code(const Script& first, const Script& second, double seconds,
                                                   bool second_is_robot = false,
                                                   Axis axis = Axis::SocialEngagement) {
  PairCoder coder(params().coder, second_is_robot);
  for (long tick = 0; tick * 0.1 < seconds; ++tick) {
    const double t = static_cast<double>(tick) * 0.1;
    coder.observe(t, first(t), second(t));
  }
  coder.finish(seconds);
  return {label_shares(coder.timeline(0), axis),
          second_is_robot ? std::array<double, kMaxLabels>{} : label_shares(coder.timeline(1), axis)};
}

/// A player that drags an item at `x` for 1 s of every `period` s (starting at `phase`).
ObservedPlayer plays(double t, double x, int item, double period = 4.0, double phase = 0.0) {
  ObservedPlayer o;
  const double u = std::fmod(t + 1000.0 * period - phase, period);
  if (u < 1.0) {
    o.touching = true;
    o.touch_point = {x, -0.15};
    o.touch_item = item;
    o.touch_started = u < 0.1;
  }
  o.gaze.kind = GazeKind::Tray;
  o.gaze.point = {x, -0.15};
  return o;
}

/// Adds an utterance of `kind` to the partner starting at times k·period + phase.
ObservedPlayer speaks(ObservedPlayer o, double t, Utterance kind, double period, double phase) {
  const double u = std::fmod(t + 1000.0 * period - phase, period);
  if (u < 0.1) o.speech = SpeechEvent{kind, Addressee::Partner, 1.0, 3};
  if (u < 1.0) o.gaze.kind = GazeKind::PartnerFace;
  return o;
}

/// A player that scribbles in `colour` (picked on the palette first) for 1 s of every `period` s.
ObservedPlayer draws(double t, PaletteColour colour, double period = 3.0) {
  ObservedPlayer o;
  const double u = std::fmod(t, period);
  if (u < 0.1) o.stroke_colour = colour;
  if (u >= 0.1 && u < 1.1) {
    o.touching = true;
    o.touch_point = {0.2 + 0.1 * u, -0.1};
    o.touch_started = u < 0.2;
  }
  o.gaze.kind = GazeKind::Tray;
  o.gaze.point = o.touch_point;
  return o;
}

/// A player that does nothing but look away.
ObservedPlayer idles(double) {
  ObservedPlayer o;
  o.gaze.kind = GazeKind::Away;
  return o;
}

/// The share of `label` (a task-engagement or social-attitude enumerator) among the shares of its axis.
template <typename Label>
double share(const std::array<double, kMaxLabels>& shares, Label label) {
  return shares[static_cast<std::size_t>(label)];
}

constexpr std::size_t kSolitary = 0, kOnlooker = 1, kParallel = 2, kAssociative = 3, kCooperative = 4;

}  // namespace

TEST(Coder, PlayingSideBySideWithoutAttentionIsParallelForBoth) {
  const auto shares = code([](double t) { return plays(t, 0.10, 0); }, [](double t) { return plays(t, 0.45, 5, 3.0); }, 120);
  EXPECT_GT(shares[0][kParallel], 0.9);
  EXPECT_GT(shares[1][kParallel], 0.9);
}

TEST(Coder, TalkingBackAndForthIsAssociativeForBoth) {
  const auto shares = code([](double t) { return speaks(plays(t, 0.10, 0), t, Utterance::Comment, 6.0, 0.0); },
                           [](double t) { return speaks(plays(t, 0.45, 5), t, Utterance::Comment, 6.0, 1.5); }, 120);
  EXPECT_GT(shares[0][kAssociative], 0.85);
  EXPECT_GT(shares[1][kAssociative], 0.85);
}

TEST(Coder, AProposalTakenUpOrJointWorkIsCooperativeForBoth) {
  // Purple proposes, yellow answers and then works on purple's item.
  const auto shares = code([](double t) { return speaks(plays(t, 0.10, 0), t, Utterance::Proposal, 6.0, 0.0); },
                           [](double t) { return speaks(plays(t, 0.11, 0, 4.0, 2.0), t, Utterance::Comment, 6.0, 1.5); },
                           120);
  EXPECT_GT(shares[0][kCooperative], 0.85);
  EXPECT_GT(shares[1][kCooperative], 0.85);
}

TEST(Coder, ChildWatchingTheOtherPlayIsOnlookerAndThePlayerSolitary) {
  const auto watcher = [](double t) {
    ObservedPlayer o;
    o.gaze.kind = GazeKind::Item;
    o.gaze.item = 0;  // the item the other child keeps moving
    (void)t;
    return o;
  };
  const auto shares = code([](double t) { return plays(t, 0.10, 0); }, watcher, 120);
  EXPECT_GT(shares[0][kSolitary], 0.85);
  EXPECT_GT(shares[1][kOnlooker], 0.8);
}

TEST(Coder, AttentionTheOtherNeverReturnsIsNoExchange) {
  // The child talks to and looks at a partner that plays on and never attends back: no joint play is coded.
  const auto shares = code([](double t) { return speaks(plays(t, 0.10, 0), t, Utterance::Proposal, 5.0, 0.0); },
                           [](double t) { return plays(t, 0.12, 1, 4.0, 2.0); }, 300, /*second_is_robot=*/true);
  EXPECT_EQ(shares[0][kAssociative] + shares[0][kCooperative], 0.0);
  EXPECT_GT(shares[0][kParallel], 0.9);
}

TEST(Coder, OneExchangeIsOneBoutForItsWindow) {
  // One spoken exchange (two remarks each) in a minute and a half of parallel play: one associative bout for each
  // child, from the answer that makes it a conversation (two answers within the window) until the answers leave
  // the interaction window, then parallel again.
  PairCoder coder(params().coder, false);
  for (long tick = 0; tick < 900; ++tick) {
    const double t = tick * 0.1;
    ObservedPlayer a = plays(t, 0.1, 0);
    ObservedPlayer b = plays(t, 0.45, 5, 3.0);
    // Each child keeps the exchange up for two remarks, 4 s apart.
    if (t > 30.0 && t < 36.0) a = speaks(a, t, Utterance::Comment, 4.0, 30.05);
    if (t > 31.0 && t < 37.0) b = speaks(b, t, Utterance::Comment, 4.0, 31.05);
    coder.observe(t, a, b);
  }
  coder.finish(90.0);
  for (int who = 0; who < 2; ++who) {
    int associative_bouts = 0;
    double associative_s = 0.0;
    for (const auto& bout : coder.timeline(who, Axis::SocialEngagement)) {
      if (bout.label != kAssociative) continue;
      ++associative_bouts;
      associative_s += bout.stop - bout.start;
    }
    EXPECT_EQ(associative_bouts, 1);
    // From the second answer (a's second remark, 34 s) until it leaves the window (only one answer is left then).
    EXPECT_NEAR(associative_s, params().coder.interaction_window_s, 1.5);
  }
}

TEST(Coder, MovingItemsAndDrawingTheLandscapeIsGoalOriented) {
  const auto shares = code([](double t) { return plays(t, 0.10, 0, 3.0); },
                           [](double t) { return draws(t, PaletteColour::Green); }, 120, false, Axis::TaskEngagement);
  EXPECT_GT(share(shares[0], TaskEngagement::GoalOriented), 0.9);
  EXPECT_GT(share(shares[1], TaskEngagement::GoalOriented), 0.9);
}

TEST(Coder, ScribblesInOtherColoursAreAimlessAndNothingIsNoPlay) {
  const auto shares = code([](double t) { return draws(t, PaletteColour::Red); }, idles, 120, false,
                           Axis::TaskEngagement);
  EXPECT_GT(share(shares[0], TaskEngagement::Aimless), 0.9);
  EXPECT_GT(share(shares[1], TaskEngagement::NoPlay), 0.9);
}

TEST(Coder, InAnExchangeThePairsKindOfPlayIsJudgedTogether) {
  // One child moves items, the other scribbles in red: apart, one is goal-oriented and the other aimless; talking
  // back and forth, the coder sees one activity and gives both the same kind of play (docs/agents.md, §8).
  const auto agreement = [](bool talk) {
    PairCoder coder(params().coder, false);
    const double seconds = 120.0;
    for (long tick = 0; tick * 0.1 < seconds; ++tick) {
      const double t = static_cast<double>(tick) * 0.1;
      ObservedPlayer builder = plays(t, 0.10, 0, 2.0);
      ObservedPlayer scribbler = draws(t, PaletteColour::Red, 4.0);
      if (talk) {
        builder = speaks(builder, t, Utterance::Comment, 6.0, 0.5);
        scribbler = speaks(scribbler, t, Utterance::Comment, 6.0, 2.0);
      }
      coder.observe(t, builder, scribbler);
    }
    coder.finish(seconds);
    return timeline_agreement(coder.timeline(0), coder.timeline(1), Axis::TaskEngagement, seconds);
  };
  EXPECT_LT(agreement(false), 0.2);
  EXPECT_GT(agreement(true), 0.8);
}

TEST(Coder, LookingAtTheExperimenterIsAdultSeeking) {
  const auto shares = code(
      [](double t) {
        ObservedPlayer o = plays(t, 0.10, 0, 3.0);
        if (std::fmod(t, 2.0) < 0.5) o.gaze.kind = GazeKind::Experimenter;
        return o;
      },
      idles, 120, false, Axis::TaskEngagement);
  EXPECT_GT(share(shares[0], TaskEngagement::AdultSeeking), 0.9);
}

TEST(Coder, PlayingAloneIsPassiveAndTalkingTogetherIsProsocial) {
  const auto alone = code([](double t) { return plays(t, 0.10, 0); }, [](double t) { return plays(t, 0.45, 5, 3.0); },
                          120, false, Axis::SocialAttitude);
  EXPECT_GT(share(alone[0], SocialAttitude::Passive), 0.9);
  const auto together =
      code([](double t) { return speaks(plays(t, 0.10, 0), t, Utterance::Comment, 6.0, 0.0); },
           [](double t) { return speaks(plays(t, 0.45, 5), t, Utterance::Comment, 6.0, 1.5); }, 120, false,
           Axis::SocialAttitude);
  EXPECT_GT(share(together[0], SocialAttitude::Prosocial), 0.8);
  EXPECT_GT(share(together[1], SocialAttitude::Prosocial), 0.8);
}

TEST(Coder, OneRemarkFromAChildKeepingToItselfIsNoAttitudeButTalkKeptUpIs) {
  // "Pro-social: the child's own interaction about the play": one comment in two minutes of playing alone is not
  // an attitude; comments kept up (one every 6 s) are.
  const auto once = code(
      [](double t) {
        ObservedPlayer o = plays(t, 0.10, 0);
        if (t > 30.0 && t < 31.0) o = speaks(o, t, Utterance::Comment, 100.0, 30.05);
        return o;
      },
      [](double t) { return plays(t, 0.45, 5, 3.0); }, 120, false, Axis::SocialAttitude);
  EXPECT_GT(share(once[0], SocialAttitude::Passive), 0.95);
  const auto kept_up = code([](double t) { return speaks(plays(t, 0.10, 0), t, Utterance::Comment, 6.0, 0.0); },
                            [](double t) { return plays(t, 0.45, 5, 3.0); }, 120, false, Axis::SocialAttitude);
  EXPECT_GT(share(kept_up[0], SocialAttitude::Prosocial), 0.8);
}

TEST(Coder, AnAnchoredCoderNeedsALongerChangeToEndALongBout) {
  // After 100 s of playing alone, 8 s of talk (longer than the attitude's minimum bout) ends the passive bout for
  // a coder without anchoring, but not for one that asks a change to last a quarter of the bout it ends.
  const auto script = [](double t) {
    ObservedPlayer o = plays(t, 0.10, 0);
    if (t >= 100.0 && t < 108.0) o = speaks(o, t, Utterance::Comment, 2.0, 100.05);
    return o;
  };
  const auto bouts = [&](double anchoring) {
    CoderParams p = params().coder;
    p.anchoring = anchoring;
    p.attitude_min_bout_s = 3.0;
    p.interaction_hold_s = 4.0;
    PairCoder coder(p, true);
    for (long tick = 0; tick < 1500; ++tick) {
      const double t = static_cast<double>(tick) * 0.1;
      coder.observe(t, script(t), idles(t));
    }
    coder.finish(150.0);
    return coder.timeline(0, Axis::SocialAttitude).size();
  };
  EXPECT_GE(bouts(0.0), 3u);
  EXPECT_EQ(bouts(0.25), 1u);
}

TEST(Coder, DirectingTheOthersPlayInAnExchangeIsAssertive) {
  const auto shares =
      code([](double t) { return speaks(plays(t, 0.10, 0), t, Utterance::Proposal, 5.0, 0.0); },
           [](double t) { return speaks(plays(t, 0.45, 5), t, Utterance::Comment, 5.0, 1.5); }, 120, false,
           Axis::SocialAttitude);
  EXPECT_GT(share(shares[0], SocialAttitude::Assertive), 0.8);
  EXPECT_GT(share(shares[1], SocialAttitude::Prosocial), 0.8);
}

TEST(Coder, TakingTheOthersItemIsAdversarialAndAProtestIsFrustrated) {
  // Yellow plays with item 3; at 30 s purple grabs it and yellow protests; the children never talk otherwise.
  PairCoder coder(params().coder, false);
  for (long tick = 0; tick < 600; ++tick) {
    const double t = tick * 0.1;
    ObservedPlayer purple = plays(t, 0.10, 0, 4.0);
    ObservedPlayer yellow = t < 29.0 ? plays(t, 0.45, 3, 2.0) : plays(t, 0.45, 5, 4.0, 2.0);
    if (t >= 30.0 && t < 31.5) {
      purple = plays(t, 0.45, 3, 100.0, 30.0);
    }
    if (t >= 31.5 && t < 31.6) yellow.speech = SpeechEvent{Utterance::Protest, Addressee::Partner, 1.0, 2};
    coder.observe(t, purple, yellow);
  }
  coder.finish(60.0);
  const auto label_at = [&](int who, double t) {
    for (const auto& bout : coder.timeline(who, Axis::SocialAttitude)) {
      if (bout.start <= t && t < bout.stop) return static_cast<SocialAttitude>(bout.label);
    }
    return SocialAttitude::Passive;
  };
  EXPECT_EQ(label_at(0, 20.0), SocialAttitude::Passive);
  EXPECT_EQ(label_at(0, 33.0), SocialAttitude::Adversarial);
  EXPECT_EQ(label_at(1, 32.5), SocialAttitude::Frustrated);
  EXPECT_EQ(label_at(0, 50.0), SocialAttitude::Passive);
}

TEST(Coder, AgreementOfTimelines) {
  const ChildTimeline internal = {{Axis::TaskEngagement, 0, 0.0, 10.0}, {Axis::SocialEngagement, 4, 0.0, 10.0}};
  const ChildTimeline coded = {{Axis::SocialEngagement, 4, 0.0, 5.0}, {Axis::SocialEngagement, 2, 5.0, 10.0}};
  EXPECT_DOUBLE_EQ(timeline_agreement(coded, internal, Axis::SocialEngagement, 10.0), 0.5);
  EXPECT_DOUBLE_EQ(timeline_agreement(coded, internal, Axis::TaskEngagement, 10.0), 0.0);  // nothing coded on it
}

// The agreement as a scan of every bout per sample computes it: the first bout in a timeline's order that holds the
// sample's time gives its label.
double agreement_by_scanning(const ChildTimeline& a, const ChildTimeline& b, Axis axis, double end, double step) {
  const auto label_at = [axis](const ChildTimeline& timeline, double t) -> int {
    for (const auto& bout : timeline) {
      if (bout.axis == axis && t >= bout.start && t < bout.stop) return bout.label;
    }
    return -1;
  };
  int same = 0;
  int both = 0;
  for (double t = 0.5 * step; t < end; t += step) {
    const int la = label_at(a, t);
    const int lb = label_at(b, t);
    if (la < 0 || lb < 0) continue;
    ++both;
    if (la == lb) ++same;
  }
  return both > 0 ? static_cast<double>(same) / both : 0.0;
}

TEST(Coder, AgreementEqualsAScanOfEveryBoutOnOverlappingUnsortedTimelines) {
  Rng rng(5);
  const auto random_timeline = [&rng](double end) {
    ChildTimeline timeline;
    const auto bouts = rng.uniform_int(0, 60);
    for (std::int64_t i = 0; i < bouts; ++i) {
      LabelInterval bout;
      bout.axis = static_cast<Axis>(rng.uniform_int(0, 2));
      bout.label = static_cast<std::uint8_t>(rng.uniform_int(0, 4));
      // Overlapping, unsorted, empty, reversed, on sample times, past the end, and now and then NaN or infinite.
      bout.start = rng.uniform() < 0.2 ? std::round(rng.uniform(-5.0, end)) + 0.5 : rng.uniform(-5.0, end);
      bout.stop = bout.start + (rng.uniform() < 0.1 ? -1.0 : rng.uniform(0.0, 0.3 * end));
      if (rng.uniform() < 0.03) bout.start = std::numeric_limits<double>::quiet_NaN();
      if (rng.uniform() < 0.03) bout.stop = std::numeric_limits<double>::infinity();
      timeline.push_back(bout);
    }
    return timeline;
  };
  for (int trial = 0; trial < 300; ++trial) {
    const double end = rng.uniform(0.0, 200.0);
    const double step = trial % 3 == 0 ? 1.0 : rng.uniform(0.05, 3.0);
    const ChildTimeline a = random_timeline(end);
    const ChildTimeline b = random_timeline(end);
    for (const Axis axis : {Axis::TaskEngagement, Axis::SocialEngagement, Axis::SocialAttitude}) {
      EXPECT_EQ(timeline_agreement(a, b, axis, end, step), agreement_by_scanning(a, b, axis, end, step)) << trial;
    }
  }
  EXPECT_THROW(timeline_agreement({}, {}, Axis::TaskEngagement, 10.0, 0.0), InputError);
  EXPECT_THROW(timeline_agreement({}, {}, Axis::TaskEngagement, std::numeric_limits<double>::infinity()), InputError);
}

// An asocial partner (the stand-in of the real `play` node: it never looks at or talks to the child) cannot hold
// the child in associative or cooperative play; what remains is side by side.
TEST(Partnership, UnresponsivePartnerGivesNearZeroJointPlay) {
  const PopulationStats cr = summarise(simulate_population(params(), Condition::ChildRobot, 60, 77), Condition::ChildRobot);
  const auto s = static_cast<std::size_t>(Axis::SocialEngagement);
  EXPECT_LT(cr.labels.share[s][kAssociative] + cr.labels.share[s][kCooperative], 0.06);
  EXPECT_GT(cr.labels.share[s][kParallel], 0.3);
  // The same children with a child partner who answers play together most of the time.
  const PopulationStats cc = summarise(simulate_population(params(), Condition::ChildChild, 60, 77), Condition::ChildChild);
  EXPECT_GT(cc.labels.share[s][kAssociative] + cc.labels.share[s][kCooperative], 0.45);
}

// One mechanism for child and robot partners: a partner that never answers (the asocial stand-in robot) is detected
// as far less contingent than a child partner, and the child's bids to it mostly go unanswered.
TEST(Partnership, AnUnresponsivePartnerIsDetectedAsNonContingent) {
  double robot_c = 0.0, child_c = 0.0, robot_s = 0.0, child_s = 0.0;
  int answered = 0, unanswered = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    SessionConfig config;
    config.condition = Condition::ChildRobot;
    const SessionResult r = simulate_session(params(), config, 500 + seed);
    robot_c += r.purple.counters.contingency_s;
    robot_s += r.duration_s;
    unanswered += r.purple.counters.unanswered_bids;
    answered += r.purple.counters.contingent_responses;
    config.condition = Condition::ChildChild;
    const SessionResult c = simulate_session(params(), config, 500 + seed);
    child_c += c.purple.counters.contingency_s;
    child_s += c.duration_s;
  }
  EXPECT_LT(robot_c / robot_s, 0.5 * child_c / child_s);
  EXPECT_GT(unanswered, 3 * std::max(answered, 1));
}

// §8: one coder, both children: their social labels are coupled within the calibration bands.
TEST(Partnership, DyadIsCodedAsAPair) {
  const PopulationStats cc = summarise(simulate_population(params(), Condition::ChildChild, 100, 31), Condition::ChildChild);
  EXPECT_GE(cc.labels.dyad_same_social, 0.75);
  EXPECT_LE(cc.labels.dyad_same_social, 0.95);
  EXPECT_GE(cc.labels.dyad_cooperative, 0.35);
  EXPECT_LE(cc.labels.dyad_cooperative, 0.60);
}
