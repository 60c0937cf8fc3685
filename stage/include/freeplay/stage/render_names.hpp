#pragma once
// The renderer's two choices (GL provider, visual preset) with their one name/value pair and the preset's one
// default: header-only, so that the scenario parser reads `rendering:` without linking MuJoCo.

#include <string_view>

#include "freeplay/core/enum_names.hpp"

namespace freeplay::stage {

/// Which OpenGL provider renders: Mesa's OSMesa (CPU, no display) or EGL (GPU, or Mesa's surfaceless llvmpipe).
enum class GlBackend { osmesa, egl };

/// The name `rendering.backend`, `--gl` and $MUJOCO_GL use ("osmesa", "egl").
constexpr std::string_view to_string(GlBackend backend) { return backend == GlBackend::egl ? "egl" : "osmesa"; }

/// Sets `backend` to the provider named `text`; false (and `backend` unchanged) when `text` names none.
constexpr bool from_string(std::string_view text, GlBackend& backend) {
  return enum_from_string(text, {GlBackend::osmesa, GlBackend::egl}, backend);
}

/// Visual quality: `fast` (no MSAA, shadows, reflections or skybox) or `pretty` (4× MSAA, shadows, skybox).
enum class VisualPreset { fast, pretty };

/// The preset a renderer and a scenario without `rendering.preset` use.
inline constexpr VisualPreset kDefaultVisualPreset = VisualPreset::fast;

/// The name `rendering.preset` and `--preset` use ("fast", "pretty").
constexpr std::string_view to_string(VisualPreset preset) { return preset == VisualPreset::pretty ? "pretty" : "fast"; }

/// Sets `preset` to the preset named `text`; false (and `preset` unchanged) when `text` names none.
constexpr bool from_string(std::string_view text, VisualPreset& preset) {
  return enum_from_string(text, {VisualPreset::fast, VisualPreset::pretty}, preset);
}

}  // namespace freeplay::stage
