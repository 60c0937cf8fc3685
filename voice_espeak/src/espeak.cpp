#include "freeplay/voice_espeak/espeak.hpp"

#include <espeak-ng/speak_lib.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <utility>

namespace freeplay::voice_espeak {

namespace {

constexpr const char* kVoice = "en+f2";  // English with the female variant f2 (no Klatt: no extra noise source)
// (pitch parameter, median fundamental frequency in Hz) of kVoice, measured with espeak-ng 1.51 (Debian 12).
constexpr std::array<std::pair<int, double>, 5> kPitch = {{{0, 128.0}, {25, 154.0}, {50, 190.0}, {75, 245.0}, {100, 320.0}}};
// Syllables per second per word-per-minute of espeak-ng's rate, measured on a 17-syllable sentence (80–250 wpm).
constexpr double kSyllablesPerWpm = 1.0 / 35.0;

// espeak-ng keeps its state in globals: it is initialised once and every synthesis runs under this lock.
std::mutex espeak_mutex;
int espeak_rate_hz = 0;  // 0 until initialised

bool write_all(int fd, const char* data, std::size_t bytes) {
  while (bytes > 0) {
    const auto wrote = ::write(fd, data, bytes);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) return false;
    data += wrote;
    bytes -= static_cast<std::size_t>(wrote);
  }
  return true;
}

// espeak-ng's callback: forwards the samples to the pipe whose descriptor the synthesis carries as user data.
int on_samples(short* wav, int count, espeak_EVENT* events) {
  const int fd = *static_cast<const int*>(events->user_data);
  if (wav == nullptr || count <= 0) return 0;
  return write_all(fd, reinterpret_cast<const char*>(wav), 2 * static_cast<std::size_t>(count)) ? 0 : 1;
}

// The forked child: speaks the request into `fd` from the state espeak-ng had right after initialisation (voice set).
[[noreturn]] void speak_and_exit(const Request& r, int fd) {
  espeak_SetParameter(espeakRATE, rate_parameter(r.syllables_per_s), 0);
  espeak_SetParameter(espeakPITCH, pitch_parameter(r.pitch_hz), 0);
  espeak_SetParameter(espeakRANGE, 40 + static_cast<int>((r.seed >> 16) % 31), 0);  // intonation, 50 = normal
  std::srand(static_cast<unsigned>(r.seed));  // espeak-ng's noise comes from rand()
  int descriptor = fd;
  const auto status = espeak_Synth(r.text.c_str(), r.text.size() + 1, 0, POS_CHARACTER, 0, espeakCHARS_UTF8, nullptr,
                                   &descriptor);
  if (status != EE_OK || espeak_Synchronize() != EE_OK) ::_exit(3);
  ::_exit(0);
}

}  // namespace

int pitch_parameter(double hz) {
  if (hz <= kPitch.front().second) return kPitch.front().first;
  for (std::size_t i = 1; i < kPitch.size(); ++i) {
    if (hz <= kPitch[i].second) {  // log-linear between the measured points
      const double f = std::log(hz / kPitch[i - 1].second) / std::log(kPitch[i].second / kPitch[i - 1].second);
      return static_cast<int>(std::lround(kPitch[i - 1].first + f * (kPitch[i].first - kPitch[i - 1].first)));
    }
  }
  return kPitch.back().first;
}

int rate_parameter(double syllables_per_s) {
  return std::clamp(static_cast<int>(std::lround(syllables_per_s / kSyllablesPerWpm)), espeakRATE_MINIMUM,
                    espeakRATE_MAXIMUM);
}

Speech speak(const Request& request) {
  std::lock_guard lock(espeak_mutex);
  if (espeak_rate_hz == 0) {
    const int rate = espeak_Initialize(AUDIO_OUTPUT_SYNCHRONOUS, 0, nullptr, espeakINITIALIZE_DONT_EXIT);
    if (rate <= 0) throw std::runtime_error("espeak-ng could not start (is espeak-ng-data installed?)");
    espeak_SetSynthCallback(on_samples);
    // The voice (its dictionary and phoneme tables) is loaded once here; the children inherit it.
    if (espeak_SetVoiceByName(kVoice) != EE_OK) {
      throw std::runtime_error(std::string("espeak-ng has no voice '") + kVoice + "' (is espeak-ng-data installed?)");
    }
    espeak_rate_hz = rate;
  }
  // espeak-ng carries state from one synthesis to the next (its output differs when the same words are said twice),
  // so each utterance is synthesised in a forked child from the state right after initialisation: the parent never
  // synthesises, and the same request gives the same samples whatever was said before.
  std::array<int, 2> fds{};
  if (::pipe2(fds.data(), O_CLOEXEC) != 0) throw std::runtime_error(std::string("espeak-ng: pipe failed: ") + std::strerror(errno));
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("espeak-ng: fork failed: ") + std::strerror(errno));
  }
  if (child == 0) {
    ::close(fds[0]);
    speak_and_exit(request, fds[1]);
  }
  ::close(fds[1]);
  std::vector<char> bytes;
  std::array<char, 1 << 16> buffer{};
  for (;;) {
    const auto got = ::read(fds[0], buffer.data(), buffer.size());
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    bytes.insert(bytes.end(), buffer.begin(), buffer.begin() + got);
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("espeak-ng failed to speak '" + request.text + "' (voice " + kVoice + ")");
  }
  Speech out;
  out.rate_hz = espeak_rate_hz;
  out.samples.resize(bytes.size() / 2);
  std::memcpy(out.samples.data(), bytes.data(), 2 * out.samples.size());
  return out;
}

}  // namespace freeplay::voice_espeak
