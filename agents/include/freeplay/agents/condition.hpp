#pragma once
// Who plays (`condition:` in scenarios, `condition` in run records), with its one name/value pair and its PInSoRo
// spelling: header-only, so that a scenario parser reads it without linking the agents. The runner's scenarios use
// this enum as `scenario::Condition`.

#include <cstdint>
#include <string_view>

#include "freeplay/core/enum_names.hpp"

namespace freeplay::agents {

/// Who plays with the purple child.
enum class Condition : std::uint8_t {
  ChildChild,  ///< two children ("child-child")
  ChildRobot,  ///< a child and the robot in the yellow place ("child-robot")
  Controller,  ///< the Nao alone on the child-robot stage, no child (scenarios of kind controller; "controller")
};

/// The name scenarios and run records use for a condition ("child-child", "child-robot", "controller").
constexpr std::string_view to_string(Condition condition) {
  switch (condition) {
    case Condition::ChildChild: return "child-child";
    case Condition::ChildRobot: return "child-robot";
    case Condition::Controller: return "controller";
  }
  return "unknown";
}

/// Sets `condition` to the condition named `text`; false (and `condition` unchanged) when `text` names none.
constexpr bool from_string(std::string_view text, Condition& condition) {
  return enum_from_string(text, {Condition::ChildChild, Condition::ChildRobot, Condition::Controller}, condition);
}

/// The PInSoRo dataset's spelling of a condition in session files ("childrobot", otherwise "childchild").
constexpr std::string_view pinsoro_name(Condition condition) {
  return condition == Condition::ChildRobot ? "childrobot" : "childchild";
}

/// Sets `condition` to the one spelled `text` in PInSoRo's session files ("childchild", "childrobot"); false (and
/// `condition` unchanged) when `text` is neither.
constexpr bool from_pinsoro_name(std::string_view text, Condition& condition) {
  for (const Condition candidate : {Condition::ChildChild, Condition::ChildRobot}) {
    if (text == pinsoro_name(candidate)) {
      condition = candidate;
      return true;
    }
  }
  return false;
}

}  // namespace freeplay::agents
