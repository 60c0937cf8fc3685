// The localisation node's logic on synthetic camera views (the screen picture warped through a pinhole, no GL):
// a search per signal, "I know where I am now!" and a held odom→sandtray on success, "I am lost!" after 5 s
// without markers, and the arm-reach frame.

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "freeplay/localisation/localiser.hpp"

namespace freeplay::localisation {
namespace {

const Pinhole kCamera{544.0, 544.0, 319.5, 239.5};

/// A camera 0.55 m above the screen centre, tilted, seeing the screen (the `sandtray` frame) in its image.
Eigen::Isometry3d camera_T_sandtray_view(double tilt_rad) {
  Eigen::Isometry3d sandtray_T_camera = Eigen::Isometry3d::Identity();
  sandtray_T_camera.translation() = Eigen::Vector3d(0.30, 0.05, 0.55);
  // optical z looks down (−z of sandtray), x along sandtray x, then tilted about x towards the screen
  sandtray_T_camera.linear() = (Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()) *
                                Eigen::AngleAxisd(tilt_rad, Eigen::Vector3d::UnitX())).toRotationMatrix();
  return sandtray_T_camera.inverse();
}

/// The camera image of a 1920 × 1072 screen picture (grey), by the plane's homography.
cv::Mat view_of(const cv::Mat& screen, const Eigen::Isometry3d& camera_T_sandtray) {
  const double s = screen.cols / 0.600;  // px per metre; pixel centres at (x·s − 0.5, −y·s − 0.5)
  Eigen::Matrix3d screen_to_sandtray;
  screen_to_sandtray << 1 / s, 0, 0.5 / s, 0, -1 / s, -0.5 / s, 0, 0, 1;
  Eigen::Matrix3d K;
  K << kCamera.fx, 0, kCamera.cx, 0, kCamera.fy, kCamera.cy, 0, 0, 1;
  Eigen::Matrix3d plane;
  plane.col(0) = camera_T_sandtray.linear().col(0);
  plane.col(1) = camera_T_sandtray.linear().col(1);
  plane.col(2) = camera_T_sandtray.translation();
  const Eigen::Matrix3d H = K * plane * screen_to_sandtray;
  cv::Matx33d h;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) h(r, c) = H(r, c);
  }
  cv::Mat image;
  cv::warpPerspective(screen, image, h, cv::Size(640, 480), cv::INTER_AREA, cv::BORDER_CONSTANT, cv::Scalar(40));
  return image;
}

cv::Mat screen_picture(bool markers) {
  cv::Mat screen(1072, 1920, CV_8UC1, cv::Scalar(150));
  if (markers) draw_marker_field(screen);
  return screen;
}

Eigen::Isometry3d odom_T_camera_example() {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.1, 0.02, 0.5);
  pose.linear() = Eigen::AngleAxisd(-1.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return pose;
}

TEST(Localiser, FramesBeforeASignalAreIgnored) {
  Localiser localiser;
  const auto camera_T_sandtray = camera_T_sandtray_view(-0.35);
  EXPECT_FALSE(localiser.on_frame(0.0, view_of(screen_picture(true), camera_T_sandtray), kCamera,
                                  odom_T_camera_example()));
  EXPECT_FALSE(localiser.odom_T_sandtray().has_value());
  EXPECT_TRUE(localiser.take_speech().empty());
}

TEST(Localiser, FindsTheFieldComputesOdomToSandtrayOnceAndHoldsIt) {
  Localiser localiser;
  const auto camera_T_sandtray = camera_T_sandtray_view(-0.35);
  const auto odom_T_camera = odom_T_camera_example();
  localiser.on_signal(1.0);
  EXPECT_TRUE(localiser.looking());
  ASSERT_TRUE(localiser.on_frame(1.1, view_of(screen_picture(true), camera_T_sandtray), kCamera, odom_T_camera));
  EXPECT_FALSE(localiser.looking());
  EXPECT_EQ(localiser.last_fit()->ids.size(), 15U);
  const auto e = pose_error(*localiser.odom_T_sandtray(), odom_T_camera * camera_T_sandtray);
  EXPECT_LT(e.translation_m, 0.002);
  EXPECT_LT(e.rotation_deg, 0.3);
  EXPECT_EQ(localiser.take_speech(), std::vector<std::string>{"I know where I am now!"});
  // Held: later frames (the robot moved, the markers are still up) change nothing until the next signal.
  const Eigen::Isometry3d held = *localiser.odom_T_sandtray();
  Eigen::Isometry3d moved = odom_T_camera;
  moved.translation().x() += 0.2;
  EXPECT_FALSE(localiser.on_frame(1.2, view_of(screen_picture(true), camera_T_sandtray), kCamera, moved));
  localiser.tick(30.0);
  EXPECT_TRUE(localiser.odom_T_sandtray()->isApprox(held, 1e-15));
  EXPECT_TRUE(localiser.take_speech().empty());
  // A new signal re-localises, as re-tapping the real screen did.
  localiser.on_signal(40.0);
  ASSERT_TRUE(localiser.on_frame(40.1, view_of(screen_picture(true), camera_T_sandtray), kCamera, moved));
  EXPECT_NEAR((localiser.odom_T_sandtray()->translation() - held.translation()).norm(), 0.2, 0.003);
  EXPECT_EQ(localiser.successes(), 2);
}

