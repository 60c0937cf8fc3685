#pragma once
// The event stream of an episode: what happened, when (simulated time), emitted by which component.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace freeplay {

/// One event: simulated time, emitting component, type (e.g. `releasing_zebra`) and free-form data.
struct Event {
  double t = 0.0;            ///< simulated seconds since the episode started
  std::string source;        ///< e.g. "sandtray", "child.purple", "robot"
  std::string type;          ///< e.g. "item_grabbed", "interaction_event", "stroke_finished"
  nlohmann::json data;       ///< event-specific fields (object or null)

  /// The event as one JSON object {t, source, type, data}.
  nlohmann::json to_json() const;
};

/// An append-only, ordered list of events with a stable content hash.
class EventLog {
 public:
  /// Appends one event.
  void emit(Event event) { events_.push_back(std::move(event)); }
  /// Appends every event of `more`, in order.
  void append(const std::vector<Event>& more) { events_.insert(events_.end(), more.begin(), more.end()); }
  /// All events in emission order.
  const std::vector<Event>& events() const { return events_; }
  /// Number of events.
  std::size_t size() const { return events_.size(); }
  /// The log as JSON Lines (one compact object per line).
  std::string to_jsonl() const;
  /// FNV-1a hash of `to_jsonl()`: equal logs give equal hashes on the same machine.
  std::uint64_t hash() const;
  /// Writes `to_jsonl()` atomically to `path`.
  void write_jsonl(const std::filesystem::path& path) const;

 private:
  std::vector<Event> events_;
};

}  // namespace freeplay
