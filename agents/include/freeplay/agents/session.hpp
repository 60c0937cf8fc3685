#pragma once
// Logic-only session simulator: children (and the asocial stand-in robot) on a kinematic stand-in tray.
//
// No physics: a dragged item follows its finger; strokes only count (fills add a zone of their colour). It exists
// for calibration, tests and benchmarks; the real episode loop feeds the Box2D sandtray instead, with the same
// agents and the same ending rule (a child that wants to stop ends the session; see SessionEnd).

#include <array>
#include <cstdint>
#include <optional>

#include "freeplay/agents/child_agent.hpp"
#include "freeplay/agents/coder.hpp"
#include "freeplay/agents/condition.hpp"
#include "freeplay/agents/params.hpp"
#include "freeplay/agents/profile.hpp"

namespace freeplay::agents {

/// Settings of one simulated session.
struct SessionConfig {
  Condition condition = Condition::ChildChild;        ///< partner of the purple child (any but ChildChild: the robot)
  double tick_s = 0.1;                                 ///< the game's 10 Hz tick
  std::optional<ChildProfile> purple_profile;          ///< fixed purple profile (sampled when empty)
  std::optional<ChildProfile> yellow_profile;          ///< fixed yellow profile (child-child only)
  std::optional<Population> population;                ///< demographics (PInSoRo CC or CR by condition when empty)
  bool robot_takes_items = true;                       ///< the stand-in robot may grab items a child placed
};

/// What one child did in a session.
struct ChildOutcome {
  ChildProfile profile;          ///< who it was
  ChildTimeline timeline;        ///< ground truth as the coder labels it: the three axes coded from behaviour
  ChildTimeline internal;        ///< the child's own state (intentions) over the whole session
  double quit_time_s = -1.0;     ///< when it decided to stop (negative: never)
  ChildCounters counters;        ///< behaviour counts
};

/// Result of one simulated session.
struct SessionResult {
  double duration_s = 0.0;                 ///< session length
  bool hit_cap = false;                    ///< stopped by the 40-minute cap
  ChildOutcome purple;                     ///< the purple child
  std::optional<ChildOutcome> yellow;      ///< the yellow child (child-child only)
  int robot_moves = 0;                     ///< stand-in robot moves (child-robot only)
};

/// Runs one session with root seed `seed` (streams: profile.purple, profile.yellow, child.purple, child.yellow, robot).
///
/// Ending rule: a child-robot session ends when the child wants to stop; a child-child session ends when both
/// children want to stop (a child that sees its partner announce it wants to stop has its quit hazard multiplied
/// by `drives.partner_quit_factor`, so the second usually follows within seconds); both end at the cap.
SessionResult simulate_session(const ChildModelParams& params, const SessionConfig& config, std::uint64_t seed);

}  // namespace freeplay::agents
