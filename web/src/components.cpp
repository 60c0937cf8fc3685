#include "freeplay/web/components.hpp"

#include "freeplay/recording/bag_recorder.hpp"

namespace freeplay::web {

void WebSignals::push(sim::Signal signal) {
  std::lock_guard lock(mutex_);
  queue_.push_back(signal);
}

std::vector<sim::Signal> WebSignals::take() {
  std::vector<sim::Signal> out;
  {
    std::lock_guard lock(mutex_);
    out.swap(queue_);
  }
  if (also_ != nullptr) {
    for (const auto s : also_->take()) out.push_back(s);
  }
  return out;
}

RecorderSwitch::RecorderSwitch(std::unique_ptr<recording::BagRecorder> recorder, std::string id, bool on,
                               SessionLog& log)
    : recorder_(std::move(recorder)),
      id_(std::move(id)),
      log_(log),
      gate_(*recorder_, on, [this](double t, bool now_on) {
        log_.add({t, "recorder", now_on ? "resumed" : "paused", {{"folder", recorder_->paths().dir.string()}}});
      }) {}

RecorderSwitch::~RecorderSwitch() = default;

void RecorderSwitch::begin(const runner::EpisodeInfo& info) { recorder_->begin({info.scenario, id_, info.seed}); }

void RecorderSwitch::observe(const runner::EpisodeSnapshot& s) {
  const bool on = gate_.apply(s.t);  // first: a resume's event is in the tick it takes effect at
  log_.events_since(cursor_, events_);
  if (!on) return;
  auto snapshot = s;
  snapshot.new_events = events_;
  gate_.observe(snapshot);
}

void RecorderSwitch::end(runner::EpisodeResult& result) { recorder_->end(result); }

void RecorderSwitch::abort() { recorder_->abort(); }

void RecorderSwitch::write(const stage::FramePack& frame) {
  if (gate_.on()) recorder_->write(frame);
}

void RecorderSwitch::set_gl_renderer(const std::string& renderer) { recorder_->set_gl_renderer(renderer); }

nlohmann::json RecorderSwitch::status() const {
  return {{"state", gate_.on() ? "recording" : "paused"},
          {"folder", recorder_->paths().dir.string()},
          {"messages", recorder_->stats().messages},
          {"paused_s", gate_.off_s()}};
}

}  // namespace freeplay::web
