#pragma once
// An optional replacement for the synthetic children of an episode: something else (a recorded session) says what
// each child does at every free-play tick, and the episode applies it exactly as it applies the agents' actions.

#include <string>

#include "freeplay/agents/perception.hpp"

namespace freeplay::runner {

/// Supplies the children's actions of an episode instead of `agents::ChildAgent::step` (e.g. replayed from a bag).
class ChildActionSource {
 public:
  virtual ~ChildActionSource() = default;
  /// What the child in `seat` ("purple" | "yellow") does during the free-play tick that starts at `t` (s since free
  /// play started) and lasts `dt`; free play ends once every child's actions have `quit` set (or at the cap).
  virtual agents::ChildActions actions(const std::string& seat, double t, double dt) = 0;
};

}  // namespace freeplay::runner
