#pragma once
// The event log of a web session: the episode's events as they happen plus every wizard, supervision and
// experiment-manager action, in arrival order, appended to `events.jsonl` and handed to the next state frame.

#include <filesystem>
#include <fstream>
#include <mutex>
#include <vector>

#include "freeplay/core/event_log.hpp"

namespace freeplay::web {

/// Thread-safe append-only event log of one web session.
class SessionLog {
 public:
  /// Appends to `path` (created, truncated); an empty path keeps the log in memory only.
  explicit SessionLog(const std::filesystem::path& path = {});
  /// Adds one event (any thread).
  void add(Event event);
  /// The events added since the previous call (for the next state frame).
  std::vector<Event> take_new();
  /// Replaces `out` with the events after position `cursor` and moves `cursor` to the end (a reader of its own).
  void events_since(std::size_t& cursor, std::vector<Event>& out) const;
  /// Every event so far.
  std::vector<Event> all() const;

 private:
  mutable std::mutex mutex_;
  std::ofstream file_;
  std::vector<Event> all_;
  std::size_t handed_ = 0;
};

}  // namespace freeplay::web