TEST(Localiser, SaysIAmLostAfterFiveSecondsWithoutMarkersAndKeepsWhatItHad) {
  Localiser localiser;
  const auto camera_T_sandtray = camera_T_sandtray_view(-0.35);
  localiser.on_signal(0.0);
  for (int k = 1; k < 50; ++k) {  // the game without its marker field, at the real node's 0.1 s steps
    EXPECT_FALSE(localiser.on_frame(0.1 * k, view_of(screen_picture(false), camera_T_sandtray), kCamera,
                                    odom_T_camera_example()));
  }
  EXPECT_TRUE(localiser.looking());
  EXPECT_TRUE(localiser.take_speech().empty());
  localiser.tick(5.0);
  EXPECT_FALSE(localiser.looking());
  EXPECT_EQ(localiser.take_speech(), std::vector<std::string>{"I am lost!"});
  EXPECT_FALSE(localiser.odom_T_sandtray().has_value());
  EXPECT_EQ(localiser.failures(), 1);
  // A later success, then a failed search: the fix stays.
  localiser.on_signal(10.0);
  ASSERT_TRUE(localiser.on_frame(10.1, view_of(screen_picture(true), camera_T_sandtray), kCamera,
                                 odom_T_camera_example()));
  const Eigen::Isometry3d held = *localiser.odom_T_sandtray();
  localiser.on_signal(20.0);
  localiser.tick(25.0);
  EXPECT_TRUE(localiser.odom_T_sandtray()->isApprox(held, 1e-15));
  EXPECT_EQ(localiser.take_speech(), (std::vector<std::string>{"I know where I am now!", "I am lost!"}));
}

TEST(Localiser, ArmReachIsTheShoulderOnTheScreenWithTheDiscRadiusAsZ) {
  LocaliserSettings settings;
  settings.arm_reach_m = 0.5;
  Localiser localiser(settings);
  const auto camera_T_sandtray = camera_T_sandtray_view(-0.35);
  const auto odom_T_camera = odom_T_camera_example();
  Eigen::Isometry3d sandtray_T_shoulder = Eigen::Isometry3d::Identity();
  sandtray_T_shoulder.translation() = Eigen::Vector3d(0.25, 0.10, 0.30);
  const Eigen::Isometry3d odom_T_sandtray_truth = odom_T_camera * camera_T_sandtray;
  EXPECT_FALSE(localiser.arm_reach(odom_T_sandtray_truth * sandtray_T_shoulder).has_value());  // not localised
  localiser.on_signal(0.0);
  ASSERT_TRUE(localiser.on_frame(0.1, view_of(screen_picture(true), camera_T_sandtray), kCamera, odom_T_camera));
  const auto reach = localiser.arm_reach(odom_T_sandtray_truth * sandtray_T_shoulder);
  ASSERT_TRUE(reach.has_value());
  EXPECT_NEAR(reach->translation.x(), 0.25, 0.003);
  EXPECT_NEAR(reach->translation.y(), 0.10, 0.003);
  EXPECT_NEAR(reach->translation.z(), 0.4, 0.003);  // √(0.5² − 0.3²)
  sandtray_T_shoulder.translation().z() = 0.6;  // "Too high!": no frame
  EXPECT_FALSE(localiser.arm_reach(odom_T_sandtray_truth * sandtray_T_shoulder).has_value());

  settings.broadcast_arm_reach = false;
  Localiser quiet(settings);
  quiet.on_signal(0.0);
  ASSERT_TRUE(quiet.on_frame(0.1, view_of(screen_picture(true), camera_T_sandtray), kCamera, odom_T_camera));
  EXPECT_FALSE(quiet.arm_reach(odom_T_sandtray_truth * sandtray_T_shoulder).has_value());
}

}  // namespace
}  // namespace freeplay::localisation
