#pragma once
// Sound for the recorded sessions (free-play-sandbox.md §1.4, §4.2): every utterance (child, robot, experimenter)
// spoken by a voice (audio_voice.hpp: the babble/formant voice of our own here, or espeak-ng; a child's pitch, the
// utterance's articulation rate; deterministic for a seed), mixed per SR300 microphone with distance attenuation and room noise, encoded as audio_capture does
// (LAME MP3, 16 kHz mono, 128 kbps) and cut into one message per MP3 frame (≈ 27.8 per second).

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace freeplay::recording {

/// Sample rate of the recorded audio (Hz), as `dual_sr300.launch` sets it.
inline constexpr int kAudioRate = 16000;
/// Samples per MP3 frame at 16 kHz (MPEG-2 layer III).
inline constexpr int kMp3FrameSamples = 576;
/// Bytes per MP3 frame at 16 kHz and 128 kbps (constant bit rate, no padding).
inline constexpr int kMp3FrameBytes = 576;

/// One utterance to be heard.
struct Utterance {
  double start_s = 0.0;      ///< sandtray time (s)
  double duration_s = 0.0;   ///< s
  int syllables = 1;         ///< spoken at syllables / duration_s
  double pitch_hz = 280.0;   ///< fundamental frequency
  Eigen::Vector3d mouth = Eigen::Vector3d::Zero();  ///< where it is spoken (sandtray frame, m)
  std::uint64_t seed = 0;    ///< the voice's random stream
  std::string text;          ///< the words (robot, experimenter); empty for a child, whose words are not simulated
  std::string kind;          ///< a child's kind of utterance (comment, question, …), as its speech event says
};

/// The babble voice: `syllables` consonant–vowel syllables (noise burst, then a pulse train through three vowel
/// formants) at `pitch_hz`, peak amplitude ≤ 0.5, `duration_s × kAudioRate` samples.
std::vector<float> babble(const Utterance& u);

/// The fundamental frequency of a child of `age_years` (≈ 300 Hz at 4 falling to ≈ 260 Hz at 8).
double child_pitch_hz(double age_years);

/// One microphone's stream: mixes utterances, adds room noise, encodes MP3 and writes the WAV and MP3 files.
class MicrophoneStream {
 public:
  /// A microphone at `position` writing `<stem>.wav` and `<stem>.mp3`; `seed` drives its room noise.
  MicrophoneStream(Eigen::Vector3d position, const std::filesystem::path& stem, std::uint64_t seed);
  ~MicrophoneStream();
  MicrophoneStream(const MicrophoneStream&) = delete;
  MicrophoneStream& operator=(const MicrophoneStream&) = delete;

  /// Adds an utterance's voice, attenuated with the distance from its mouth (1 at 0.3 m and closer, then 0.3 / d).
  void add(const Utterance& u, const std::vector<float>& voice);
  /// Encodes everything up to sandtray time `t` and returns the MP3 frames completed, each with the sandtray time
  /// its last sample was captured.
  std::vector<std::pair<double, std::vector<std::uint8_t>>> advance(double t);
  /// Encodes the rest, closes the files and returns the last frames.
  std::vector<std::pair<double, std::vector<std::uint8_t>>> finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Times (s from the first sample) where a simple voice-activity detector (10 ms frames, energy above 4 × the quietest tenth)
/// finds speech starting after at least `min_silence_s` of silence.
std::vector<double> voice_onsets_s(const std::vector<float>& samples, double min_silence_s = 0.3);
/// The 16-bit mono samples of a WAV file written by MicrophoneStream, as floats in [−1, 1].
std::vector<float> read_wav(const std::filesystem::path& file);
/// The mono samples an MP3 stream (e.g. a microphone topic's chunks concatenated) decodes to, as floats in [−1, 1],
/// by LAME's own decoder (hip); the decoder's delay is kept (≈ 1 100 samples at 16 kHz).
std::vector<float> decode_mp3(const std::vector<std::uint8_t>& mp3);

}  // namespace freeplay::recording
