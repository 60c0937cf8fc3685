#include "freeplay/stage/renderer.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>
#include <dlfcn.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "freeplay/core/error.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {
namespace {

using GetStringFn = const unsigned char* (*)(unsigned int);

// A GL context made current on demand. The GL libraries are opened at run time so that exactly one GL provider
// is in the process (MuJoCo 2.2 finds its GL functions through whichever provider is loaded).
class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual void make_current() = 0;
  virtual void* proc_address(const char* name) = 0;
};

void* open_library(const char* name, const char* package) {
  void* handle = dlopen(name, RTLD_NOW | RTLD_GLOBAL);
  if (handle == nullptr) {
    throw std::runtime_error(fmt::format("cannot load {} ({}); install the Debian package {}", name, dlerror(),
                                         package));
  }
  return handle;
}

template <typename Fn>
Fn symbol(void* library, const char* name) {
  void* address = dlsym(library, name);
  if (address == nullptr) throw std::runtime_error(fmt::format("GL library lacks {}", name));
  return reinterpret_cast<Fn>(address);
}

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext(int width, int height) : width_(width), height_(height) {
    library_ = open_library("libOSMesa.so.8", "libosmesa6");
    create_ = symbol<decltype(create_)>(library_, "OSMesaCreateContextExt");
    make_current_ = symbol<decltype(make_current_)>(library_, "OSMesaMakeCurrent");
    destroy_ = symbol<decltype(destroy_)>(library_, "OSMesaDestroyContext");
    get_proc_ = symbol<decltype(get_proc_)>(library_, "OSMesaGetProcAddress");
    context_ = create_(OSMESA_RGBA, 24, 8, 0, nullptr);
    if (context_ == nullptr) throw std::runtime_error("OSMesaCreateContextExt failed");
    buffer_.resize(static_cast<size_t>(width_) * static_cast<size_t>(height_) * 4);
    make_current();
  }
  ~OsMesaContext() override { destroy_(context_); }
  void make_current() override {
    if (!make_current_(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_)) {
      throw std::runtime_error("OSMesaMakeCurrent failed");
    }
  }
  void* proc_address(const char* name) override { return reinterpret_cast<void*>(get_proc_(name)); }

 private:
  int width_, height_;
  void* library_ = nullptr;
  OSMesaContext (*create_)(GLenum, GLint, GLint, GLint, OSMesaContext) = nullptr;
  GLboolean (*make_current_)(OSMesaContext, void*, GLenum, GLsizei, GLsizei) = nullptr;
  void (*destroy_)(OSMesaContext) = nullptr;
  OSMESAproc (*get_proc_)(const char*) = nullptr;
  OSMesaContext context_ = nullptr;
  std::vector<unsigned char> buffer_;
};

