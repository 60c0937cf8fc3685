#pragma once
// The event stream of an episode: what happened, when (simulated time), emitted by which component.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "freeplay/core/events.hpp"
#include "freeplay/core/rng.hpp"

namespace freeplay {

/// One event: simulated time, emitting component and what happened, typed (events.hpp: its type, e.g.
/// `interaction_event`, and its fields).
struct Event {
  double t = 0.0;                 ///< simulated seconds since the episode started
  std::string source;             ///< e.g. "sandtray", "child.purple", "robot"
  events::EventPayload payload;   ///< what happened

  /// An empty event (an `other` event with no type).
  Event() : payload(events::Other{}) {}
  /// An event carrying `payload`.
  Event(double at, std::string from, events::EventPayload what)
      : t(at), source(std::move(from)), payload(std::move(what)) {}
  /// An event of `type` with `data`, typed when its type and data are one of events.hpp's (events::payload_of).
  Event(double at, std::string from, std::string_view type, nlohmann::json data)
      : t(at), source(std::move(from)), payload(events::payload_of(type, std::move(data))) {}

  /// Its type, e.g. "item_grabbed".
  std::string_view type() const { return events::type_of(payload); }
  /// Its fields as the event log writes them (object or null).
  nlohmann::json data() const { return events::data_of(payload); }
  /// Its payload if it is a `T` (e.g. events::InteractionEvent), else null.
  template <class T>
  const T* get() const {
    return std::get_if<T>(&payload);
  }
  /// The event as one JSON object {t, source, type, data}.
  nlohmann::json to_json() const;
};

/// An append-only, ordered list of events with a stable content hash. Each event is serialised once, when it is
/// appended: the JSON Lines text and its hash grow with the log instead of being rebuilt from it.
class EventLog {
 public:
  /// Appends one event.
  void emit(Event event);
  /// Appends every event of `more`, in order.
  void append(const std::vector<Event>& more);
  /// All events in emission order.
  const std::vector<Event>& events() const { return events_; }
  /// Number of events.
  std::size_t size() const { return events_.size(); }
  /// The log as JSON Lines (one compact `Event::to_json()` object per line).
  const std::string& to_jsonl() const { return jsonl_; }
  /// FNV-1a hash of `to_jsonl()`: equal logs give equal hashes on the same machine.
  std::uint64_t hash() const { return hash_; }
  /// Writes `to_jsonl()` atomically to `path`.
  void write_jsonl(const std::filesystem::path& path) const;

 private:
  std::vector<Event> events_;
  std::string jsonl_;                             // to_jsonl(), one line per event of events_
  std::uint64_t hash_ = fnv1a64(std::string_view{});  // FNV-1a of jsonl_, extended line by line
};

}  // namespace freeplay
