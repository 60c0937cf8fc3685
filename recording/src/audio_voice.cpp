#include "freeplay/recording/audio_voice.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>
#include <utility>

#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/recording/record_settings.hpp"
#ifdef FREEPLAY_WITH_ESPEAK
#include "freeplay/voice_espeak/espeak.hpp"
#endif

namespace freeplay::recording {

namespace {

constexpr int kResampleHalfWidth = 24;  // input samples either side of each output sample
constexpr double kFadeOutS = 0.02;      // a speech cut at the utterance's end fades out over this
constexpr float kPeak = 0.5F;           // every voice's peak amplitude

/// A word and its syllables.
struct Word {
  std::string_view text;
  int syllables;
};

// How each kind of child utterance opens, then words of the sandbox (animals, places, play) fill the syllables.
constexpr std::array<std::pair<std::string_view, std::array<Word, 2>>, 6> kOpenings = {{
    {"comment", {{{"look", 1}, {"the", 1}}}},
    {"proposal", {{{"let's", 1}, {"put", 1}}}},
    {"question", {{{"where", 1}, {"is", 1}}}},
    {"protest", {{{"no", 1}, {"that's", 1}}}},
    {"request", {{{"can", 1}, {"I", 1}}}},
    {"announce_stop", {{{"I'm", 1}, {"done", 1}}}},
}};
constexpr std::array<Word, 30> kWords = {{
    {"the", 1},     {"lion", 2},     {"zebra", 2},    {"here", 1},    {"there", 1},  {"big", 1},
    {"water", 2},   {"elephant", 3}, {"giraffe", 2},  {"put", 1},     {"go", 1},     {"home", 1},
    {"my", 1},      {"ball", 1},     {"hippo", 2},    {"crocodile", 3}, {"caravan", 3}, {"boy", 1},
    {"girl", 1},    {"this", 1},     {"one", 1},      {"over", 2},    {"by", 1},     {"tree", 1},
    {"eat", 1},     {"run", 1},      {"little", 2},   {"yellow", 2},  {"purple", 2}, {"jump", 1},
}};

/// Our babble/formant voice (recording::babble).
class BabbleVoice final : public Voice {
 public:
  std::vector<float> speak(const Utterance& u) const override { return babble(u); }
};

#ifdef FREEPLAY_WITH_ESPEAK
/// espeak-ng's English speech (freeplay_voice_espeak), resampled to kAudioRate and fitted to the utterance.
class EspeakVoice final : public Voice {
 public:
  std::vector<float> speak(const Utterance& u) const override {
    voice_espeak::Request request;
    request.text = u.text.empty() ? made_up_words(u.kind, u.syllables, u.seed) : u.text;
    request.pitch_hz = u.pitch_hz;
    if (u.duration_s > 0.0) request.syllables_per_s = std::max(1, u.syllables) / u.duration_s;
    request.seed = u.seed;
    const auto speech = voice_espeak::speak(request);
    std::vector<float> native(speech.samples.size());
    std::transform(speech.samples.begin(), speech.samples.end(), native.begin(),
                   [](std::int16_t v) { return static_cast<float>(v) / 32768.0F; });
    auto out = resample(native, speech.rate_hz, kAudioRate);
    // The sound starts with the utterance: espeak-ng's leading silence goes; it ends with it: a longer one is cut.
    float peak = 0.0F;
    for (const float v : out) peak = std::max(peak, std::abs(v));
    const auto first = std::find_if(out.begin(), out.end(), [&](float v) { return std::abs(v) > 0.02F * peak; });
    out.erase(out.begin(), first);
    const auto limit = static_cast<std::size_t>(std::max(0.0, u.duration_s) * kAudioRate);
    if (u.duration_s > 0.0 && out.size() > limit) {
      out.resize(limit);
      const auto fade = std::min(limit, static_cast<std::size_t>(kFadeOutS * kAudioRate));
      for (std::size_t i = 0; i < fade; ++i) out[limit - 1 - i] *= static_cast<float>(i) / static_cast<float>(fade);
    }
    if (peak > 0.0F) {
      for (auto& v : out) v *= kPeak / peak;
    }
    return out;
  }
};
#endif

}  // namespace

std::vector<std::string> voice_names() {
#ifdef FREEPLAY_WITH_ESPEAK
  return {kVoiceNames.begin(), kVoiceNames.end()};
#else
  return {std::string(kVoiceNames.front())};  // babble only
#endif
}

std::unique_ptr<Voice> make_voice(const std::string& name) {
  const auto names = voice_names();
  const auto allowed = fmt::format("{}", fmt::join(names, ", "));
  if (name == "babble") return std::make_unique<BabbleVoice>();
#ifdef FREEPLAY_WITH_ESPEAK
  if (name == "espeak") return std::make_unique<EspeakVoice>();
#else
  if (name == "espeak") {
    throw InputError("this freeplay was built without espeak-ng (install libespeak-ng-dev and rebuild with "
                     "FREEPLAY_WITH_ESPEAK=ON)",
                     "record.voice", allowed);
  }
#endif
  throw InputError(fmt::format("unknown voice '{}'", name), "record.voice", allowed);
}

std::vector<float> resample(const std::vector<float>& samples, int from_hz, int to_hz) {
  if (from_hz == to_hz || samples.empty()) return samples;
  const double step = static_cast<double>(from_hz) / to_hz;  // input samples per output sample
  const double cutoff = 0.9 * 0.5 * std::min(from_hz, to_hz) / from_hz;  // cycles per input sample
  const auto n = static_cast<std::size_t>(std::floor(static_cast<double>(samples.size()) / step));
  std::vector<float> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double x = static_cast<double>(k) * step;
    const auto centre = static_cast<std::int64_t>(std::floor(x));
    double sum = 0.0, weights = 0.0;
    for (std::int64_t i = centre - kResampleHalfWidth + 1; i <= centre + kResampleHalfWidth; ++i) {
      const double d = x - static_cast<double>(i);
      const double w = d / (kResampleHalfWidth + 1);  // in (−1, 1)
      const double window = 0.42 + 0.5 * std::cos(M_PI * w) + 0.08 * std::cos(2.0 * M_PI * w);
      const double arg = 2.0 * cutoff * d;
      const double h = window * (std::abs(arg) < 1e-12 ? 1.0 : std::sin(M_PI * arg) / (M_PI * arg));
      weights += h;
      if (i >= 0 && i < static_cast<std::int64_t>(samples.size())) sum += h * static_cast<double>(samples[static_cast<std::size_t>(i)]);
    }
    out[k] = static_cast<float>(sum / weights);
  }
  return out;
}

std::string made_up_words(const std::string& kind, int syllables, std::uint64_t seed) {
  Rng rng(seed);
  const auto opening = std::find_if(kOpenings.begin(), kOpenings.end(), [&](const auto& o) { return o.first == kind; });
  std::string out;
  int left = std::max(1, syllables);
  auto add = [&](const Word& w) {
    out += out.empty() ? "" : " ";
    out += w.text;
    left -= w.syllables;
  };
  for (const auto& w : (opening != kOpenings.end() ? opening : kOpenings.begin())->second) {
    if (left > 0) add(w);
  }
  while (left > 0) {
    const auto& w = kWords[static_cast<std::size_t>(rng.uniform_int(0, kWords.size() - 1))];
    if (w.syllables <= left) add(w);
  }
  return out + (kind == "question" || kind == "request" ? "?" : ".");
}

}  // namespace freeplay::recording
