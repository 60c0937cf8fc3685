#include "freeplay/recording/audio.hpp"

#include <fmt/format.h>
#include <lame/lame.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <deque>
#include <type_traits>

#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"

namespace freeplay::recording {

namespace {

constexpr double kNoiseAmplitude = 0.002;  // room noise (uniform white, ≈ −57 dBFS RMS)
constexpr double kNearFieldM = 0.3;        // closer than this the level no longer rises

/// A two-pole resonator (formant) at `frequency` with `bandwidth` (Hz).
struct Resonator {
  double a1 = 0, a2 = 0, gain = 0, y1 = 0, y2 = 0;
  Resonator(double frequency, double bandwidth) {
    const double r = std::exp(-M_PI * bandwidth / kAudioRate);
    a1 = 2.0 * r * std::cos(2.0 * M_PI * frequency / kAudioRate);
    a2 = -r * r;
    gain = 1.0 - r;
  }
  double operator()(double x) {
    const double y = gain * x + a1 * y1 + a2 * y2;
    y2 = y1;
    y1 = y;
    return y;
  }
};

// Vowel formants F1, F2, F3 (Hz) of a child's a, e, i, o, u.
constexpr std::array<std::array<double, 3>, 5> kVowels = {{{1000, 1800, 3300},
                                                          {700, 2600, 3500},
                                                          {420, 3100, 3800},
                                                          {650, 1150, 3200},
                                                          {460, 1250, 3300}}};

void write_wav_header(std::ofstream& out, std::uint32_t samples) {
  auto u32 = [&](std::uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
  auto u16 = [&](std::uint16_t v) { out.write(reinterpret_cast<const char*>(&v), 2); };
  out.seekp(0);
  out.write("RIFF", 4);
  u32(36 + 2 * samples);
  out.write("WAVEfmt ", 8);
  u32(16);
  u16(1);  // PCM
  u16(1);  // mono
  u32(kAudioRate);
  u32(2 * kAudioRate);
  u16(2);
  u16(16);
  out.write("data", 4);
  u32(2 * samples);
}

}  // namespace

double child_pitch_hz(double age_years) { return 300.0 - 10.0 * (std::clamp(age_years, 4.0, 8.0) - 4.0); }

std::vector<float> babble(const Utterance& u) {
  Rng rng(u.seed);
  const auto n = static_cast<std::size_t>(std::max(0.0, u.duration_s) * kAudioRate);
  std::vector<float> out(n, 0.0F);
  const int syllables = std::max(1, u.syllables);
  const double syllable = static_cast<double>(n) / syllables;
  double phase = 0.0;
  for (int s = 0; s < syllables; ++s) {
    const auto& vowel = kVowels[static_cast<std::size_t>(rng.uniform_int(0, 4))];
    std::array<Resonator, 3> formants = {Resonator(vowel[0], 90), Resonator(vowel[1], 120), Resonator(vowel[2], 180)};
    Resonator fricative(rng.uniform(2500, 6000), 1500);
    const double f0 = u.pitch_hz * rng.uniform(0.9, 1.15);
    const auto begin = static_cast<std::size_t>(s * syllable);
    const auto end = std::min(n, static_cast<std::size_t>((s + 1) * syllable));
    const std::size_t burst = std::min<std::size_t>((end - begin) / 5, kAudioRate / 30);
    for (std::size_t i = begin; i < end; ++i) {
      const double x = static_cast<double>(i - begin) / static_cast<double>(end - begin);
      const double envelope = std::sin(M_PI * x);  // each syllable rises and falls
      double sample = 0.0;
      if (i - begin < burst) {
        sample = 0.6 * fricative(rng.uniform(-1.0, 1.0));
      } else {
        const double f = f0 * (1.0 + 0.05 * std::sin(M_PI * x));  // a little intonation
        phase += f / kAudioRate;
        const double pulse = phase - std::floor(phase) < 0.5 ? 1.0 : -1.0;  // glottal source (square)
        for (auto& formant : formants) sample += formant(pulse);
        sample *= 2.0;
      }
      out[i] = static_cast<float>(std::clamp(0.5 * envelope * sample, -0.5, 0.5));
    }
  }
  return out;
}

struct MicrophoneStream::Impl {
  Eigen::Vector3d position;
  Rng noise;
  std::ofstream wav, mp3;
  std::uint32_t written = 0;              // samples encoded so far
  std::deque<float> future;               // mixed voices from sample `written` on
  lame_global_flags* lame = nullptr;
  std::vector<std::uint8_t> bytes;        // encoded, not yet cut into frames
  std::uint64_t frames = 0;               // frames cut so far

