// EGL rendering (GPU device, or Mesa's surfaceless llvmpipe): same pictures as OSMesa's contract.

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "freeplay/stage/renderer.hpp"

// Mesa keeps a few small allocations of its GL contexts until exit (OSMesaMakeCurrent, EGL drivers): not ours.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\nleak:libEGL_mesa.so\nleak:libgallium\nleak:libGLdispatch.so\nleak:libubsan.so\n";
}

namespace freeplay::stage {
namespace {

TEST(EglRenderer, RendersDepthAndColourWhenEglIsAvailable) {
  const auto model = StageModel::create({});
  std::unique_ptr<Renderer> renderer;
  try {
    renderer = std::make_unique<Renderer>(model, RendererOptions{GlBackend::egl, VisualPreset::fast, 1280, 960});
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "EGL unavailable here: " << e.what();
  }
  EXPECT_FALSE(renderer->gl_renderer().empty());
  Stage stage(model);
  RenderRequest request;
  request.depth = true;
  const FramePack frame = renderer->render(stage, "top_view", request);
  ASSERT_EQ(frame.rgb.cols, 960);
  const float centre = frame.depth_m.at<float>(frame.depth_m.rows / 2, frame.depth_m.cols / 2);
  EXPECT_NEAR(centre, 0.9, 0.01);  // top_view hangs 0.9 m above the screen
  const cv::Scalar mean = cv::mean(frame.rgb(cv::Rect(460, 250, 40, 40)));
  EXPECT_GT(mean[1], mean[0]);  // the default screen texture is green
}

}  // namespace
}  // namespace freeplay::stage
