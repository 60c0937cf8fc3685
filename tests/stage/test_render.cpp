// Off-screen rendering (OSMesa): geometry lands where the calibration says, the screen texture updates,
// depth is metric, renders repeat exactly.

#include <gtest/gtest.h>

#include <array>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "freeplay/core/error.hpp"
#include "freeplay/stage/avatar_controller.hpp"
#include "freeplay/stage/renderer.hpp"
#include "raw_mujoco.hpp"

// Mesa keeps a few small allocations of its GL contexts until exit (OSMesaMakeCurrent, EGL drivers): not ours.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\nleak:libEGL_mesa.so\nleak:libgallium\nleak:libGLdispatch.so\nleak:libubsan.so\n";
}

namespace freeplay::stage {
namespace {

class RenderTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = StageModel::create({});
    renderer_ = std::make_unique<Renderer>(model_, RendererOptions{GlBackend::osmesa, VisualPreset::fast, 1280, 960});
  }
  static void TearDownTestSuite() {
    renderer_.reset();
    model_.reset();
  }
  static Eigen::Vector2d project(const FramePack& frame, const Eigen::Vector3d& point, const CameraIntrinsics& k) {
    const Eigen::Vector3d p = frame.sandtray_T_camera_optical.inverse() * point;
    return {k.fx * p.x() / p.z() + k.cx, k.fy * p.y() / p.z() + k.cy};
  }
  static std::shared_ptr<const StageModel> model_;
  static std::unique_ptr<Renderer> renderer_;
};

std::shared_ptr<const StageModel> RenderTest::model_;
std::unique_ptr<Renderer> RenderTest::renderer_;

cv::Vec3d mean_colour(const cv::Mat& rgb, const Eigen::Vector2d& centre, int half) {
  const cv::Rect box(static_cast<int>(std::lround(centre.x())) - half, static_cast<int>(std::lround(centre.y())) - half,
                     2 * half + 1, 2 * half + 1);
  const cv::Scalar mean = cv::mean(rgb(box & cv::Rect(0, 0, rgb.cols, rgb.rows)));
  return {mean[0], mean[1], mean[2]};
}

TEST_F(RenderTest, ReportsTheGlRendererAndTheCalibration) {
  EXPECT_FALSE(renderer_->gl_renderer().empty());
  EXPECT_NE(renderer_->gl_renderer(), "unknown");
  Stage stage(model_);
  const FramePack frame = renderer_->render(stage, "camera_purple");
  EXPECT_EQ(frame.rgb.cols, 960);
  EXPECT_EQ(frame.rgb.rows, 540);
  EXPECT_EQ(frame.rgb.type(), CV_8UC3);
  EXPECT_TRUE(frame.depth_m.empty());
  EXPECT_DOUBLE_EQ(frame.K.cx, 479.047);
  EXPECT_TRUE(frame.sandtray_T_camera_optical.translation().isApprox(Eigen::Vector3d(-0.108, 0.021, 0.035), 1e-9));
  EXPECT_EQ(frame.camera, "camera_purple");
  EXPECT_THROW(renderer_->render(stage, "kinect"), InputError);
  EXPECT_THROW(renderer_->render(stage, "env_camera", {true, false, 4000, 3000, std::nullopt}), InputError);
}

TEST_F(RenderTest, PurpleBibAppearsInCameraPurpleWhereTheGeometrySays) {
  Stage stage(model_);
  const FramePack frame = renderer_->render(stage, "camera_purple");
  const int bib = model_->avatar(ChildRole::purple).bib_geom;
  const Eigen::Vector3d centre = Eigen::Map<const Eigen::Vector3d>(raw_data(stage)->geom_xpos + 3 * bib);
  // the upper chest (above the resting hands), stepped from the bib's centre towards the camera
  const Eigen::Vector3d towards = (frame.sandtray_T_camera_optical.translation() - centre).normalized();
  const Eigen::Vector2d pixel = project(frame, centre + 0.09 * Eigen::Vector3d::UnitZ() + 0.05 * towards, frame.K);
  ASSERT_GT(pixel.x(), 10);
  ASSERT_LT(pixel.x(), 950);
  ASSERT_GT(pixel.y(), 10);
  ASSERT_LT(pixel.y(), 530);
  const cv::Vec3d colour = mean_colour(frame.rgb, pixel, 4);
  EXPECT_GT(colour[0], colour[1] + 40) << colour;  // red over green
  EXPECT_GT(colour[2], colour[1] + 40) << colour;  // blue over green: purple
  // and the yellow bib is in camera_yellow
  const FramePack yellow = renderer_->render(stage, "camera_yellow");
  const int yellow_bib = model_->avatar(ChildRole::yellow).bib_geom;
  const Eigen::Vector3d yellow_centre = Eigen::Map<const Eigen::Vector3d>(raw_data(stage)->geom_xpos + 3 * yellow_bib);
  const Eigen::Vector3d yellow_towards = (yellow.sandtray_T_camera_optical.translation() - yellow_centre).normalized();
  const cv::Vec3d yellow_colour = mean_colour(yellow.rgb, project(yellow, yellow_centre + 0.09 * Eigen::Vector3d::UnitZ() + 0.05 * yellow_towards, yellow.K), 4);
  EXPECT_GT(yellow_colour[0], yellow_colour[2] + 60) << yellow_colour;
  EXPECT_GT(yellow_colour[1], yellow_colour[2] + 60) << yellow_colour;
}

