// The voices of the recorded audio (record.voice): espeak-ng's speech where the binary has it, the babble voice
// always, the resampler between espeak-ng's rate and the microphones', and the refusal of an unknown voice.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <fstream>
#include <thread>

#include "audio_checks.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/recording/audio.hpp"
#include "freeplay/recording/audio_voice.hpp"
#include "freeplay/recording/bag_recorder.hpp"
#include "freeplay/runner/episode.hpp"

using namespace freeplay;
using namespace freeplay::recording;

namespace {

bool have_espeak() {
  const auto names = voice_names();
  return std::find(names.begin(), names.end(), "espeak") != names.end();
}

#define SKIP_WITHOUT_ESPEAK() \
  if (!have_espeak()) GTEST_SKIP() << "this binary was built without espeak-ng (FREEPLAY_WITH_ESPEAK=OFF)"

scenario::Scenario test_scenario(const std::string& record) {
  return scenario::scenario_from_document(parse_yaml(
      fmt::format("name: tiny\ncondition: child-robot\nrecord: {}\n"
                  "protocol: {{greeting_s: 1, tutorial_s: 1, freeplay_cap_s: 20, debriefing_s: 1}}\n",
                  record),
      "tiny.yaml"));
}

struct Recorded {
  runner::EpisodeResult result;
  std::vector<float> purple;  // the purple microphone's WAV
};

Recorded record(const std::string& name, const scenario::Scenario& s, std::uint64_t seed = 7) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("freeplay-voice-" + name + "-" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::remove_all(dir);
  runner::EpisodeObservers observers;
  observers.push_back(std::make_unique<BagRecorder>(dir / "sessions", s.recording));
  const std::atomic<bool> stop{false};
  Recorded out;
  out.result = runner::run_episode({.scenario = s, .seed = seed, .stop = stop, .id = "tiny-0000"},
                                   runner::observed_by(observers));
  out.purple = read_wav(dir / "sessions" / "tiny-0000" / "audio" / "freeplay_camera_purple_audio.wav");
  std::filesystem::remove_all(dir);
  return out;
}

// The median fundamental frequency of the voiced 40 ms frames (normalised autocorrelation above 0.6, 70–500 Hz).
double median_f0_hz(const std::vector<float>& s) {
  constexpr std::size_t kFrame = kAudioRate / 25;
  std::vector<double> found;
  for (std::size_t i = 0; i + kFrame < s.size(); i += kFrame / 2) {
    const std::size_t n = kFrame - kAudioRate / 70;  // every lag's window inside the frame
    double energy = 0.0;
    for (std::size_t j = i; j < i + kFrame; ++j) energy += static_cast<double>(s[j]) * static_cast<double>(s[j]);
    if (energy / kFrame < 1e-5) continue;  // silence
    double best = 0.0;
    int best_lag = 0;
    for (int lag = kAudioRate / 500; lag <= kAudioRate / 70; ++lag) {
      const double r = audio_checks::correlation(s, i, s, i + static_cast<std::size_t>(lag), n);
      if (r > best) best = r, best_lag = lag;
    }
    if (best > 0.6) found.push_back(static_cast<double>(kAudioRate) / best_lag);
  }
  if (found.empty()) return 0.0;
  std::nth_element(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(found.size() / 2), found.end());
  return found[found.size() / 2];
}

Utterance utterance(double pitch_hz, const std::string& text = "") {
  Utterance u;
  u.duration_s = 2.0;
  u.syllables = 7;
  u.pitch_hz = pitch_hz;
  u.seed = 42;
  u.text = text;
  u.kind = "proposal";
  return u;
}

}  // namespace

TEST(AudioVoice, EspeakEveryUtteranceIsHeardWhereTheEventsSay) {
  SKIP_WITHOUT_ESPEAK();
  const auto r = record("heard", test_scenario("{voice: espeak}"));
  EXPECT_NEAR(static_cast<double>(r.purple.size()), r.result.simulated_s * kAudioRate, 2.0);
  EXPECT_GT(audio_checks::expect_utterances_heard(r.purple, r.result.events.events()), 0);
}

