#pragma once
// A progress line for long runs: episodes done, simulated hours, speed (× real time) and ETA, on stderr.

#include <chrono>
#include <mutex>
#include <string>

namespace freeplay::runner {

/// Thread-safe progress reporter; redraws in place on a terminal, prints a line every few seconds otherwise.
class ProgressReporter {
 public:
  /// `total` episodes to run in this invocation (already finished ones excluded); `enabled` false = silent.
  ProgressReporter(int total, bool enabled);
  /// Records one finished episode of `simulated_s` simulated seconds.
  void episode_done(double simulated_s);
  /// Prints the final line (newline-terminated).
  void finish();
  /// The current progress line (for tests and logs).
  std::string line() const;

 private:
  void draw(bool force);
  int total_;
  bool enabled_;
  bool tty_;
  int done_ = 0;
  double simulated_s_ = 0.0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  mutable std::mutex mutex_;
};

}  // namespace freeplay::runner