TEST_F(RenderTest, AnOffCentrePrincipalPointShiftsTheImageExactly) {
  Stage stage(model_);
  stage.set_screen_image(demo_screen_image(1920, 1080));  // red 120 px marker at the top-left corner
  const CameraIntrinsics centred = model_->camera("top_view").color;
  CameraIntrinsics shifted = centred;
  shifted.cx += 40;
  shifted.cy -= 30;
  auto marker_centroid = [&](const CameraIntrinsics& k, FramePack* out) {
    RenderRequest request;
    request.intrinsics = k;
    *out = renderer_->render(stage, "top_view", request);
    cv::Mat mask;
    cv::inRange(out->rgb, cv::Scalar(180, 0, 0), cv::Scalar(255, 60, 60), mask);
    const cv::Moments m = cv::moments(mask, true);
    EXPECT_GT(m.m00, 100);
    return Eigen::Vector2d(m.m10 / m.m00, m.m01 / m.m00);
  };
  FramePack a, b;
  const Eigen::Vector2d pa = marker_centroid(centred, &a);
  const Eigen::Vector2d pb = marker_centroid(shifted, &b);
  EXPECT_NEAR(pb.x() - pa.x(), 40.0, 0.5);
  EXPECT_NEAR(pb.y() - pa.y(), -30.0, 0.5);
  const double side = 0.600 * 120.0 / 1920.0;  // the marker's size on the screen (m)
  const Eigen::Vector2d expected = project(a, Eigen::Vector3d(0.5 * side, -0.5 * side, 0.0), centred);
  EXPECT_NEAR(pa.x(), expected.x(), 1.0);
  EXPECT_NEAR(pa.y(), expected.y(), 1.0);
}

TEST_F(RenderTest, AScreenChangeChangesTheEnvCameraImageOnTheScreenOnly) {
  Stage stage(model_);
  stage.set_screen_image(demo_screen_image(960, 540));
  const FramePack before = renderer_->render(stage, "env_camera");
  stage.set_screen_image(cv::Mat(540, 960, CV_8UC3, cv::Scalar(255, 0, 255)));
  const FramePack after = renderer_->render(stage, "env_camera");
  cv::Mat difference, changed;
  cv::absdiff(before.rgb, after.rgb, difference);
  cv::cvtColor(difference, difference, cv::COLOR_RGB2GRAY);
  cv::threshold(difference, changed, 20, 255, cv::THRESH_BINARY);
  std::vector<cv::Point> screen;
  for (const Eigen::Vector3d& corner : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.6, 0, 0),
                                       Eigen::Vector3d(0.6, -0.335, 0), Eigen::Vector3d(0, -0.335, 0)}) {
    const Eigen::Vector2d p = project(before, corner, before.K);
    screen.emplace_back(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
  }
  cv::Mat inside = cv::Mat::zeros(changed.size(), CV_8UC1);
  cv::fillConvexPoly(inside, screen, cv::Scalar(255));
  cv::Mat grown;
  cv::dilate(inside, grown, cv::Mat(), cv::Point(-1, -1), 3);
  const int changed_inside = cv::countNonZero(changed & inside);
  const int changed_outside = cv::countNonZero(changed & ~grown);
  EXPECT_GT(changed_inside, cv::countNonZero(inside) / 3);
  EXPECT_EQ(changed_outside, 0);
}

