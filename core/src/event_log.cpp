#include "freeplay/core/event_log.hpp"

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/rng.hpp"

namespace freeplay {

nlohmann::json Event::to_json() const {
  return nlohmann::json{{"t", t}, {"source", source}, {"type", type}, {"data", data}};
}

std::string EventLog::to_jsonl() const {
  std::string out;
  for (const auto& e : events_) {
    out += e.to_json().dump();
    out += '\n';
  }
  return out;
}

std::uint64_t EventLog::hash() const { return fnv1a64(to_jsonl()); }

void EventLog::write_jsonl(const std::filesystem::path& path) const { write_file_atomically(path, to_jsonl()); }

}  // namespace freeplay
