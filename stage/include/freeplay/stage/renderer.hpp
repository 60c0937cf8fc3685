#pragma once
// Off-screen rendering of the stage's cameras (OSMesa by default, EGL on request) into OpenCV images.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <opencv2/core.hpp>
#include <string>
#include <string_view>

#include "freeplay/stage/render_names.hpp"
#include "freeplay/stage/stage.hpp"
#include "freeplay/stage/stage_model.hpp"

namespace freeplay::stage {

/// Parses "osmesa" / "egl"; throws InputError naming the allowed values.
GlBackend gl_backend_from_name(std::string_view name);
/// "osmesa" or "egl".
std::string_view gl_backend_name(GlBackend backend);
/// The backend named by $MUJOCO_GL ("osmesa" or "egl"), OSMesa when it is unset.
GlBackend default_gl_backend();

/// Parses "fast" / "pretty"; throws InputError naming the allowed values.
VisualPreset visual_preset_from_name(std::string_view name);
/// "fast" or "pretty".
std::string_view visual_preset_name(VisualPreset preset);

/// Renderer settings.
struct RendererOptions {
  GlBackend backend = GlBackend::osmesa;     ///< GL provider
  VisualPreset preset = kDefaultVisualPreset;  ///< quality
  int max_width = 1280;                      ///< largest image this renderer can produce (px)
  int max_height = 960;                      ///< largest image this renderer can produce (px)
};

/// Which images a render call produces.
struct RenderRequest {
  bool rgb = true;     ///< colour image at the camera's colour intrinsics
  bool depth = false;  ///< depth image (metres) at the camera's depth intrinsics
  int width = 0;       ///< override the colour resolution (0 = the camera's); intrinsics scale with it
  int height = 0;      ///< override the colour resolution (0 = the camera's)
  std::optional<CameraIntrinsics> intrinsics;  ///< render this pinhole instead (colour and depth) when set
};

/// One camera's output at one instant, with its calibration in the `sandtray` frame.
struct FramePack {
  std::string camera;                        ///< camera name
  cv::Mat rgb;                               ///< CV_8UC3, channel order R, G, B (empty unless requested)
  cv::Mat depth_m;                           ///< CV_32FC1 planar depth in metres (empty unless requested)
  CameraIntrinsics K;                        ///< intrinsics of `rgb`
  CameraIntrinsics K_depth;                  ///< intrinsics of `depth_m`
  Eigen::Isometry3d sandtray_T_camera_optical = Eigen::Isometry3d::Identity();  ///< optical frame pose
  double stamp = 0;                          ///< simulated time of the stage state (s)
};

/// Owns one GL context and MuJoCo render context; create one per thread and use it only from that thread.
class Renderer {
 public:
  /// Creates the GL context and uploads the model; throws std::runtime_error when the backend is unavailable.
  Renderer(std::shared_ptr<const StageModel> model, RendererOptions options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renders `camera` for the current stage state (call Stage::update_kinematics first when joints changed).
  FramePack render(const Stage& stage, std::string_view camera, const RenderRequest& request = {});

  /// glGetString(GL_RENDERER): shows whether a GPU or a software rasteriser draws.
  const std::string& gl_renderer() const { return gl_renderer_; }
  /// The settings in use.
  const RendererOptions& options() const { return options_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  RendererOptions options_;
  std::string gl_renderer_;
};

/// Converts MuJoCo's normalised depth-buffer value to planar distance (m) for a frustum's near/far planes.
double depth_buffer_to_metres(float buffer_value, double near_m, double far_m);

}  // namespace freeplay::stage
