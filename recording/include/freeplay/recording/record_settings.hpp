#pragma once
// The recorder's user-facing settings (a scenario's `record:` map, docs/recording.md), declared once by the library
// that records: header-only, so that the scenario parser reads them without linking rosbag, OpenCV or the
// simulation. Member initialisers are the defaults; `visit` lists the keys, ranges and help
// (core/settings_archive.hpp).

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/core/settings_archive.hpp"

namespace freeplay::recording {

/// The voices a build can have (`record.voice`): "babble" always, "espeak" only in binaries built with espeak-ng
/// (voice_names() in audio_voice.hpp says which this binary has).
inline constexpr std::array<std::string_view, 2> kVoiceNames = {"babble", "espeak"};

/// How an episode is recorded (`record:` as a map; docs/recording.md).
struct RecordSettings {
  int jpeg_quality = 90;              ///< colour JPEG quality (the real launch files: 90)
  int png_level = 3;                  ///< PNG level of depth and background images (the real launch files: 3)
  int chunk_kb = 768;                 ///< bag chunk size (rosbag's default): at most this much is lost on a kill
  std::string compression = "none";   ///< bag chunk compression: "none" (as the real bags), "lz4", "bz2"
  int encoder_threads = 2;            ///< threads compressing camera images (0: on the episode's own thread)
  std::string voice = "babble";       ///< speech synthesiser of the audio: "babble" (ours) or "espeak" (espeak-ng)

  /// Same settings.
  bool operator==(const RecordSettings&) const = default;

  /// The keys of the `record:` map besides `bag` (`voice_names`: the names `voice` accepts).
  template <typename Archive>
  void visit(Archive& a, const std::vector<std::string>& voice_names) {
    a.field("jpeg_quality", jpeg_quality, Schema::integer(1, 100));
    a.field("png_level", png_level, Schema::integer(0, 9));
    a.field("chunk_kb", chunk_kb, Schema::integer(16, 1 << 20));
    a.field("compression", compression, Schema::enumeration({"none", "lz4", "bz2"}));
    a.field("encoder_threads", encoder_threads, Schema::integer(0, 64),
            "threads compressing camera images (0: the episode's thread)");
    a.field("voice", voice, Schema::enumeration(voice_names),
            "speech synthesiser of the audio: babble (ours) or espeak (espeak-ng, GPL-3; only in binaries built with it)");
  }
};

}  // namespace freeplay::recording
