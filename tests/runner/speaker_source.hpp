#pragma once
// A robot action source for the runner tests: an external robot that only speaks, once, at free-play second 2.

#include <string>
#include <utility>

#include "freeplay/runner/robot_action_source.hpp"

namespace freeplay::runner::test {

/// Says `text` to `to` at the first free-play tick at or after second 2, and does nothing else.
class Speaker final : public RobotActionSource {
 public:
  /// Speaks `text` to `to` ("" = everyone).
  Speaker(std::string text, std::string to) : text_(std::move(text)), to_(std::move(to)) {}
  /// The utterance at the first tick at or after second 2, nothing otherwise.
  RobotCommands commands(double t, const sim::Sandtray& /*tray*/, const ReachDisc& /*reach*/) override {
    RobotCommands out;
    if (!said_ && t >= 2.0 - 1e-9) {
      said_ = true;
      out.say.push_back({text_, to_});
    }
    return out;
  }

 private:
  std::string text_;
  std::string to_;
  bool said_ = false;
};

}  // namespace freeplay::runner::test
