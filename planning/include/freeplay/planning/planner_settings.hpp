#pragma once
// The planner's user-facing settings (a scenario's `planner:` block), declared once by the library that uses them:
// the defaults every front starts from (`PlanRequest`, `PlannerOptions`, `MoveExecutorConfig`, the command-line
// flags) and `visit`, which lists the keys, ranges and help (core/settings_archive.hpp).

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/core/settings_archive.hpp"

namespace freeplay::planning {

/// The names `make_planner` (plan.hpp) builds, in the order scenarios list them: header-only, so that the scenario
/// parser accepts exactly these without linking the planners.
inline constexpr std::array<std::string_view, 5> kPlannerNames = {"astar", "rrtconnect", "prmstar", "rrtstar",
                                                                  "bitstar"};

/// Default planning budget (s): wall clock, only anytime planners use it up.
inline constexpr double kDefaultTimeBudgetS = 1.0;
/// Default robot finger speed (m/s): 5 mm per 0.1 s, as the real system.
inline constexpr double kDefaultFingerSpeedMps = 0.05;

/// `planner:` the motion planner of the robot's item moves.
struct PlannerSettings {
  std::string name = "astar";          ///< motion planner
  double time_budget_s = kDefaultTimeBudgetS;        ///< wall-clock planning budget (anytime planners use it up)
  double finger_speed_mps = kDefaultFingerSpeedMps;  ///< robot finger speed (5 mm per 0.1 s)
  bool reject_blocked_goals = false;   ///< refuse goals inside other footprints (the real planner does not)

  /// The keys of `planner:` (`planner_names`: the names `name` accepts).
  template <typename Archive>
  void visit(Archive& a, const std::vector<std::string>& planner_names) {
    a.field("name", name, Schema::enumeration(planner_names));
    a.field("time_budget_s", time_budget_s, Schema::number(0.001, 60.0),
            "wall-clock budget; only anytime planners (rrtstar, bitstar) use it up: keep it large so that "
            "deterministic planners never hit it on a slow machine");
    a.field("finger_speed_mps", finger_speed_mps, Schema::number(0.005, 1.0), "5 mm per 0.1 s in the real system");
    a.field("reject_blocked_goals", reject_blocked_goals, Schema::boolean(),
            "refuse a goal whose cell lies inside other items' footprints; the real planner plans to any point (the "
            "item then lands on the others and the physics pushes them apart)");
  }
};

}  // namespace freeplay::planning
