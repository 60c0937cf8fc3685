#pragma once
// Who decides a web session's robot actions (`--web-mode`, the page's `mode` command, the session log), with its one
// name/value pair: header-only, so that the command line lists the names without the web session's headers.

#include <string>
#include <string_view>
#include <vector>

#include "freeplay/core/enum_names.hpp"

namespace freeplay::web {

/// Who decides the robot's actions.
enum class RobotMode { Autonomous, Wizard, Supervised };

/// The name the command line, the page and the session log use for a mode ("autonomous", "wizard", "supervised").
constexpr std::string_view to_string(RobotMode mode) {
  switch (mode) {
    case RobotMode::Autonomous: return "autonomous";
    case RobotMode::Wizard: return "wizard";
    case RobotMode::Supervised: return "supervised";
  }
  return "wizard";
}

/// Sets `mode` to the mode named `text`; false (and `mode` unchanged) when `text` names none.
constexpr bool from_string(std::string_view text, RobotMode& mode) {
  return enum_from_string(text, {RobotMode::Autonomous, RobotMode::Wizard, RobotMode::Supervised}, mode);
}

/// The names of every mode, in the order the command line and the page list them.
inline std::vector<std::string> robot_mode_names() {
  return enum_names({RobotMode::Autonomous, RobotMode::Wizard, RobotMode::Supervised});
}

}  // namespace freeplay::web
