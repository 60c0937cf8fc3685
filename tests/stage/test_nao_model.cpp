// The NAO MJCF against the reference numbers: zero-pose kinematics, mass, joints, postures, model-file errors.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>

#include "freeplay/core/assets.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/stage/nao_controller.hpp"
#include "freeplay/stage/stage.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {
namespace {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

ModelPtr load_nao() { return ModelPtr(load_mjcf_file(assets_dir() / "nao" / "nao.xml")); }

Eigen::Vector3d site(const mjModel* m, const mjData* d, const char* name) {
  const int id = mj_name2id(m, mjOBJ_SITE, name);
  EXPECT_GE(id, 0) << name;
  return Eigen::Map<const Eigen::Vector3d>(d->site_xpos + 3 * id);
}

TEST(NaoModel, ZeroPoseHeightToHeadTopIs569mm) {
  const ModelPtr m = load_nao();
  DataPtr d(mj_makeData(m.get()));
  mj_kinematics(m.get(), d.get());
  const double sole = site(m.get(), d.get(), "l_sole").z();
  EXPECT_NEAR(site(m.get(), d.get(), "r_sole").z(), sole, 1e-9);
  EXPECT_NEAR(site(m.get(), d.get(), "head_top").z() - sole, 0.569, 0.005);
}

TEST(NaoModel, ShoulderToFingertipIs273mm) {
  const ModelPtr m = load_nao();
  DataPtr d(mj_makeData(m.get()));
  mj_kinematics(m.get(), d.get());
  const int shoulder = mj_name2id(m.get(), mjOBJ_BODY, "RShoulder");
  const Eigen::Vector3d origin = Eigen::Map<const Eigen::Vector3d>(d->xpos + 3 * shoulder);
  EXPECT_NEAR((site(m.get(), d.get(), "r_fingertip") - origin).norm(), 0.273, 0.003);
  const int left = mj_name2id(m.get(), mjOBJ_BODY, "LShoulder");
  const Eigen::Vector3d left_origin = Eigen::Map<const Eigen::Vector3d>(d->xpos + 3 * left);
  EXPECT_NEAR((site(m.get(), d.get(), "l_fingertip") - left_origin).norm(), 0.273, 0.003);
}

TEST(NaoModel, TotalMassIs5305gWithinOnePercent) {
  const ModelPtr m = load_nao();
  EXPECT_NEAR(mj_getTotalmass(m.get()), kNaoTotalMass, 0.01 * kNaoTotalMass);
  EXPECT_NEAR(mj_getTotalmass(m.get()), 5.30535, 1e-4);  // the link masses are the URDF's exactly
}

TEST(NaoModel, Has26NamedJoints25MotorsAndTheHipCoupling) {
  const ModelPtr m = load_nao();
  EXPECT_EQ(m->njnt, kNaoJointCount);
  EXPECT_EQ(m->nu, kNaoMotorCount);
  EXPECT_EQ(m->neq, 1);
  for (auto name : kNaoJointNames) {
    const int id = mj_name2id(m.get(), mjOBJ_JOINT, std::string(name).c_str());
    ASSERT_GE(id, 0) << name;
    EXPECT_EQ(m->jnt_limited[id], 1) << name;
  }
  EXPECT_LT(mj_name2id(m.get(), mjOBJ_ACTUATOR, "RHipYawPitch"), 0);
  const int hyp = mj_name2id(m.get(), mjOBJ_JOINT, "LHipYawPitch");
  EXPECT_NEAR(m->jnt_axis[3 * hyp + 1], 0.7071068, 1e-6);
  EXPECT_NEAR(m->jnt_axis[3 * hyp + 2], -0.7071068, 1e-6);
  EXPECT_NEAR(m->actuator_gainprm[0], 21.1, 1e-9);  // §1.10 tuned gain
  for (const char* camera : {"CameraTop", "CameraBottom"}) {
    const int id = mj_name2id(m.get(), mjOBJ_CAMERA, camera);
    ASSERT_GE(id, 0);
    EXPECT_NEAR(m->cam_fovy[id], 47.6, 1e-9);
  }
}

TEST(NaoModel, RightHipYawPitchFollowsTheLeftInDynamics) {
  const ModelPtr m = load_nao();
  DataPtr d(mj_makeData(m.get()));
  const int actuator = mj_name2id(m.get(), mjOBJ_ACTUATOR, "LHipYawPitch");
  d->ctrl[actuator] = -0.4;
  for (int i = 0; i < 500; ++i) mj_step(m.get(), d.get());
  const int left = m->jnt_qposadr[mj_name2id(m.get(), mjOBJ_JOINT, "LHipYawPitch")];
  const int right = m->jnt_qposadr[mj_name2id(m.get(), mjOBJ_JOINT, "RHipYawPitch")];
  EXPECT_LT(d->qpos[left], -0.2);
  EXPECT_NEAR(d->qpos[right], d->qpos[left], 0.01);
}

TEST(NaoModel, EveryPostureIsWithinTheJointRanges) {
  const ModelPtr m = load_nao();
  for (NaoPosture posture : kAllNaoPostures) {
    const NaoJointVector& q = posture_angles(posture);
    for (int i = 0; i < kNaoJointCount; ++i) {
      const int id = mj_name2id(m.get(), mjOBJ_JOINT, std::string(kNaoJointNames[static_cast<size_t>(i)]).c_str());
      // the posture table is rounded to 4 decimals
      EXPECT_GE(q[static_cast<size_t>(i)], m->jnt_range[2 * id] - 1e-4) << posture_name(posture) << " " << i;
      EXPECT_LE(q[static_cast<size_t>(i)], m->jnt_range[2 * id + 1] + 1e-4) << posture_name(posture) << " " << i;
    }
  }
}

TEST(NaoModel, PosturesLoadOnTheStageWithTheSolesOnTheFloor) {
  StageConfig config;
  config.scene = SceneKind::child_robot;
  Stage stage(StageModel::create(config));
  NaoController nao(stage);
  const NaoIndex& index = stage.model().nao();
  const mjModel* m = raw_model(stage.model());
  for (NaoPosture posture : kAllNaoPostures) {
    nao.go_to_posture(posture);
    stage.update_kinematics();
    const NaoJointVector q = nao.joint_positions();
    for (int i = 0; i < kNaoJointCount; ++i) {
      const int id = index.joint[static_cast<size_t>(i)];
      EXPECT_GE(q[static_cast<size_t>(i)], m->jnt_range[2 * id]);
      EXPECT_LE(q[static_cast<size_t>(i)], m->jnt_range[2 * id + 1]);
      EXPECT_NEAR(q[static_cast<size_t>(i)], posture_angles(posture)[static_cast<size_t>(i)], 1e-4);
    }
    const double lowest = std::min(stage.site_position(index.l_sole_site).z(), stage.site_position(index.r_sole_site).z());
    EXPECT_NEAR(lowest, SandtrayGeometry::floor_z, 1e-9) << posture_name(posture);
  }
}

TEST(NaoModel, StandInitGeometryMatchesTheReferenceTable) {
  StageConfig config;
  config.scene = SceneKind::child_robot;
  const Stage stage(StageModel::create(config));
  const NaoIndex& nao = stage.model().nao();
  const double floor = SandtrayGeometry::floor_z;
  // §1.9 world geometry of StandInit: torso origin 0.320 m, CameraTop 0.504 m, tilt 6.9° down.
  EXPECT_NEAR(raw_data(stage)->xpos[3 * nao.torso_body + 2] - floor, 0.320, 0.005);
  const Eigen::Isometry3d top = stage.camera_pose("CameraTop");
  EXPECT_NEAR(top.translation().z() - floor, 0.504, 0.005);
  const double tilt_down = std::asin(-top.linear().col(2).z()) * 180.0 / M_PI;
  EXPECT_NEAR(tilt_down, 6.9, 0.5);
  // standing on the yellow side, facing the screen (-y)
  EXPECT_GT(raw_data(stage)->xpos[3 * nao.torso_body + 1], SandtrayGeometry::bezel_max_y);
  EXPECT_LT(top.linear().col(2).y(), -0.9);
}

TEST(NaoModel, MissingModelFileGivesAClearError) {
  StageConfig config;
  config.scene = SceneKind::child_robot;
  config.nao_model = "/nonexistent/nao.xml";
  try {
    StageModel model(config);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/nao.xml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
}

TEST(NaoModel, MalformedModelFileReportsMuJoCosMessage) {
  const auto path = std::filesystem::temp_directory_path() / "freeplay_stage_malformed_nao.xml";
  {
    std::ofstream out(path);
    out << "<mujoco><worldbody><body name=\"torso\"><joint type=\"hinge\" range=\"1\"/></body></worldbody></mujoco>\n";
  }
  StageConfig config;
  config.scene = SceneKind::child_robot;
  config.nao_model = path;
  try {
    StageModel model(config);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("MuJoCo could not load"), std::string::npos) << message;
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("range"), std::string::npos) << message;  // MuJoCo names the bad attribute
  }
  std::filesystem::remove(path);
}

TEST(HeadPitchLimits, InterpolateTheNaoqiTable) {
  const HeadPitchRange zero = head_pitch_range(0.0);
  EXPECT_NEAR(zero.min, -0.671951, 1e-9);
  EXPECT_NEAR(zero.max, 0.515047, 1e-9);
  const HeadPitchRange row = head_pitch_range(-1.526988);
  EXPECT_NEAR(row.min, -0.330041, 1e-9);
  EXPECT_NEAR(row.max, 0.200015, 1e-9);
  const HeadPitchRange between = head_pitch_range(0.5 * (0.756077 + 0.903033));
  EXPECT_NEAR(between.max, 0.5 * (0.370010 + 0.330041), 1e-9);
  EXPECT_NEAR(head_pitch_range(3.0).max, 0.330041, 1e-9);  // held beyond the table
}

TEST(Postures, NamesRoundTripAndBadNamesAreInputErrors) {
  for (NaoPosture posture : kAllNaoPostures) EXPECT_EQ(posture_from_name(posture_name(posture)), posture);
  EXPECT_THROW(posture_from_name("Kneel"), InputError);
}

}  // namespace
}  // namespace freeplay::stage
