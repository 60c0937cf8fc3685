#include "freeplay/web/session_log.hpp"

#include <algorithm>

#include "freeplay/core/error.hpp"

namespace freeplay::web {

SessionLog::SessionLog(const std::filesystem::path& path) {
  if (path.empty()) return;
  file_.open(path, std::ios::trunc);
  if (!file_) throw InputError("cannot write the session's event log " + path.string(), "--web-out");
}

void SessionLog::add(Event event) {
  std::lock_guard lock(mutex_);
  if (file_.is_open()) file_ << event.to_json().dump() << '\n' << std::flush;
  all_.push_back(std::move(event));
}

std::vector<Event> SessionLog::take_new() {
  std::lock_guard lock(mutex_);
  std::vector<Event> out(all_.begin() + static_cast<std::ptrdiff_t>(handed_), all_.end());
  handed_ = all_.size();
  return out;
}

void SessionLog::events_since(std::size_t& cursor, std::vector<Event>& out) const {
  std::lock_guard lock(mutex_);
  out.assign(all_.begin() + static_cast<std::ptrdiff_t>(std::min(cursor, all_.size())), all_.end());
  cursor = all_.size();
}

std::vector<Event> SessionLog::all() const {
  std::lock_guard lock(mutex_);
  return all_;
}

}  // namespace freeplay::web
