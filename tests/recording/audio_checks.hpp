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
    if ((e.type == "speech" && e.source.rfind("child.", 0) == 0) || (e.type == "say" && e.source == "robot")) {
      spoken.emplace_back(e.t, e.t + e.data.value("duration_s", 0.0));
    }
  }
  EXPECT_FALSE(spoken.empty());
  int checked = 0;
  for (const auto& [start, end] : spoken) {
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

}  // namespace freeplay::recording::audio_checks
