#pragma once
// The stage's user-facing camera settings (a scenario's `cameras:` list and `rendering:` block), declared once by the
// library that renders them: header-only, so that the scenario parser reads them without linking MuJoCo. Member
// initialisers are the defaults; `visit` lists the keys, ranges and help (core/settings_archive.hpp).

#include <optional>
#include <string>
#include <vector>

#include "freeplay/core/settings_archive.hpp"
#include "freeplay/stage/render_names.hpp"

namespace freeplay::stage {

/// One camera stream the scenario asks for (an element of `cameras:`).
struct CameraStream {
  std::string name;      ///< stage camera name
  double rate_hz = 30;   ///< frames per simulated second
  int width = 960;       ///< pixels
  int height = 540;      ///< pixels
  bool depth = false;    ///< also read back depth
  bool video = false;    ///< write `videos/<episode>/<name>.mp4`

  /// Same settings.
  bool operator==(const CameraStream&) const = default;

  /// The keys of one camera (`camera_names`: the names `name` accepts, camera_names.hpp).
  template <typename Archive>
  void visit(Archive& a, const std::vector<std::string>& camera_names) {
    a.required("name", name, Schema::enumeration(camera_names));
    a.field("rate_hz", rate_hz, Schema::number(0.1, 60));
    a.field("width", width, Schema::integer(16, 4096));
    a.field("height", height, Schema::integer(16, 4096));
    a.field("depth", depth, Schema::boolean());
    a.field("video", video, Schema::boolean(), "write videos/<episode>/<name>.mp4 (mp4v, fps = rate_hz)");
  }
};

/// `rendering:` how the cameras are rendered (the renderer's options: renderer.hpp).
struct RenderingSettings {
  std::optional<GlBackend> backend;              ///< GL provider; nullopt: $MUJOCO_GL, else osmesa
  VisualPreset preset = kDefaultVisualPreset;    ///< visual quality

  /// Same settings.
  bool operator==(const RenderingSettings&) const = default;

  /// The keys of `rendering:`.
  template <typename Archive>
  void visit(Archive& a) {
    a.optional("backend", backend, Schema::enumeration(enum_names({GlBackend::osmesa, GlBackend::egl})),
               "GL provider; default $MUJOCO_GL, else osmesa");
    a.field("preset", preset, Schema::enumeration(enum_names({VisualPreset::fast, VisualPreset::pretty})),
            "fast: no MSAA/shadows/reflections/skybox; pretty: 4x MSAA, shadows, skybox");
  }
};

}  // namespace freeplay::stage
