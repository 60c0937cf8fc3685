#pragma once
// The PInSoRo session metadata file `experiment.yaml` (free-play-sandbox.md §4.3).

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/agents/annotations.hpp"
#include "freeplay/agents/condition.hpp"

namespace freeplay::recording {

/// One child of a session as `experiment.yaml` describes it.
struct Participant {
  std::string id;                          ///< e.g. `<session>-p1`
  int age = 0;                             ///< years
  std::string gender;                      ///< "male" | "female"
  std::string tablet_familiarity = "na";   ///< "0" | "1" | "2" | "na"
};

/// The content of `experiment.yaml`.
struct ExperimentInfo {
  std::string header;                        ///< comment line (the real files: the date)
  std::uint64_t timestamp_ns = 0;            ///< ROS time of the start of free play (ns)
  agents::Condition condition = agents::Condition::ChildChild;  ///< written in PInSoRo's spelling (pinsoro_name)
  std::optional<Participant> purple;         ///< the purple child
  std::optional<Participant> yellow;         ///< the yellow child (absent in child-robot sessions)
  std::map<double, std::string> markers;     ///< seconds since free play started → interesting|issue|note|screenshot
  std::map<std::string, std::string> notes;  ///< `general` and `<seconds>` → text
  std::vector<std::string> issues;           ///< problems (an interrupted recording says so here)
  std::optional<int> social_engagement;      ///< `extras: {social-engagement: 1..5}` (end-of-session Likert)
};

/// The end-of-session social-engagement Likert (1..5) of a session's annotations: 1 + 4 × the children's mean share
/// of labelled time in the social labels `associative` and `cooperative`, rounded (nullopt without annotations).
std::optional<int> social_engagement_likert(const agents::SessionAnnotations& annotations);

/// `experiment.yaml` text in the PInSoRo layout.
std::string to_experiment_yaml(const ExperimentInfo& info);

}  // namespace freeplay::recording