TEST_F(RenderTest, DepthAtTheScreenCentreMatchesTheGeometry) {
  Stage stage(model_);
  for (const char* camera : {"env_camera", "top_view"}) {
    RenderRequest request;
    request.rgb = false;
    request.depth = true;
    const FramePack frame = renderer_->render(stage, camera, request);
    ASSERT_EQ(frame.depth_m.type(), CV_32FC1);
    const Eigen::Vector3d centre(0.3, -0.1675, 0.0);
    const Eigen::Vector2d pixel = project(frame, centre, frame.K_depth);
    const double expected = (frame.sandtray_T_camera_optical.inverse() * centre).z();
    const float measured = frame.depth_m.at<float>(static_cast<int>(std::lround(pixel.y())),
                                                   static_cast<int>(std::lround(pixel.x())));
    EXPECT_NEAR(measured, expected, 0.01) << camera;
  }
  // SR300 depth comes at its own 640×480 resolution
  RenderRequest both;
  both.depth = true;
  const FramePack purple = renderer_->render(stage, "camera_purple", both);
  EXPECT_EQ(purple.rgb.cols, 960);
  EXPECT_EQ(purple.depth_m.cols, 640);
  EXPECT_EQ(purple.depth_m.rows, 480);
}

TEST_F(RenderTest, TwoRendersOfTheSameStateAgreeWithinOne) {
  Stage stage(model_);
  AvatarController(stage, ChildRole::purple).touch({0.3, -0.25});
  stage.update_kinematics();
  const FramePack first = renderer_->render(stage, "env_camera");
  const FramePack second = renderer_->render(stage, "env_camera");
  cv::Mat difference;
  cv::absdiff(first.rgb, second.rgb, difference);
  double largest = 0;
  cv::minMaxLoc(difference.reshape(1), nullptr, &largest);
  EXPECT_LE(largest, 1.0);
  // a second renderer (fresh context) agrees too
  Renderer other(model_);
  const FramePack third = other.render(stage, "env_camera");
  cv::absdiff(first.rgb, third.rgb, difference);
  cv::minMaxLoc(difference.reshape(1), nullptr, &largest);
  EXPECT_LE(largest, 1.0);
}

TEST_F(RenderTest, ResolutionOverrideScalesTheIntrinsics) {
  Stage stage(model_);
  RenderRequest request;
  request.width = 480;
  request.height = 270;
  const FramePack frame = renderer_->render(stage, "camera_purple", request);
  EXPECT_EQ(frame.rgb.cols, 480);
  EXPECT_NEAR(frame.K.fx, 697.811 / 2, 1e-9);
  EXPECT_NEAR(frame.K.cx, (479.047 + 0.5) / 2 - 0.5, 1e-9);
  request.height = 0;
  EXPECT_THROW(renderer_->render(stage, "camera_purple", request), InputError);
}

TEST(RendererThreads, OneRendererPerThreadRendersTheSameImage) {
  const auto model = StageModel::create({});
  const Stage stage(model);
  std::array<cv::Mat, 2> images;
  std::array<std::thread, 2> threads;
  for (size_t i = 0; i < threads.size(); ++i) {
    threads[i] = std::thread([&, i] {
      Renderer renderer(model, RendererOptions{GlBackend::osmesa, VisualPreset::fast, 960, 540});
      images[i] = renderer.render(stage, "camera_yellow").rgb;
    });
  }
  for (auto& thread : threads) thread.join();
  cv::Mat difference;
  cv::absdiff(images[0], images[1], difference);
  double largest = 0;
  cv::minMaxLoc(difference.reshape(1), nullptr, &largest);
  EXPECT_LE(largest, 1.0);
}

TEST(RendererNames, ParseAndReject) {
  EXPECT_EQ(gl_backend_from_name("egl"), GlBackend::egl);
  EXPECT_EQ(visual_preset_from_name("pretty"), VisualPreset::pretty);
  EXPECT_THROW(gl_backend_from_name("glx"), InputError);
  EXPECT_THROW(visual_preset_from_name("ultra"), InputError);
  EXPECT_NEAR(depth_buffer_to_metres(0.0F, 0.02, 50.0), 0.02, 1e-12);
  EXPECT_NEAR(depth_buffer_to_metres(1.0F, 0.02, 50.0), 50.0, 1e-9);
}

}  // namespace
}  // namespace freeplay::stage
