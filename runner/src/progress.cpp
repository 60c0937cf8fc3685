#include "freeplay/runner/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace freeplay::runner {

ProgressReporter::ProgressReporter(int total, bool enabled)
    : total_(total), enabled_(enabled), tty_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

std::string ProgressReporter::line() const {
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const int width = 24;
  const int filled = total_ > 0 ? done_ * width / total_ : width;
  const double speed = wall > 0 ? simulated_s_ / wall : 0.0;
  std::string eta = "–";
  if (done_ > 0 && done_ < total_) {
    const auto remaining = static_cast<long>(wall / done_ * (total_ - done_));
    eta = fmt::format("{}:{:02d}", remaining / 60, remaining % 60);
  } else if (done_ >= total_) {
    eta = "done";
  }
  return fmt::format("[{}{}] {}/{} episodes · {:.1f} simulated h · {:.0f}× real time · ETA {}",
                     std::string(static_cast<std::size_t>(filled), '#'),
                     std::string(static_cast<std::size_t>(width - filled), '.'), done_, total_, simulated_s_ / 3600.0,
                     speed, eta);
}

void ProgressReporter::draw(bool force) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_draw_).count();
  if (!force && since < (tty_ ? 0.2 : 5.0)) return;
  last_draw_ = now;
  std::fprintf(stderr, tty_ ? "\r%s\033[K" : "%s\n", line().c_str());
  std::fflush(stderr);
}

void ProgressReporter::episode_done(double simulated_s) {
  std::lock_guard lock(mutex_);
  ++done_;
  simulated_s_ += simulated_s;
  draw(done_ == total_);
}

void ProgressReporter::finish() {
  std::lock_guard lock(mutex_);
  if (!enabled_) return;
  if (tty_) {
    std::fprintf(stderr, "\r%s\033[K\n", line().c_str());
  } else if (done_ != total_) {
    std::fprintf(stderr, "%s\n", line().c_str());
  }
  std::fflush(stderr);
}

}  // namespace freeplay::runner
