#include "freeplay/core/event_log.hpp"

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/rng.hpp"

namespace freeplay {

nlohmann::json Event::to_json() const {
  return nlohmann::json{{"t", t}, {"source", source}, {"type", type}, {"data", data}};
}

void EventLog::emit(Event event) {
  // The line is `event.to_json().dump()`; the data is moved into the object and back instead of being copied.
  nlohmann::json line{{"t", event.t}, {"source", event.source}, {"type", event.type}, {"data", std::move(event.data)}};
  const std::size_t start = jsonl_.size();
  jsonl_ += line.dump();
  jsonl_ += '\n';
  hash_ = fnv1a64(std::string_view(jsonl_).substr(start), hash_);
  event.data = std::move(line["data"]);
  events_.push_back(std::move(event));
}

void EventLog::append(const std::vector<Event>& more) {
  for (const auto& e : more) emit(e);
}

void EventLog::write_jsonl(const std::filesystem::path& path) const { write_file_atomically(path, to_jsonl()); }

}  // namespace freeplay
