#pragma once
// The voice-activity check the audio tests share: the speech is heard where the events say.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "freeplay/core/event_log.hpp"
#include "freeplay/recording/audio.hpp"

namespace freeplay::recording::audio_checks {

/// Expects the detector to find every utterance of `events` (children's speech, the robot's say) that starts after
/// 0.4 s of silence within 100 ms of its start, and no onset where nobody speaks; returns how many were checked.
inline int expect_utterances_heard(const std::vector<float>& samples, const std::vector<Event>& events) {
  const auto onsets = voice_onsets_s(samples);
  std::vector<std::pair<double, double>> spoken;  // start, end
  for (const auto& e : events) {
    if ((e.type() == "speech" && e.source.rfind("child.", 0) == 0) || (e.type() == "say" && e.source == "robot")) {
      spoken.emplace_back(e.t, e.t + e.data().value("duration_s", 0.0));
    }
  }
  EXPECT_FALSE(spoken.empty());
  int checked = 0;
  for (const auto& utterance : spoken) {
    const double start = utterance.first;
    const bool after_silence = std::none_of(spoken.begin(), spoken.end(), [&](const auto& o) {
      return o.first < start && o.second > start - 0.4;
    });
    if (!after_silence) continue;
    const auto near = std::find_if(onsets.begin(), onsets.end(), [&](double o) { return std::abs(o - start) <= 0.1; });
    EXPECT_NE(near, onsets.end()) << "utterance at " << start << " s";
    ++checked;
  }
  for (const double o : onsets) {
    EXPECT_TRUE(std::any_of(spoken.begin(), spoken.end(), [&](const auto& u) { return o >= u.first - 0.1 && o <= u.second + 0.1; }))
        << "onset at " << o << " s";
  }
  return checked;
}

/// The normalised correlation of `n` samples of `a` from `ia` with `n` samples of `b` from `ib` (0 for silence).
inline double correlation(const std::vector<float>& a, std::size_t ia, const std::vector<float>& b, std::size_t ib,
                          std::size_t n) {
  double c = 0.0, ea = 0.0, eb = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto x = static_cast<double>(a[ia + i]), y = static_cast<double>(b[ib + i]);
    c += x * y;
    ea += x * x;
    eb += y * y;
  }
  return ea > 0.0 && eb > 0.0 ? c / std::sqrt(ea * eb) : 0.0;
}

/// The lag (samples, ≤ `max_lag`) at which `delayed` best matches `original`, expecting the match to be close
/// (correlation above 0.9).
inline std::size_t delay_of(const std::vector<float>& delayed, const std::vector<float>& original, std::size_t max_lag) {
  std::size_t best_lag = 0;
  double best = -1.0;
  for (std::size_t lag = 0; lag <= max_lag && lag < delayed.size(); ++lag) {
    const double r = correlation(original, 0, delayed, lag, std::min(original.size(), delayed.size() - lag));
    if (r > best) best = r, best_lag = lag;
  }
  EXPECT_GT(best, 0.9) << "the decoded sound does not match the original at any lag up to " << max_lag;
  return best_lag;
}

}  // namespace freeplay::recording::audio_checks
