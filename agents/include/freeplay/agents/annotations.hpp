#pragma once
// Ground-truth state timelines in the PInSoRo annotation format (free-play-sandbox.md §4.3).
//
// File layout: a header comment line, then `purple:` / `yellow:` lists of single-key maps `- <label>: [start, stop]`,
// the three axes interleaved in one list sorted by start time. The real files use ROS epoch seconds (bag time
// base); synthetic files use episode seconds plus a configurable `time_base` (0 by default).

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/agents/labels.hpp"

namespace freeplay::agents {

/// One annotated bout: a label held on one axis from `start` to `stop` (seconds).
struct LabelInterval {
  Axis axis = Axis::TaskEngagement;  ///< which axis
  std::uint8_t label = 0;            ///< label index on that axis
  double start = 0.0;                ///< seconds
  double stop = 0.0;                 ///< seconds (≥ start)

  /// The exact label string.
  std::string_view name() const { return label_name(axis, label); }
};

/// One child's annotation: every bout of the three axes.
using ChildTimeline = std::vector<LabelInterval>;

/// The two children's annotations of one session (yellow is empty in child-robot sessions).
struct SessionAnnotations {
  std::optional<ChildTimeline> purple;  ///< the purple child's bouts
  std::optional<ChildTimeline> yellow;  ///< the yellow child's bouts (absent when the robot plays yellow)
};

/// PInSoRo YAML text of `annotations`; times are written as `time_base + t`; `header` becomes the comment line.
std::string to_pinsoro_yaml(const SessionAnnotations& annotations, double time_base = 0.0,
                            std::string_view header = "Annotations made by freeplay-sim (synthetic ground truth)");
/// Parses PInSoRo annotation YAML (times minus `time_base`); InputError with file:line:column on bad input.
SessionAnnotations parse_pinsoro_yaml(std::string_view yaml_text, const std::string& file = "<string>",
                                      double time_base = 0.0);

/// Share of the labelled time of `axis` spent in each label (zeros when nothing is labelled).
std::array<double, kMaxLabels> label_shares(const ChildTimeline& timeline, Axis axis);

}  // namespace freeplay::agents
