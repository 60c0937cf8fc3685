// The stage scene: cameras at the real poses, children seated by age, configuration errors.

#include <gtest/gtest.h>

#include <cmath>

#include "freeplay/core/error.hpp"
#include "freeplay/stage/camera_names.hpp"
#include "freeplay/stage/stage.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {
namespace {

TEST(StageModel, SceneKindsListTheirBodiesAndCameras) {
  StageConfig config;
  const auto child_child = StageModel::create(config);
  EXPECT_TRUE(child_child->avatar(ChildRole::purple).present);
  EXPECT_TRUE(child_child->avatar(ChildRole::yellow).present);
  EXPECT_FALSE(child_child->nao().present);
  EXPECT_THROW(child_child->camera("CameraTop"), InputError);
  config.scene = SceneKind::child_robot;
  const auto child_robot = StageModel::create(config);
  EXPECT_TRUE(child_robot->avatar(ChildRole::purple).present);
  EXPECT_FALSE(child_robot->avatar(ChildRole::yellow).present);
  EXPECT_TRUE(child_robot->nao().present);
  for (const char* name : {"camera_purple", "camera_yellow", "env_camera", "CameraTop", "CameraBottom"}) {
    EXPECT_NO_THROW(child_robot->camera(name)) << name;
  }
}

TEST(StageModel, TheCameraNameListsAreTheModelsCameras) {
  // camera_names.hpp is what the parser, the recorder and the help list: it must name the model's cameras, in order.
  const auto names_of = [](const StageModel& model) {
    std::vector<std::string> names;
    for (const auto& camera : model.cameras()) names.push_back(camera.name);
    return names;
  };
  StageConfig config;
  std::vector<std::string> room(kRoomCameraNames.begin(), kRoomCameraNames.end());
  room.emplace_back(kTopViewCameraName);
  EXPECT_EQ(names_of(*StageModel::create(config)), room);
  config.scene = SceneKind::child_robot;
  std::vector<std::string> real = real_camera_names();
  real.emplace_back(kTopViewCameraName);
  EXPECT_EQ(names_of(*StageModel::create(config)), real);
  EXPECT_EQ(real_camera_names(),
            (std::vector<std::string>{"camera_purple", "camera_yellow", "env_camera", "CameraTop", "CameraBottom"}));
  EXPECT_TRUE(is_nao_camera("CameraBottom"));
  EXPECT_FALSE(is_nao_camera("env_camera"));
}

TEST(StageModel, SensorIntrinsicsAreThePublishedOnes) {
  const auto model = StageModel::create({});
  const CameraSpec& purple = model->camera("camera_purple");
  EXPECT_EQ(purple.color.width, 960);
  EXPECT_EQ(purple.color.height, 540);
  EXPECT_DOUBLE_EQ(purple.color.fx, 697.811);
  EXPECT_DOUBLE_EQ(purple.color.fy, 697.811);
  EXPECT_DOUBLE_EQ(purple.color.cx, 479.047);
  EXPECT_DOUBLE_EQ(purple.color.cy, 261.227);
  EXPECT_EQ(purple.depth.width, 640);
  EXPECT_EQ(purple.depth.height, 480);
  EXPECT_EQ(model->camera("env_camera").color.width, 960);
}

TEST(StageModel, CamerasSitAtTheSandtrayXacroPoses) {
  const Stage stage(StageModel::create({}));
  const Eigen::Isometry3d purple = stage.camera_pose("camera_purple");
  EXPECT_TRUE(purple.translation().isApprox(Eigen::Vector3d(-0.108, 0.021, 0.035), 1e-9));
  // optical axis = link x: yaw -45°, pitched 20° up (URDF pitch -0.349)
  const Eigen::Vector3d axis = purple.linear().col(2);
  EXPECT_NEAR(std::atan2(axis.y(), axis.x()), -0.785, 1e-6);
  EXPECT_NEAR(std::asin(axis.z()), 0.349, 1e-6);
  const Eigen::Isometry3d yellow = stage.camera_pose("camera_yellow");
  EXPECT_TRUE(yellow.translation().isApprox(Eigen::Vector3d(-0.108, -0.377, 0.035), 1e-9));
  const Eigen::Isometry3d env = stage.camera_pose("env_camera");
  EXPECT_TRUE(env.translation().isApprox(Eigen::Vector3d(1.4, -0.15, 0.52), 1e-9));
  EXPECT_NEAR(std::asin(-env.linear().col(2).z()), 0.29, 1e-6);
  // optical frames: y points down in the image, so it has a negative world z component for level cameras
  EXPECT_LT(env.linear().col(1).z(), 0.0);
}

TEST(StageModel, OpticalFramesMatchThePinsoroDatasetQuaternions) {
  // dataset data/README.md: optical frames relative to sandtray_centre (same axes as sandtray), (x, y, z, w)
  const Stage stage(StageModel::create({}));
  const Eigen::Quaterniond purple(stage.camera_pose("camera_purple").linear());
  const Eigen::Quaterniond yellow(stage.camera_pose("camera_yellow").linear());
  EXPECT_NEAR(std::abs(purple.coeffs().dot(Eigen::Vector4d(0.220, -0.530, 0.757, -0.314))), 1.0, 1e-3);
  EXPECT_NEAR(std::abs(yellow.coeffs().dot(Eigen::Vector4d(-0.530, 0.220, -0.314, 0.757))), 1.0, 1e-3);
}

TEST(StageModel, EachSr300FacesItsChildAcrossTheTable) {
  const Stage stage(StageModel::create({}));
  for (ChildRole role : {ChildRole::purple, ChildRole::yellow}) {
    const std::string name = "camera_" + std::string(child_role_name(role));
    const Eigen::Isometry3d camera = stage.camera_pose(name);
    const Eigen::Vector3d eyes = stage.site_position(stage.model().avatar(role).eyes_site);
    const Eigen::Vector3d in_camera = camera.inverse() * eyes;
    const CameraIntrinsics& k = stage.model().camera(name).color;
    const double u = k.fx * in_camera.x() / in_camera.z() + k.cx;
    const double v = k.fy * in_camera.y() / in_camera.z() + k.cy;
    EXPECT_GT(in_camera.z(), 0.3) << name;
    EXPECT_GT(u, 0.15 * k.width) << name;
    EXPECT_LT(u, 0.85 * k.width) << name;
    EXPECT_GT(v, 0.0) << name;
    EXPECT_LT(v, k.height) << name;
  }
}

TEST(StageModel, ChildrenSitOnOppositeLongSidesFacingEachOther) {
  const auto model = StageModel::create({});
  const auto& purple = model->avatar(ChildRole::purple).sandtray_T_base;
  const auto& yellow = model->avatar(ChildRole::yellow).sandtray_T_base;
  EXPECT_LT(purple.translation().y(), SandtrayGeometry::bezel_min_y);
  EXPECT_GT(yellow.translation().y(), SandtrayGeometry::bezel_max_y);
  EXPECT_NEAR(purple.linear().col(0).dot(yellow.linear().col(0)), -1.0, 1e-9);
  EXPECT_GT(purple.linear().col(0).y(), 0.99);  // purple faces +y (the table)
}

TEST(StageModel, ChildDimensionsComeFromTheAgeTable) {
  const ChildDimensions seven = child_dimensions(7.0);
  EXPECT_NEAR(seven.stature, 1.219, 1e-9);
  EXPECT_NEAR(seven.sitting_height, 0.670, 1e-9);
  EXPECT_NEAR(seven.shoulder_height, 0.416, 1e-9);
  const ChildDimensions between = child_dimensions(6.5);
  EXPECT_NEAR(between.sitting_height, 0.655, 1e-9);
  EXPECT_NEAR(child_dimensions(4.0).stature, 1.018, 1e-9);
  EXPECT_NEAR(child_dimensions(8.0).stature, 1.279, 1e-9);
  EXPECT_THROW(child_dimensions(3.9), InputError);
  EXPECT_THROW(child_dimensions(std::nan("")), InputError);
  StageConfig config;
  config.child_age_years = 9;
  EXPECT_THROW(StageModel model(config), InputError);
}

TEST(StageModel, OlderChildrenSitTaller) {
  StageConfig config;
  config.child_age_years = 4;
  const Stage young(StageModel::create(config));
  config.child_age_years = 8;
  const Stage old(StageModel::create(config));
  // the neck pivot sits 4 cm above the acromion; both children lean by the same rest angle
  auto neck_height = [](const Stage& stage) {
    const int head = raw_model(stage.model())->site_bodyid[stage.model().avatar(ChildRole::purple).eyes_site];
    return raw_data(stage)->xpos[3 * head + 2];
  };
  EXPECT_NEAR(neck_height(old) - neck_height(young), std::cos(0.1) * (0.432 - 0.356), 0.002);
}

TEST(StageModel, NamesParseAndRejectUnknownValues) {
  EXPECT_EQ(scene_kind_from_name("child-robot"), SceneKind::child_robot);
  EXPECT_EQ(scene_kind_from_name("child-child"), SceneKind::child_child);
  try {
    scene_kind_from_name("robot-robot");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.allowed(), "child-child, child-robot");
  }
}

TEST(Stage, ScreenImageIsResampledToTheTexture) {
  Stage stage(StageModel::create({}));
  const auto before = stage.screen_version();
  cv::Mat image(100, 200, CV_8UC3, cv::Scalar(255, 0, 0));  // pure blue, BGR
  stage.set_screen_image(image);
  EXPECT_NE(stage.screen_version(), before);
  const cv::Mat& texture = stage.screen_texture();
  EXPECT_EQ(texture.cols, 1024);
  EXPECT_EQ(texture.rows, 572);
  const cv::Vec3b pixel = texture.at<cv::Vec3b>(10, 10);
  EXPECT_EQ(pixel[0], 0);    // R
  EXPECT_EQ(pixel[2], 255);  // B
  EXPECT_THROW(stage.set_screen_image(cv::Mat()), InputError);
  EXPECT_THROW(stage.set_screen_image(cv::Mat(10, 10, CV_32FC3)), InputError);
}

}  // namespace
}  // namespace freeplay::stage
