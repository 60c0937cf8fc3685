#include <gtest/gtest.h>

#include "freeplay/agents/calibration.hpp"
#include "freeplay/core/error.hpp"

using namespace freeplay::agents;

namespace {
const ChildModelParams& params() {
  static const ChildModelParams p = default_child_model_params();
  return p;
}
}  // namespace

// The logic-only simulator is what the fit runs on: its fixed-seed population of 200 sessions per condition meets
// the bands of what the fit matches (child-child label shares, bout medians, dyadic coupling). Durations and
// transitions are held by the full-episode gate (`freeplay calibrate --full --check` in CI), the product itself.
TEST(Calibration, ShippedParametersMeetTheTargets) {
  const PopulationStats cc = summarise(simulate_population(params(), Condition::ChildChild, 200, 42), Condition::ChildChild);
  const PopulationStats cr = summarise(simulate_population(params(), Condition::ChildRobot, 200, 42), Condition::ChildRobot);
  const auto rows = compare_with_targets(&cc, &cr);
  int checked = 0;
  for (const ComparisonRow& row : rows) {
    const bool fitted = row.group.find("share") != std::string::npos || row.group.find("bout median") != std::string::npos ||
                        row.group.find("dyad") != std::string::npos;
    if (!fitted || !row.checked) continue;
    ++checked;
    EXPECT_TRUE(row.within()) << row.group << " / " << row.name << ": simulated " << row.simulated << ", bound ["
                              << row.lo << ", " << row.hi << "]";
  }
  EXPECT_GE(checked, 30);
  // The asocial partner shortens sessions through the child's reactions, with the same parameters.
  EXPECT_LT(cr.duration.mean_min, cc.duration.mean_min);
}

TEST(Calibration, StatisticsOfAKnownPopulation) {
  std::vector<SessionResult> sessions(4);
  for (int i = 0; i < 4; ++i) {
    sessions[static_cast<std::size_t>(i)].duration_s = 60.0 * (10 * (i + 1));
    sessions[static_cast<std::size_t>(i)].purple.timeline = {{Axis::TaskEngagement, 0, 0.0, 30.0},
                                                             {Axis::TaskEngagement, 3, 30.0, 40.0}};
  }
  const PopulationStats s = summarise(sessions, Condition::ChildRobot);
  EXPECT_DOUBLE_EQ(s.duration.mean_min, 25.0);
  EXPECT_DOUBLE_EQ(s.duration.median_min, 25.0);
  EXPECT_DOUBLE_EQ(s.duration.survival[1], 1.0);
  EXPECT_DOUBLE_EQ(s.duration.survival[2], 0.75);
  EXPECT_DOUBLE_EQ(s.duration.survival[3], 0.5);
  EXPECT_DOUBLE_EQ(s.labels.share[0][0], 0.75);
  EXPECT_DOUBLE_EQ(s.labels.bout_median_s[0][3], 10.0);
}

// `freeplay calibrate --fit --full --fit-only …`: the fit moves only the named parameters and evaluates every trial
// through the simulation it is given (the full episode loop plugs in there); an unknown name is refused.
TEST(Calibration, FitMovesOnlyTheNamedParametersThroughTheGivenSimulation) {
  FitOptions options;
  options.rounds = 1;
  options.only = {"drives.decay_per_min"};
  int evaluations = 0;
  options.simulate = [&evaluations](const ChildModelParams& p) {
    ++evaluations;
    return std::pair{summarise(simulate_population(p, Condition::ChildChild, 6, 7), Condition::ChildChild),
                     summarise(simulate_population(p, Condition::ChildRobot, 6, 7), Condition::ChildRobot)};
  };
  const FitResult result = fit_child_model(params(), options);
  EXPECT_GE(evaluations, 2);  // the start and at least one trial step
  EXPECT_LE(evaluations, 3);  // one parameter: the start, one step up, one step down
  ChildModelParams expected = params();
  expected.drives.decay_per_min = result.params.drives.decay_per_min;
  EXPECT_EQ(child_model_params_to_yaml(result.params, ""), child_model_params_to_yaml(expected, ""));

  options.only = {"drives.no_such_parameter"};
  EXPECT_THROW(fit_child_model(params(), options), freeplay::InputError);
}
