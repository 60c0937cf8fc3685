#pragma once
// Speech from espeak-ng (libespeak-ng, GPL-3): the optional voice of the recorded audio, kept in this library of its
// own so that a build without it (FREEPLAY_WITH_ESPEAK=OFF) contains no GPL code (docs/recording.md, Audio).

#include <cstdint>
#include <string>
#include <vector>

namespace freeplay::voice_espeak {

/// What to say and how.
struct Request {
  std::string text;              ///< UTF-8 words (English)
  double pitch_hz = 280.0;       ///< the speaker's fundamental frequency (espeak-ng reaches ≈ 130–320 Hz)
  double syllables_per_s = 3.0;  ///< articulation rate (espeak-ng reaches ≈ 2.3–12)
  std::uint64_t seed = 0;        ///< seeds espeak-ng's noise and the intonation range
};

/// Mono speech at espeak-ng's own sample rate.
struct Speech {
  std::vector<std::int16_t> samples;  ///< 16-bit PCM
  int rate_hz = 0;                    ///< sample rate (22050 for espeak-ng's voices)
};

/// Synthesises `request` with espeak-ng's English voice (variant f2); the same request gives the same samples,
/// whatever was said before and on whichever thread. std::runtime_error when espeak-ng or its data is missing.
Speech speak(const Request& request);

/// The espeak-ng pitch parameter (0–100) that gives about `hz` with the voice speak() uses (measured, clamped).
int pitch_parameter(double hz);
/// The espeak-ng rate (words per minute, 80–450) that gives about `syllables_per_s` (measured, clamped).
int rate_parameter(double syllables_per_s);

}  // namespace freeplay::voice_espeak