class EglContext final : public GlContext {
 public:
  EglContext() {
    library_ = open_library("libEGL.so.1", "libegl1 libegl-mesa0");
    get_proc_ = symbol<PFNEGLGETPROCADDRESSPROC>(library_, "eglGetProcAddress");
    auto initialize = symbol<PFNEGLINITIALIZEPROC>(library_, "eglInitialize");
    auto bind_api = symbol<PFNEGLBINDAPIPROC>(library_, "eglBindAPI");
    auto choose_config = symbol<PFNEGLCHOOSECONFIGPROC>(library_, "eglChooseConfig");
    auto create_context = symbol<PFNEGLCREATECONTEXTPROC>(library_, "eglCreateContext");
    make_current_ = symbol<PFNEGLMAKECURRENTPROC>(library_, "eglMakeCurrent");
    destroy_context_ = symbol<PFNEGLDESTROYCONTEXTPROC>(library_, "eglDestroyContext");
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(get_proc_("eglGetPlatformDisplayEXT"));
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(get_proc_("eglQueryDevicesEXT"));
    if (get_platform_display == nullptr) throw std::runtime_error("EGL lacks eglGetPlatformDisplayEXT");
    // Prefer a GPU device; fall back to Mesa's surfaceless platform (llvmpipe on CPU-only machines).
    if (query_devices != nullptr && std::getenv("EGL_PLATFORM") == nullptr) {
      EGLDeviceEXT devices[8];
      EGLint count = 0;
      if (query_devices(8, devices, &count) && count > 0) {
        for (EGLint i = 0; i < count && display_ == EGL_NO_DISPLAY; ++i) {
          EGLDisplay candidate = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
          EGLint major = 0, minor = 0;
          if (candidate != EGL_NO_DISPLAY && initialize(candidate, &major, &minor)) display_ = candidate;
        }
      }
    }
    if (display_ == EGL_NO_DISPLAY) {
      EGLDisplay candidate = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      EGLint major = 0, minor = 0;
      if (candidate != EGL_NO_DISPLAY && initialize(candidate, &major, &minor)) display_ = candidate;
    }
    if (display_ == EGL_NO_DISPLAY) {
      throw std::runtime_error("EGL: no usable display (neither a GPU device nor Mesa's surfaceless platform)");
    }
    // MuJoCo draws into its own framebuffer object, so any OpenGL-capable config will do; prefer RGBA8 + depth.
    const EGLint rich[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_RED_SIZE, 8,
                           EGL_GREEN_SIZE,   8, EGL_BLUE_SIZE, 8, EGL_DEPTH_SIZE, 24, EGL_NONE};
    const EGLint pbuffer[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    const EGLint bare[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    for (const EGLint* attributes : {rich, pbuffer, bare}) {
      if (choose_config(display_, attributes, &config, 1, &configs) && configs > 0) break;
    }
    if (configs < 1) throw std::runtime_error("EGL: no OpenGL-renderable config on this display");
    if (!bind_api(EGL_OPENGL_API)) throw std::runtime_error("EGL: eglBindAPI(EGL_OPENGL_API) failed");
    context_ = create_context(display_, config, EGL_NO_CONTEXT, nullptr);
    if (context_ == EGL_NO_CONTEXT) throw std::runtime_error("EGL: eglCreateContext failed");
    make_current();
  }
  // The display stays initialised: EGL displays are per process, shared by every renderer of this thread pool.
  ~EglContext() override {
    make_current_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    destroy_context_(display_, context_);
  }
  void make_current() override {
    if (!make_current_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      throw std::runtime_error("EGL: eglMakeCurrent (surfaceless) failed");
    }
  }
  void* proc_address(const char* name) override { return reinterpret_cast<void*>(get_proc_(name)); }

 private:
  void* library_ = nullptr;
  PFNEGLGETPROCADDRESSPROC get_proc_ = nullptr;
  PFNEGLMAKECURRENTPROC make_current_ = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroy_context_ = nullptr;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

GlBackend gl_backend_from_name(std::string_view name) {
  GlBackend backend{};
  if (from_string(name, backend)) return backend;
  throw InputError("unknown GL backend '" + std::string(name) + "'", "gl", "osmesa, egl");
}

std::string_view gl_backend_name(GlBackend backend) { return to_string(backend); }

GlBackend default_gl_backend() {
  const char* env = std::getenv("MUJOCO_GL");
  if (env == nullptr || *env == '\0') return GlBackend::osmesa;
  return gl_backend_from_name(env);
}

VisualPreset visual_preset_from_name(std::string_view name) {
  VisualPreset preset{};
  if (from_string(name, preset)) return preset;
  throw InputError("unknown visual preset '" + std::string(name) + "'", "preset", "fast, pretty");
}

std::string_view visual_preset_name(VisualPreset preset) { return to_string(preset); }

double depth_buffer_to_metres(float buffer_value, double near_m, double far_m) {
  return near_m / (1.0 - static_cast<double>(buffer_value) * (1.0 - near_m / far_m));
}

struct Renderer::Impl {
  std::shared_ptr<const StageModel> stage_model;
  std::unique_ptr<GlContext> gl;
  mjModel* model = nullptr;  // private copy: its screen texture pixels are overwritten before upload
  mjvScene scene{};
  mjvOption option{};
  mjrContext context{};
  std::uint64_t uploaded_screen = 0;
  std::vector<unsigned char> rgb_buffer;
  std::vector<float> depth_buffer;

  ~Impl() {
    if (gl) {
      gl->make_current();
      mjr_freeContext(&context);
      mjv_freeScene(&scene);
    }
    if (model != nullptr) mj_deleteModel(model);
  }
};

Renderer::Renderer(std::shared_ptr<const StageModel> model, RendererOptions options)
    : impl_(std::make_unique<Impl>()), options_(options) {
  if (options.max_width < 1 || options.max_height < 1 || options.max_width > 8192 || options.max_height > 8192) {
    throw InputError("renderer size out of range", "max_width/max_height", "1 to 8192 px");
  }
  impl_->stage_model = std::move(model);
  impl_->model = mj_copyModel(nullptr, raw_model(*impl_->stage_model));
  mjModel* m = impl_->model;
  m->vis.global.offwidth = options.max_width;
  m->vis.global.offheight = options.max_height;
  m->vis.quality.offsamples = options.preset == VisualPreset::fast ? 0 : 4;
  if (options.preset == VisualPreset::fast) {  // coarser tessellation of spheres, capsules and ellipsoids
    m->vis.quality.numslices = 14;
    m->vis.quality.numstacks = 8;
    m->vis.quality.numquads = 1;
    const int floor = mj_name2id(m, mjOBJ_MATERIAL, "floor");  // plain floor: texturing a large area is costly
    if (floor >= 0) {
      m->mat_texid[floor] = -1;
      const float average_checker[4] = {0.69F, 0.63F, 0.55F, 1.0F};
      std::copy(average_checker, average_checker + 4, m->mat_rgba + 4 * floor);
    }
  }
  if (options.backend == GlBackend::osmesa) {
    impl_->gl = std::make_unique<OsMesaContext>(options.max_width, options.max_height);
  } else {
    impl_->gl = std::make_unique<EglContext>();
  }
  mjv_defaultOption(&impl_->option);
  for (int i = 0; i < mjNGROUP; ++i) impl_->option.sitegroup[i] = 0;
  mjv_defaultScene(&impl_->scene);
  mjv_makeScene(m, &impl_->scene, 2000);
  const bool pretty = options.preset == VisualPreset::pretty;
  impl_->scene.flags[mjRND_SHADOW] = pretty;
  impl_->scene.flags[mjRND_REFLECTION] = pretty;
  impl_->scene.flags[mjRND_SKYBOX] = pretty;
  mjr_defaultContext(&impl_->context);
  mjr_makeContext(m, &impl_->context, mjFONTSCALE_50);
  mjr_setBuffer(mjFB_OFFSCREEN, &impl_->context);
  if (impl_->context.currentBuffer != mjFB_OFFSCREEN) {
    throw std::runtime_error("MuJoCo could not select its off-screen framebuffer");
  }
  auto get_string = reinterpret_cast<GetStringFn>(impl_->gl->proc_address("glGetString"));
  const unsigned char* renderer = get_string != nullptr ? get_string(0x1F01 /* GL_RENDERER */) : nullptr;
  gl_renderer_ = renderer != nullptr ? reinterpret_cast<const char*>(renderer) : "unknown";
  spdlog::info("stage renderer: {} via {}, preset {}", gl_renderer_, gl_backend_name(options.backend),
               visual_preset_name(options.preset));
  impl_->rgb_buffer.resize(static_cast<size_t>(options.max_width) * static_cast<size_t>(options.max_height) * 3);
  impl_->depth_buffer.resize(static_cast<size_t>(options.max_width) * static_cast<size_t>(options.max_height));
}

Renderer::~Renderer() = default;

FramePack Renderer::render(const Stage& stage, std::string_view camera, const RenderRequest& request) {
  if (&stage.model() != impl_->stage_model.get()) {
    throw InputError("stage and renderer were made from different stage models", "stage");
  }
  const CameraSpec& spec = impl_->stage_model->camera(camera);
  if ((request.width == 0) != (request.height == 0) || request.width < 0 || request.height < 0) {
    throw InputError("give both width and height, or neither", "width/height", "positive pixel counts");
  }
  FramePack frame;
  frame.camera = spec.name;
  frame.K = request.width > 0 ? spec.color.scaled_to(request.width, request.height) : spec.color;
  frame.K_depth = request.width > 0 && spec.depth.width == spec.color.width ? frame.K : spec.depth;
  if (request.intrinsics) {
    const CameraIntrinsics& k = *request.intrinsics;
    if (k.width < 1 || k.height < 1 || !(k.fx > 0) || !(k.fy > 0) || std::abs(k.fx - k.fy) > 1e-9 * k.fx) {
      throw InputError("custom intrinsics need a positive size and fx = fy > 0 (square pixels)", "intrinsics");
    }
    frame.K = frame.K_depth = k;
  }
  for (const CameraIntrinsics* k : {&frame.K, &frame.K_depth}) {
    if (k->width > options_.max_width || k->height > options_.max_height) {
      throw InputError(fmt::format("image {}x{} exceeds this renderer's {}x{}", k->width, k->height,
                                   options_.max_width, options_.max_height),
                       "width/height", fmt::format("up to {}x{}", options_.max_width, options_.max_height));
    }
  }
  frame.sandtray_T_camera_optical = camera_optical_pose(raw_model(stage.model()), raw_data(stage), spec.camera_id);
  frame.stamp = stage.time();

  impl_->gl->make_current();
  mjModel* m = impl_->model;
  if (impl_->uploaded_screen != stage.screen_version()) {
    const int tex = impl_->stage_model->screen_texture();
    const cv::Mat& pixels = stage.screen_texture();
    std::memcpy(m->tex_rgb + m->tex_adr[tex], pixels.data, pixels.total() * pixels.elemSize());
    mjr_uploadTexture(m, &impl_->context, tex);
    impl_->uploaded_screen = stage.screen_version();
  }
  mjvCamera cam;
  mjv_defaultCamera(&cam);
  cam.type = mjCAMERA_FIXED;
  cam.fixedcamid = spec.camera_id;
  // mjv_updateScene only reads mjData; the API takes a non-const pointer.
  mjv_updateScene(m, const_cast<mjData*>(raw_data(stage)), &impl_->option, nullptr, &cam, mjCAT_ALL, &impl_->scene);
  const double near_m = static_cast<double>(m->vis.map.znear) * m->stat.extent;
  const double far_m = static_cast<double>(m->vis.map.zfar) * m->stat.extent;

  auto draw = [&](const CameraIntrinsics& k, cv::Mat* rgb_out, cv::Mat* depth_out) {
    // An off-centre pinhole: set the frustum from the intrinsics instead of MuJoCo's symmetric fovy.
    for (auto& gl_camera : impl_->scene.camera) {
      gl_camera.frustum_near = static_cast<float>(near_m);
      gl_camera.frustum_far = static_cast<float>(far_m);
      gl_camera.frustum_top = static_cast<float>(near_m * (k.cy + 0.5) / k.fy);
      gl_camera.frustum_bottom = static_cast<float>(-near_m * (k.height - 0.5 - k.cy) / k.fy);
      gl_camera.frustum_center = static_cast<float>(near_m * (0.5 * (k.width - 1) - k.cx) / k.fx);
    }
    const mjrRect viewport{0, 0, k.width, k.height};
    mjr_render(viewport, &impl_->scene, &impl_->context);
    mjr_readPixels(rgb_out != nullptr ? impl_->rgb_buffer.data() : nullptr,
                   depth_out != nullptr ? impl_->depth_buffer.data() : nullptr, viewport, &impl_->context);
    if (rgb_out != nullptr) {
      const cv::Mat upside_down(k.height, k.width, CV_8UC3, impl_->rgb_buffer.data());
      cv::flip(upside_down, *rgb_out, 0);
    }
    if (depth_out != nullptr) {
      depth_out->create(k.height, k.width, CV_32FC1);
      for (int row = 0; row < k.height; ++row) {
        const float* src = impl_->depth_buffer.data() + static_cast<size_t>(k.height - 1 - row) * k.width;
        float* dst = depth_out->ptr<float>(row);
        for (int col = 0; col < k.width; ++col) {
          dst[col] = static_cast<float>(depth_buffer_to_metres(src[col], near_m, far_m));
        }
      }
    }
  };
  const bool same_view = frame.K.width == frame.K_depth.width && frame.K.height == frame.K_depth.height &&
                         frame.K.fx == frame.K_depth.fx && frame.K.cx == frame.K_depth.cx &&
                         frame.K.cy == frame.K_depth.cy;
  if (request.rgb && request.depth && same_view) {
    draw(frame.K, &frame.rgb, &frame.depth_m);
  } else {
    if (request.rgb) draw(frame.K, &frame.rgb, nullptr);
    if (request.depth) draw(frame.K_depth, nullptr, &frame.depth_m);
  }
  return frame;
}

}  // namespace freeplay::stage
