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
    : recorder_(std::move(recorder)), id_(std::move(id)), log_(log), requested_(on), on_(on) {}

RecorderSwitch::~RecorderSwitch() = default;

void RecorderSwitch::begin(const runner::EpisodeInfo& info) { recorder_->begin({info.scenario, id_, info.seed}); }

void RecorderSwitch::observe(const runner::EpisodeSnapshot& s) {
  const bool want = requested_;
  {
    std::lock_guard lock(mutex_);
    last_t_ = s.t;
  }
  if (want != on_) {
    {
      std::lock_guard lock(mutex_);
      if (want && paused_since_ >= 0.0) paused_s_ += s.t - paused_since_;
      paused_since_ = want ? -1.0 : s.t;
    }
    on_ = want;
    log_.add({s.t, "recorder", want ? "resumed" : "paused", {{"folder", recorder_->paths().dir.string()}}});
  } else if (!on_ && paused_since_ < 0.0) {
    std::lock_guard lock(mutex_);
    paused_since_ = s.t;  // paused from the start
  }
  log_.events_since(cursor_, events_);
  if (!on_) return;
  auto snapshot = s;
  snapshot.new_events = events_;
  recorder_->observe(snapshot);
}

void RecorderSwitch::end(runner::EpisodeResult& result) { recorder_->end(result); }

void RecorderSwitch::abort() { recorder_->abort(); }

void RecorderSwitch::write(const stage::FramePack& frame) {
  if (on_) recorder_->write(frame);
}

void RecorderSwitch::set_gl_renderer(const std::string& renderer) { recorder_->set_gl_renderer(renderer); }

nlohmann::json RecorderSwitch::status() const {
  std::lock_guard lock(mutex_);
  return {{"state", on_ ? "recording" : "paused"},
          {"folder", recorder_->paths().dir.string()},
          {"messages", recorder_->stats().messages},
          {"paused_s", paused_s_ + (paused_since_ >= 0.0 ? last_t_ - paused_since_ : 0.0)}};
}

ObserverSwitch::ObserverSwitch(std::unique_ptr<runner::EpisodeObserver> inner, std::string name, SessionLog& log)
    : inner_(std::move(inner)), name_(std::move(name)), log_(log) {}

void ObserverSwitch::observe(const runner::EpisodeSnapshot& s) {
  const bool want = requested_;
  if (want != on_) {
    on_ = want;
    log_.add({s.t, name_, want ? "resumed" : "paused", nullptr});
  }
  if (on_) inner_->observe(s);
}

}  // namespace freeplay::web