  std::vector<std::pair<double, std::vector<std::uint8_t>>> cut(bool all) {
    std::vector<std::pair<double, std::vector<std::uint8_t>>> out;
    std::size_t at = 0;
    while (bytes.size() - at >= kMp3FrameBytes || (all && at < bytes.size())) {
      const std::size_t len = std::min<std::size_t>(kMp3FrameBytes, bytes.size() - at);
      ++frames;
      // Frame k holds the k-th 576 samples' worth of sound: it is stamped when they had been captured.
      out.emplace_back(static_cast<double>(frames * kMp3FrameSamples) / kAudioRate, std::vector<std::uint8_t>(bytes.begin() + at, bytes.begin() + at + len));
      at += len;
    }
    bytes.erase(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(at));
    return out;
  }
};

MicrophoneStream::MicrophoneStream(Eigen::Vector3d position, const std::filesystem::path& stem, std::uint64_t seed)
    : impl_(std::make_unique<Impl>()) {
  auto& d = *impl_;
  d.position = position;
  d.noise = Rng(seed);
  auto wav = stem;
  wav += ".wav";
  auto mp3 = stem;
  mp3 += ".mp3";
  d.wav.open(wav, std::ios::binary | std::ios::trunc);
  d.mp3.open(mp3, std::ios::binary | std::ios::trunc);
  if (!d.wav || !d.mp3) throw InputError(fmt::format("cannot write '{}'", stem.string()), "record");
  write_wav_header(d.wav, 0);
  d.lame = lame_init();
  lame_set_in_samplerate(d.lame, kAudioRate);
  lame_set_out_samplerate(d.lame, kAudioRate);
  lame_set_num_channels(d.lame, 1);
  lame_set_mode(d.lame, MONO);
  lame_set_brate(d.lame, 128);
  lame_set_VBR(d.lame, vbr_off);
  lame_set_bWriteVbrTag(d.lame, 0);
  lame_set_quality(d.lame, 7);  // LAME's fast algorithm choice (2 = best, 9 = fastest): it was a third of the time
  if (lame_init_params(d.lame) < 0) throw std::runtime_error("LAME refused 16 kHz mono 128 kbps");
}

MicrophoneStream::~MicrophoneStream() {
  if (impl_->lame != nullptr) lame_close(impl_->lame);
}

void MicrophoneStream::add(const Utterance& u, const std::vector<float>& voice) {
  auto& d = *impl_;
  const double gain = kNearFieldM / std::max(kNearFieldM, (u.mouth - d.position).norm());
  const auto start = static_cast<std::int64_t>(std::llround(u.start_s * kAudioRate)) - d.written;
  const std::size_t skip = start < 0 ? static_cast<std::size_t>(-start) : 0;
  const std::size_t offset = start < 0 ? 0 : static_cast<std::size_t>(start);
  if (d.future.size() < offset + voice.size() - std::min(skip, voice.size())) {
    d.future.resize(offset + voice.size() - std::min(skip, voice.size()), 0.0F);
  }
  for (std::size_t i = skip; i < voice.size(); ++i) d.future[offset + i - skip] += static_cast<float>(gain) * voice[i];
}

std::vector<std::pair<double, std::vector<std::uint8_t>>> MicrophoneStream::advance(double t) {
  auto& d = *impl_;
  const auto until = static_cast<std::int64_t>(std::llround(t * kAudioRate));
  if (until <= d.written) return {};
  const auto n = static_cast<std::size_t>(until - d.written);
  std::vector<float> pcm(n);
  std::vector<std::int16_t> pcm16(n);
  for (std::size_t i = 0; i < n; ++i) {
    float v = static_cast<float>(d.noise.uniform(-kNoiseAmplitude, kNoiseAmplitude) * std::sqrt(3.0));
    if (!d.future.empty()) {
      v += d.future.front();
      d.future.pop_front();
    }
    pcm[i] = std::clamp(v, -1.0F, 1.0F);
    pcm16[i] = static_cast<std::int16_t>(std::lround(pcm[i] * 32767.0F));
  }
  d.wav.write(reinterpret_cast<const char*>(pcm16.data()), static_cast<std::streamsize>(2 * n));
  std::vector<unsigned char> buffer(n + n / 4 + 7200);
  const int got = lame_encode_buffer(d.lame, pcm16.data(), nullptr, static_cast<int>(n), buffer.data(),
                                     static_cast<int>(buffer.size()));
  if (got < 0) throw std::runtime_error(fmt::format("LAME failed to encode ({})", got));
  d.mp3.write(reinterpret_cast<const char*>(buffer.data()), got);
  d.bytes.insert(d.bytes.end(), buffer.begin(), buffer.begin() + got);
  d.written += static_cast<std::uint32_t>(n);
  return d.cut(false);
}

std::vector<std::pair<double, std::vector<std::uint8_t>>> MicrophoneStream::finish() {
  auto& d = *impl_;
  std::vector<unsigned char> buffer(7200);
  const int got = lame_encode_flush(d.lame, buffer.data(), static_cast<int>(buffer.size()));
  if (got > 0) {
    d.mp3.write(reinterpret_cast<const char*>(buffer.data()), got);
    d.bytes.insert(d.bytes.end(), buffer.begin(), buffer.begin() + got);
  }
  write_wav_header(d.wav, d.written);
  d.wav.close();
  d.mp3.close();
  return d.cut(true);
}

std::vector<double> voice_onsets_s(const std::vector<float>& samples, double min_silence_s) {
  constexpr std::size_t kFrame = kAudioRate / 100;
  std::vector<double> energy;
  for (std::size_t i = 0; i + kFrame <= samples.size(); i += kFrame) {
    double e = 0.0;
    for (std::size_t j = i; j < i + kFrame; ++j) e += static_cast<double>(samples[j]) * static_cast<double>(samples[j]);
    energy.push_back(e / kFrame);
  }
  if (energy.empty()) return {};
  auto sorted = energy;
  std::sort(sorted.begin(), sorted.end());
  const double threshold = 4.0 * sorted[sorted.size() / 10] + 1e-9;
  std::vector<double> onsets;
  std::size_t silent = static_cast<std::size_t>(min_silence_s * 100);
  for (std::size_t k = 0; k < energy.size(); ++k) {
    if (energy[k] > threshold) {
      if (silent * 10 >= static_cast<std::size_t>(min_silence_s * 1000)) onsets.push_back(static_cast<double>(k) / 100.0);
      silent = 0;
    } else {
      ++silent;
    }
  }
  return onsets;
}

std::vector<float> read_wav(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("cannot read '{}'", file.string()), "wav");
  in.seekg(44);
  std::vector<float> out;
  std::int16_t v = 0;
  while (in.read(reinterpret_cast<char*>(&v), 2)) out.push_back(static_cast<float>(v) / 32767.0F);
  return out;
}

std::vector<float> decode_mp3(const std::vector<std::uint8_t>& mp3) {
  const std::unique_ptr<std::remove_pointer_t<hip_t>, int (*)(hip_t)> hip(hip_decode_init(), hip_decode_exit);
  if (!hip) throw std::runtime_error("LAME's MP3 decoder did not start");
  std::vector<float> out;
  std::vector<short> left(1 << 16), right(1 << 16);  // hip writes up to a second's worth per call
  std::vector<unsigned char> bytes(mp3.begin(), mp3.end());
  constexpr std::size_t kFeed = 4096;
  for (std::size_t at = 0; at <= bytes.size(); at += kFeed) {
    const std::size_t n = at < bytes.size() ? std::min(kFeed, bytes.size() - at) : 0;  // a last empty call drains it
    int got = hip_decode(hip.get(), bytes.data() + at, n, left.data(), right.data());
    for (; got > 0; got = hip_decode(hip.get(), bytes.data() + at, 0, left.data(), right.data())) {
      for (int i = 0; i < got; ++i) out.push_back(static_cast<float>(left[static_cast<std::size_t>(i)]) / 32767.0F);
    }
    if (got < 0) throw std::runtime_error(fmt::format("the MP3 stream does not decode (byte {})", at));
  }
  return out;
}

}  // namespace freeplay::recording
