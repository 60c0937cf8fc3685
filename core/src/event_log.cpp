#include "freeplay/core/event_log.hpp"

#include <algorithm>
#include <string_view>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/rng.hpp"

namespace freeplay {

nlohmann::json Event::to_json() const {
  return nlohmann::json{{"t", t}, {"source", source}, {"type", type()}, {"data", data()}};
}

namespace {

/// True when nlohmann's serializer writes `text` as it is between quotes (printable ASCII, no quote, no backslash).
bool needs_no_escape(std::string_view text) {
  return std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c <= 0x7E && c != '"' && c != '\\'; });
}

/// Appends `event.to_json().dump()` to `out` without building the object: nlohmann keeps an object's keys sorted
/// (data, source, t, type), and each value is written by its serializer, or verbatim when that is what it writes.
void append_event_json(std::string& out, const Event& event) {
  nlohmann::detail::serializer<nlohmann::json> serializer(nlohmann::detail::output_adapter<char>(out), ' ');
  const auto append_string = [&](std::string_view text) {
    if (needs_no_escape(text)) {
      out += '"';
      out += text;
      out += '"';
    } else {
      serializer.dump(nlohmann::json(text), false, false, 0);
    }
  };
  out += R"({"data":)";
  if (const auto* other = event.get<events::Other>()) {
    serializer.dump(other->data, false, false, 0);  // kept as it came: written without a copy
  } else {
    serializer.dump(event.data(), false, false, 0);
  }
  out += R"(,"source":)";
  append_string(event.source);
  out += R"(,"t":)";
  serializer.dump(nlohmann::json(event.t), false, false, 0);
  out += R"(,"type":)";
  append_string(event.type());
  out += '}';
}

}  // namespace

void EventLog::emit(Event event) {
  const std::size_t start = jsonl_.size();
  append_event_json(jsonl_, event);
  jsonl_ += '\n';
  hash_ = fnv1a64(std::string_view(jsonl_).substr(start), hash_);
  events_.push_back(std::move(event));
}

void EventLog::append(const std::vector<Event>& more) {
  for (const auto& e : more) emit(e);
}

void EventLog::write_jsonl(const std::filesystem::path& path) const { write_file_atomically(path, to_jsonl()); }

}  // namespace freeplay
