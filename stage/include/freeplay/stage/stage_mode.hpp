#pragma once
// How the stage moves, with its one name/value pair: header-only, so that the scenario parser reads `robot.mode` and
// `controller.mode` into this enum without linking the stage.

#include <string_view>

#include "freeplay/core/enum_names.hpp"

namespace freeplay::stage {

/// How the stage moves: joint angles written directly (kinematic) or position actuators simulated (dynamic).
enum class StageMode { kinematic, dynamic };

/// The name scenarios and run records use for `mode` ("kinematic", "dynamic").
constexpr std::string_view to_string(StageMode mode) {
  return mode == StageMode::dynamic ? "dynamic" : "kinematic";
}

/// Sets `mode` to the mode named `text`; false (and `mode` unchanged) when `text` names none.
constexpr bool from_string(std::string_view text, StageMode& mode) {
  return enum_from_string(text, {StageMode::kinematic, StageMode::dynamic}, mode);
}

}  // namespace freeplay::stage
