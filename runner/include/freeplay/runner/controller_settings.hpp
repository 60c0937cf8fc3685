#pragma once
// The settings of a controller scenario (`controller:`) that the controller episodes read (controller_episode.hpp):
// the Nao's mode and gains and its target sequence. Header-only (freeplay_runner_headers), so that the parse-only
// scenario parser reads them without linking the runner. Member initialisers are the defaults; `visit` lists the keys,
// ranges and help (core/settings_archive.hpp); the parser builds the `targets` schema and list itself, since the
// targets name items and postures it takes from their owners.

#include <optional>
#include <string>
#include <vector>

#include "freeplay/core/settings_archive.hpp"
#include "freeplay/stage/stage_mode.hpp"

namespace freeplay::runner {

/// One step of a controller scenario's target sequence.
struct ControllerTarget {
  /// What the step asks of the Nao.
  enum class Kind { Point, Look, Move, Posture, Wait, RandomPoints };
  Kind kind = Kind::Wait;                   ///< the step's kind
  std::vector<double> point;                ///< Point: screen x, y (m); Look: x, y, z (m); Move: target x, y
  std::string item;                         ///< Move: the item to drag
  std::optional<std::vector<double>> from;  ///< Move: where the item is placed first (nullopt: where it is)
  std::string posture;                      ///< Posture: NAOqi posture name
  double seconds = 0.0;                     ///< Wait: how long to hold still (s)
  int count = 0;                            ///< RandomPoints: how many points
  std::string region;                       ///< RandomPoints: "reach" or "screen"
};

/// The `controller:` section of a scenario of kind `controller`.
struct ControllerSpec {
  stage::StageMode mode = stage::StageMode::dynamic;  ///< dynamic (simulated actuators) or kinematic
  double speed_fraction = 0.3;              ///< joint speed of the commanded profile, as a fraction of each joint's
                                            ///< velocity limit (ALMotion's angleInterpolationWithSpeed fraction)
  double torque_fraction = 0.5;             ///< and no faster than this fraction of each joint's effort limit can
                                            ///< drive against the joint's damping
  int trace_interval_steps = 50;            ///< golden-trace checkpoint every N physics steps (2 ms each)
  double settle_tolerance_m = 0.003;        ///< fingertip distance to its commanded position that counts as settled
  double settle_tolerance_rad = 0.01;       ///< joint error that counts as settled (look and posture targets)
  double settle_speed_rad_s = 0.05;         ///< joint speeds below which the robot counts as still
  double hold_s = 0.2;                      ///< time held at each target once settled
  double timeout_s = 5.0;                   ///< longest time spent on one target
  std::vector<ControllerTarget> targets;    ///< the sequence, in order (its own schema: `targets`)

  /// The keys of `controller:` besides `targets`.
  template <typename Archive>
  void visit(Archive& a) {
    a.field("mode", mode, Schema::enumeration(enum_names({stage::StageMode::dynamic, stage::StageMode::kinematic})),
            "robot simulation mode");
    a.field("speed_fraction", speed_fraction, Schema::number(0.01, 50.0),
            "joint speed of the commanded profile as a fraction of the Nao's velocity limits (> 1 exceeds them "
            "deliberately)");
    a.field("torque_fraction", torque_fraction, Schema::number(0.01, 50.0),
            "profile speed at most this fraction of each joint's effort limit / its damping (> 1 exceeds the "
            "motors' efforts deliberately)");
    a.field("trace_interval_steps", trace_interval_steps, Schema::integer(1, 1000000),
            "golden-trace checkpoint every N steps");
    a.field("settle_tolerance_m", settle_tolerance_m, Schema::number(1e-5, 0.1));
    a.field("settle_tolerance_rad", settle_tolerance_rad, Schema::number(1e-5, 1.0));
    a.field("settle_speed_rad_s", settle_speed_rad_s, Schema::number(1e-4, 10.0));
    a.field("hold_s", hold_s, Schema::number(0.0, 60.0), "time held at a target once settled");
    a.field("timeout_s", timeout_s, Schema::number(0.1, 600.0), "longest time spent on one target");
  }
};

}  // namespace freeplay::runner
