#pragma once
// Reads a recorded session back (with rosbag_storage only) and recomputes the episode's metrics from it: the
// event log of /freeplay/events, the item poses of /tf, the zones of /zones and the annotations.

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "freeplay/core/event_log.hpp"
#include "freeplay/core/geometry.hpp"

namespace freeplay::recording {

/// One event as recorded: the event and the 10 Hz tick (sandtray time) at which the observers saw it.
struct RecordedEvent {
  double tick = 0.0;  ///< sandtray time of the snapshot that carried it
  Event event;        ///< the event-log entry
};

/// A colour zone as /zones carries it.
struct RecordedZone {
  std::string colour;  ///< from the marker namespace `sandbox_zone_<colour>`
  Polygon2 polygon;    ///< open polygon (sandtray frame)
  double area_m2 = 0;  ///< |signed area|
};

/// Everything replay needs from one session's bag.
struct SessionRecording {
  std::filesystem::path bag;                                   ///< the bag read
  std::map<std::string, std::size_t> topic_counts;             ///< messages per topic
  std::map<std::string, std::string> topic_types;              ///< message type per topic
  double start_s = 0.0;                                        ///< first message (sandtray time)
  double end_s = 0.0;                                          ///< last message (sandtray time)
  std::vector<RecordedEvent> events;                           ///< /freeplay/events in order
  std::map<long, std::map<std::string, Vec2>> item_positions;  ///< game /tf per tick index (publication_tick): item → position
  std::vector<std::pair<double, std::vector<RecordedZone>>> zones;  ///< /zones messages in time order (their tick's time)
  std::string annotations_yaml;                                ///< /freeplay/annotations (empty when interrupted)
  std::vector<std::string> interaction_events;                 ///< /sandtray/interaction_events in order
  std::vector<std::pair<double, std::vector<std::uint8_t>>> backgrounds;  ///< background PNGs in time order (their tick's time)
};

/// Reads `path` (a session folder or a bag file; `freeplay.bag`, else `freeplay.bag.active`); InputError when no
/// readable bag is there (an unindexed bag: the message says to run `rosbag reindex`).
SessionRecording read_session(const std::filesystem::path& path);

/// Recomputes every metric of an episode record from its recording (events, item poses, zones, backgrounds and
/// annotations), with the names and arithmetic of episodes.jsonl: {"duration_s", "metrics": {...}, "extra": {...}}.
nlohmann::json recompute_metrics(const SessionRecording& recording);

/// One metric compared with the episode record.
struct MetricComparison {
  std::string name;        ///< dotted path, e.g. "child.purple.touches_per_min"
  double replayed = 0.0;   ///< from the bag
  double recorded = 0.0;   ///< from episodes.jsonl (NaN when absent)
  bool equal = false;      ///< identical values (both NaN counts as equal)
};

/// Compares every recomputed metric (and duration_s) with the same names in an episodes.jsonl record; a metric of
/// the record that was not recomputed is listed too, as not equal (NaN replayed).
std::vector<MetricComparison> compare_with_record(const nlohmann::json& recomputed, const nlohmann::json& record);

/// The `metrics` of a record (or of recompute_metrics) as dotted names ("metrics.zone_transitions"), NaN for nulls.
std::map<std::string, double> metric_values(const nlohmann::json& record);

}  // namespace freeplay::recording
