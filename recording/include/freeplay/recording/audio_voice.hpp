#pragma once
// The voices that turn an utterance into sound (`record.voice`, docs/recording.md, Audio): the babble voice of our
// own (permissive, always there) and espeak-ng's speech (GPL-3, only in binaries built with the optional
// freeplay_voice_espeak library).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "freeplay/recording/audio.hpp"

namespace freeplay::recording {

/// A speech synthesiser: an utterance in, kAudioRate mono samples out, deterministic for the utterance's seed.
class Voice {
 public:
  virtual ~Voice() = default;
  /// The sound of `u`, starting at its start (no leading silence) and no longer than its duration_s; peak ≤ 0.5.
  virtual std::vector<float> speak(const Utterance& u) const = 0;
};

/// The voices this binary has: "babble", and "espeak" when it was built with espeak-ng (FREEPLAY_WITH_ESPEAK).
std::vector<std::string> voice_names();
/// The voice named `name` (a `record.voice` value); InputError naming `record.voice` and voice_names() when this
/// binary has no such voice.
std::unique_ptr<Voice> make_voice(const std::string& name);

/// `samples` at `from_hz` resampled to `to_hz` with a Blackman-windowed sinc low-pass at 0.9 × the lower Nyquist
/// frequency (24 input samples either side).
std::vector<float> resample(const std::vector<float>& samples, int from_hz, int to_hz);

/// Words for an utterance the simulation gives no text (a child's): about `syllables` syllables of sandbox talk
/// opening as its `kind` does (comment, proposal, question, protest, request, announce_stop), drawn from `seed`.
std::string made_up_words(const std::string& kind, int syllables, std::uint64_t seed);

}  // namespace freeplay::recording
