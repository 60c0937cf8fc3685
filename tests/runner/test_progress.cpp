// The suite's progress line.
#include <gtest/gtest.h>

#include "freeplay/runner/progress.hpp"

using namespace freeplay::runner;

TEST(Progress, LineCountsEpisodesAndSimulatedHours) {
  ProgressReporter progress(4, false);
  progress.episode_done(1800.0);
  progress.episode_done(1800.0);
  const auto line = progress.line();
  EXPECT_NE(line.find("2/4 episodes"), std::string::npos) << line;
  EXPECT_NE(line.find("1.0 simulated h"), std::string::npos) << line;
}