TEST(AudioVoice, EspeakSameSeedGivesTheSameSamples) {
  SKIP_WITHOUT_ESPEAK();
  // A whole episode twice: the same WAV.
  const auto s = test_scenario("{voice: espeak}");
  EXPECT_EQ(record("first", s).purple, record("second", s).purple);
  // One utterance, whatever was said before and on whichever thread.
  const auto voice = make_voice("espeak");
  const auto first = voice->speak(utterance(280.0));
  (void)voice->speak(utterance(200.0, "Hello, shall we play together?"));
  std::vector<float> from_thread;
  std::thread([&] { from_thread = voice->speak(utterance(280.0)); }).join();
  EXPECT_EQ(voice->speak(utterance(280.0)), first);
  EXPECT_EQ(from_thread, first);
  auto other = utterance(280.0);
  other.seed = 43;  // other words
  EXPECT_NE(voice->speak(other), first);
}

TEST(AudioVoice, EspeakSpeaksAtTheSpeakersPitchWithinTheUtterance) {
  SKIP_WITHOUT_ESPEAK();
  const auto voice = make_voice("espeak");
  for (const double hz : {child_pitch_hz(4), child_pitch_hz(8), 200.0, 210.0}) {
    const auto u = utterance(hz, "Look at the lion, it is over there by the water.");
    const auto sound = voice->speak(u);
    EXPECT_NEAR(median_f0_hz(sound), hz, 0.15 * hz) << hz << " Hz";
    EXPECT_LE(sound.size(), static_cast<std::size_t>(u.duration_s * kAudioRate));
    EXPECT_GT(std::abs(sound.front()), 0.0F);  // no leading silence: the sound starts with the utterance
    EXPECT_LE(*std::max_element(sound.begin(), sound.end()), 0.5F);
  }
}

TEST(AudioVoice, UnknownOrMissingVoicesAreRefusedNamingTheKeyAndTheVoices) {
  try {
    (void)test_scenario("{voice: robotic}");
    ADD_FAILURE() << "record.voice: robotic was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("voice"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("babble, espeak"), std::string::npos) << e.what();
  }
  try {
    (void)make_voice("robotic");
    ADD_FAILURE() << "make_voice(robotic) succeeded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("record.voice"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("babble"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(make_voice("babble"));
  if (have_espeak()) {
    EXPECT_TRUE(make_voice("espeak"));
  } else {  // a binary without espeak-ng says so when a scenario asks for it
    EXPECT_THROW(BagRecorder(std::filesystem::temp_directory_path(), test_scenario("{voice: espeak}").recording), InputError);
  }
}

TEST(AudioVoice, ResampleKeepsTheSpeechBandAndRemovesWhatWouldAlias) {
  auto tone = [](double hz, int rate) {
    std::vector<float> s(static_cast<std::size_t>(rate));
    for (std::size_t i = 0; i < s.size(); ++i) s[i] = static_cast<float>(std::sin(2.0 * M_PI * hz * static_cast<double>(i) / rate));
    return s;
  };
  auto rms = [](const std::vector<float>& s) {  // the middle half (away from the edges)
    double e = 0.0;
    for (std::size_t i = s.size() / 4; i < 3 * s.size() / 4; ++i) e += static_cast<double>(s[i]) * static_cast<double>(s[i]);
    return std::sqrt(e / static_cast<double>(s.size() / 2));
  };
  const auto kept = resample(tone(1000.0, 22050), 22050, kAudioRate);
  EXPECT_NEAR(static_cast<double>(kept.size()), kAudioRate, 1.0);
  EXPECT_NEAR(rms(kept), std::sqrt(0.5), 0.01);
  const auto expected = tone(1000.0, kAudioRate);
  for (std::size_t i = 1000; i < 1100; ++i) EXPECT_NEAR(kept[i], expected[i], 0.01F);
  EXPECT_LT(rms(resample(tone(10000.0, 22050), 22050, kAudioRate)), 0.01);  // above 8 kHz: gone, not folded to 6 kHz
}

TEST(AudioVoice, MadeUpWordsFollowTheKindAndTheSeed) {
  const auto question = made_up_words("question", 6, 1);
  EXPECT_EQ(question.rfind("where is ", 0), 0U) << question;
  EXPECT_EQ(question.back(), '?');
  EXPECT_EQ(made_up_words("question", 6, 1), question);
  EXPECT_NE(made_up_words("question", 6, 2), question);
  EXPECT_EQ(made_up_words("proposal", 1, 3), "let's.");
}
