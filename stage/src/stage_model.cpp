#include "freeplay/stage/stage_model.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>

#include "freeplay/core/assets.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/sandtray_links.hpp"
#include "freeplay/stage/camera_names.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

// nao-and-setup.md §4.2 (cm): age, stature, sitting height, eye height, shoulder height, biacromial,
// upper arm, forearm, hand, hand breadth.
struct ChildRow {
  double age, stature, sitting, eye, shoulder, biacromial, upper_arm, forearm, hand, hand_breadth;
};
constexpr std::array<ChildRow, 5> kChildTable = {{{4, 101.8, 57.5, 47.0, 35.6, 21.9, 18.3, 14.8, 11.0, 4.9},
                                                  {5, 108.6, 60.8, 50.3, 37.7, 23.3, 19.5, 15.7, 11.7, 5.2},
                                                  {6, 115.3, 64.0, 53.5, 39.7, 24.8, 20.8, 16.7, 12.5, 5.5},
                                                  {7, 121.9, 67.0, 56.5, 41.6, 26.2, 21.9, 17.7, 13.2, 5.9},
                                                  {8, 127.9, 69.7, 59.2, 43.2, 27.5, 23.0, 18.6, 13.8, 6.1}}};


// SR300 colour at qHD with the PInSoRo calibration; depth 640×480 with fx ≈ 475 (§2).
const CameraIntrinsics kSr300Color{960, 540, 697.811, 697.811, 479.047, 261.227};
const CameraIntrinsics kSr300Depth{640, 480, 475.0, 475.0, 319.5, 239.5};
// Kinect v2 qHD colour: no calibration is published for env_camera; 84.1° horizontal FOV (documented estimate).
const CameraIntrinsics kKinectQhd{960, 540, 540.7, 540.7, 479.5, 269.5};
// NAO V5 MT9M114 at 640×480: 47.6° vertical FOV → fy ≈ 544 (§1.8).
const double kNaoFy = 240.0 / std::tan(47.6 / 2.0 * kPi / 180.0);
const CameraIntrinsics kNaoCamera{640, 480, kNaoFy, kNaoFy, 319.5, 239.5};
// Debug camera straight above the screen (not part of the real setup).
const CameraIntrinsics kTopView{960, 540, 800.0, 800.0, 479.5, 269.5};

Matrix3d rpy_matrix(const Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Vector3d::UnitX()))
      .toRotationMatrix();
}

std::string v3(const Vector3d& v) { return fmt::format("{:.6g} {:.6g} {:.6g}", v.x(), v.y(), v.z()); }

// MJCF camera (looks along -z, +y up) for a URDF link whose x axis looks forward; named without "_link".
std::string camera_xml(const UrdfLink& link) {
  const std::string frame = link.frame;
  const std::string name = frame.substr(0, frame.rfind("_link"));
  const Matrix3d r = rpy_matrix(link.rpy);
  const Vector3d x_cam = -r.col(1);
  const Vector3d y_cam = r.col(2);
  const double fovy = 2.0 * std::atan(0.5 * kSr300Color.height / kSr300Color.fy) * 180.0 / kPi;
  const Vector3d housing = link.xyz - 0.025 * r.col(0);
  return fmt::format(
      "    <camera name=\"{0}\" pos=\"{1}\" xyaxes=\"{2} {3}\" fovy=\"{4:.4f}\"/>\n"
      "    <geom name=\"{0}_housing\" type=\"box\" size=\"0.02 0.045 0.012\" pos=\"{5}\" xyaxes=\"{6} {7}\" "
      "material=\"device\"/>\n",
      name, v3(link.xyz), v3(x_cam), v3(y_cam), fovy, v3(housing), v3(r.col(0)), v3(r.col(1)));
}

std::string box_xml(const std::string& name, double x0, double x1, double y0, double y1, double z0, double z1,
                    const std::string& material) {
  return fmt::format("    <geom name=\"{}\" type=\"box\" pos=\"{:.6g} {:.6g} {:.6g}\" size=\"{:.6g} {:.6g} {:.6g}\" "
                     "material=\"{}\"/>\n",
                     name, 0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1), 0.5 * (x1 - x0), 0.5 * (y1 - y0),
                     0.5 * (z1 - z0), material);
}

std::string table_xml() {
  using G = SandtrayGeometry;
  std::string xml;
  const double slab_bottom = -0.045;
  const double screen_bottom = -0.002;
  xml += box_xml("table_slab", G::bezel_min_x, G::bezel_max_x, G::bezel_min_y, G::bezel_max_y, slab_bottom,
                 screen_bottom, "table");
  xml += box_xml("bezel_left", G::bezel_min_x, 0, G::bezel_min_y, G::bezel_max_y, screen_bottom, G::bezel_top_z,
                 "bezel");
  xml += box_xml("bezel_right", G::screen_width, G::bezel_max_x, G::bezel_min_y, G::bezel_max_y, screen_bottom,
                 G::bezel_top_z, "bezel");
  xml += box_xml("bezel_yellow_side", 0, G::screen_width, 0, G::bezel_max_y, screen_bottom, G::bezel_top_z, "bezel");
  xml += box_xml("bezel_purple_side", 0, G::screen_width, G::bezel_min_y, -G::screen_height, screen_bottom,
                 G::bezel_top_z, "bezel");
  xml += box_xml("screen", 0, G::screen_width, -G::screen_height, 0, screen_bottom, 0, "screen");
  const double leg = 0.041;
  int i = 0;
  for (double x : {G::bezel_min_x, G::bezel_max_x - leg}) {
    for (double y : {G::bezel_min_y, G::bezel_max_y - leg}) {
      xml += box_xml(fmt::format("table_leg{}", i++), x, x + leg, y, y + leg, G::floor_z, slab_bottom, "table");
    }
  }
  return xml;
}

// The seat pose of a child: on the floor, x axis towards the table.
Eigen::Isometry3d child_base_pose(ChildRole role, const StageConfig& config) {
  using G = SandtrayGeometry;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  const double x = 0.5 * G::screen_width;
  if (role == ChildRole::purple) {  // the purple child sits at the far long side (y < -0.335), facing +y
    pose.translation() = Vector3d(x, G::bezel_min_y - config.child_table_gap, G::floor_z);
    pose.linear() = Eigen::AngleAxisd(kPi / 2, Vector3d::UnitZ()).toRotationMatrix();
  } else {  // yellow at the near long side (y > 0), facing -y
    pose.translation() = Vector3d(x, G::bezel_max_y + config.child_table_gap, G::floor_z);
    pose.linear() = Eigen::AngleAxisd(-kPi / 2, Vector3d::UnitZ()).toRotationMatrix();
  }
  return pose;
}

std::string child_xml(ChildRole role, const StageConfig& config) {
  const ChildDimensions c = child_dimensions(config.child_age_years);
  const std::string p{child_role_name(role)};
  const Eigen::Isometry3d base = child_base_pose(role, config);
  const double yaw = std::atan2(base.linear()(1, 0), base.linear()(0, 0));
  const double head_r = 0.085;
  const double neck_z = c.shoulder_height + 0.04;
  const double head_c = c.sitting_height - head_r - neck_z;
  const double eye_z = c.eye_height - neck_z;
  const double eye_dz = eye_z - head_c;
  const double eye_x = std::sqrt(head_r * head_r - eye_dz * eye_dz - 0.03 * 0.03);
  const double torso_top = c.shoulder_height + 0.02;
  const double torso_bottom = 0.04;
  const double torso_c = 0.5 * (torso_top + torso_bottom);
  const double torso_h = 0.5 * (torso_top - torso_bottom);
  const double thigh = 0.245 * c.stature;
  const double half_b = 0.5 * c.biacromial;
  std::string arms;
  for (int side = 0; side < 2; ++side) {
    const char* s = side == 0 ? "r" : "l";
    const double sign = side == 0 ? -1.0 : 1.0;
    arms += fmt::format(
        "        <body name=\"{p}_{s}_upper_arm\" pos=\"0 {y:.4f} {z:.4f}\">\n"
        "          <joint name=\"{p}_{s}_shoulder_yaw\" axis=\"0 0 1\" range=\"-1.3 1.3\"/>\n"
        "          <joint name=\"{p}_{s}_shoulder_pitch\" axis=\"0 1 0\" range=\"-1.6 1.7\"/>\n"
        "          <inertial pos=\"{ua2:.4f} 0 0\" mass=\"0.6\" diaginertia=\"0.001 0.003 0.003\"/>\n"
        "          <geom type=\"capsule\" size=\"0.03\" fromto=\"0 0 0 {ua:.4f} 0 0\" material=\"{p}_shirt\"/>\n"
        "          <body name=\"{p}_{s}_forearm\" pos=\"{ua:.4f} 0 0\">\n"
        "            <joint name=\"{p}_{s}_elbow\" axis=\"0 1 0\" range=\"-2.5 0\"/>\n"
        "            <inertial pos=\"{fa2:.4f} 0 0\" mass=\"0.4\" diaginertia=\"0.0005 0.002 0.002\"/>\n"
        "            <geom type=\"capsule\" size=\"0.024\" fromto=\"0 0 0 {fa:.4f} 0 0\" material=\"skin\"/>\n"
        "            <geom type=\"ellipsoid\" size=\"{hh:.4f} {hb:.4f} 0.014\" pos=\"{hc:.4f} 0 0\" material=\"skin\"/>\n"
        "            <site name=\"{p}_{s}_hand_tip\" pos=\"{tip:.4f} 0 0\" size=\"0.008\"/>\n"
        "          </body>\n"
        "        </body>\n",
        fmt::arg("p", p), fmt::arg("s", s), fmt::arg("y", sign * half_b), fmt::arg("z", c.shoulder_height),
        fmt::arg("ua", c.upper_arm), fmt::arg("ua2", 0.5 * c.upper_arm), fmt::arg("fa", c.forearm),
        fmt::arg("fa2", 0.5 * c.forearm), fmt::arg("hh", 0.5 * c.hand), fmt::arg("hb", 0.5 * c.hand_breadth),
        fmt::arg("hc", c.forearm + 0.5 * c.hand), fmt::arg("tip", c.forearm + c.hand));
  }
  std::string legs;
  for (double sign : {-1.0, 1.0}) {
    const Vector3d hip(0.0, sign * 0.07, 0.05);
    const Vector3d knee(0.8 * thigh, sign * 0.6 * thigh, 0.06);
    const Vector3d ankle(0.25 * thigh, -sign * 0.15 * thigh, 0.045);
    legs += fmt::format("        <geom type=\"capsule\" size=\"0.05\" fromto=\"{} {}\" material=\"trousers\"/>\n",
                        v3(hip), v3(knee));
    legs += fmt::format("        <geom type=\"capsule\" size=\"0.04\" fromto=\"{} {}\" material=\"trousers\"/>\n",
                        v3(knee), v3(ankle));
  }
  return fmt::format(
      "    <body name=\"{p}_child\" pos=\"{pos}\" euler=\"0 0 {yaw:.6f}\">\n"
      "      <geom name=\"{p}_cushion\" type=\"cylinder\" size=\"0.22 {ch2:.4f}\" pos=\"0.03 0 {ch2:.4f}\" "
      "material=\"cushion\"/>\n"
      "      <body name=\"{p}_pelvis\" pos=\"0 0 {ch:.4f}\">\n"
      "        <joint name=\"{p}_lean\" axis=\"0 1 0\" range=\"-0.3 0.9\"/>\n"
      "        <inertial pos=\"0 0 {tc:.4f}\" mass=\"12\" diaginertia=\"0.3 0.3 0.1\"/>\n"
      "{legs}"
      "        <geom name=\"{p}_torso\" type=\"ellipsoid\" size=\"0.08 {tw:.4f} {th:.4f}\" pos=\"0 0 {tc:.4f}\" "
      "material=\"{p}_shirt\"/>\n"
      "        <geom name=\"{p}_bib\" type=\"ellipsoid\" size=\"0.065 {bw:.4f} {bh:.4f}\" pos=\"0.03 0 {bc:.4f}\" "
      "material=\"{p}_bib\"/>\n"
      "        <geom type=\"capsule\" size=\"0.035\" fromto=\"0 0 {n0:.4f} 0 0 {n1:.4f}\" material=\"skin\"/>\n"
      "{arms}"
      "        <body name=\"{p}_head\" pos=\"0 0 {nz:.4f}\">\n"
      "          <joint name=\"{p}_head_yaw\" axis=\"0 0 1\" range=\"-1.4 1.4\"/>\n"
      "          <joint name=\"{p}_head_pitch\" axis=\"0 1 0\" range=\"-0.7 0.9\"/>\n"
      "          <inertial pos=\"0 0 {hc:.4f}\" mass=\"3\" diaginertia=\"0.01 0.01 0.01\"/>\n"
      "          <geom name=\"{p}_face\" type=\"sphere\" size=\"{hr:.4f}\" pos=\"0 0 {hc:.4f}\" material=\"skin\"/>\n"
      "          <geom type=\"ellipsoid\" size=\"0.082 0.089 0.07\" pos=\"-0.018 0 {hair:.4f}\" material=\"hair\"/>\n"
      "          <geom type=\"sphere\" size=\"0.017\" pos=\"{ex0:.4f} 0.03 {ez:.4f}\" material=\"eye_white\"/>\n"
      "          <geom type=\"sphere\" size=\"0.017\" pos=\"{ex0:.4f} -0.03 {ez:.4f}\" material=\"eye_white\"/>\n"
      "          <geom type=\"sphere\" size=\"0.009\" pos=\"{ex1:.4f} 0.03 {ez:.4f}\" material=\"pupil\"/>\n"
      "          <geom type=\"sphere\" size=\"0.009\" pos=\"{ex1:.4f} -0.03 {ez:.4f}\" material=\"pupil\"/>\n"
      "          <geom type=\"ellipsoid\" size=\"0.006 0.022 0.005\" pos=\"{mx:.4f} 0 {mz:.4f}\" material=\"mouth\"/>\n"
      "          <site name=\"{p}_eyes\" pos=\"{ex:.4f} 0 {ez:.4f}\" size=\"0.005\"/>\n"
      "        </body>\n"
      "      </body>\n"
      "    </body>\n",
      fmt::arg("p", p), fmt::arg("pos", v3(base.translation())), fmt::arg("yaw", yaw),
      fmt::arg("ch", config.cushion_height), fmt::arg("ch2", 0.5 * config.cushion_height), fmt::arg("legs", legs),
      fmt::arg("tw", 0.85 * half_b), fmt::arg("th", torso_h), fmt::arg("tc", torso_c),
      fmt::arg("bw", 0.7 * half_b), fmt::arg("bh", 0.75 * torso_h), fmt::arg("bc", torso_c + 0.02),
      fmt::arg("n0", c.shoulder_height - 0.02), fmt::arg("n1", neck_z + 0.03), fmt::arg("arms", arms),
      fmt::arg("nz", neck_z), fmt::arg("hc", head_c), fmt::arg("hr", head_r), fmt::arg("hair", head_c + 0.025),
      fmt::arg("ex0", eye_x - 0.006), fmt::arg("ex1", eye_x + 0.006), fmt::arg("ex", eye_x), fmt::arg("ez", eye_z),
      fmt::arg("mx", head_r * 0.93), fmt::arg("mz", head_c - 0.045));
}

// Inner text of the single <tag>…</tag> section of an MJCF document.
std::string section(const std::string& xml, const std::string& tag, const std::filesystem::path& file) {
  const std::string open = "<" + tag + ">";
  const std::string close = "</" + tag + ">";
  const auto begin = xml.find(open);
  const auto end = xml.find(close);
  if (begin == std::string::npos || end == std::string::npos || end < begin) {
    throw std::runtime_error(fmt::format("NAO model '{}': expected one <{}> section", file.string(), tag));
  }
  return xml.substr(begin + open.size(), end - begin - open.size());
}

// The whole <default class="nao"> element of the NAO model.
std::string nao_default_class(const std::string& xml, const std::filesystem::path& file) {
  const std::string open = "<default class=\"nao\">";
  const auto begin = xml.find(open);
  const auto end = begin == std::string::npos ? begin : xml.find("</default>", begin);
  if (end == std::string::npos) {
    throw std::runtime_error(fmt::format("NAO model '{}': expected a <default class=\"nao\"> section", file.string()));
  }
  return xml.substr(begin, end + std::string("</default>").size() - begin);
}

mjModel* load_from_string(const std::string& xml) {
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "freeplay_stage.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0) {
    throw std::runtime_error("MuJoCo VFS: cannot hold the stage MJCF");
  }
  const int index = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* model = mj_loadXML(name, vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (model == nullptr) throw std::runtime_error(fmt::format("MuJoCo rejected the stage MJCF: {}", error));
  if (error[0] != '\0') spdlog::warn("MuJoCo: {}", error);
  return model;
}

int require_id(const mjModel* m, mjtObj type, const std::string& name) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw std::runtime_error(fmt::format("stage model: '{}' is missing", name));
  return id;
}

}  // namespace

SceneKind scene_kind_from_name(std::string_view name) {
  if (name == "child-child") return SceneKind::child_child;
  if (name == "child-robot") return SceneKind::child_robot;
  throw InputError("unknown scene '" + std::string(name) + "'", "scene", "child-child, child-robot");
}

std::string_view child_role_name(ChildRole role) { return role == ChildRole::purple ? "purple" : "yellow"; }

Eigen::Matrix3d CameraIntrinsics::matrix() const {
  Eigen::Matrix3d k;
  k << fx, 0, cx, 0, fy, cy, 0, 0, 1;
  return k;
}

CameraIntrinsics CameraIntrinsics::scaled_to(int new_width, int new_height) const {
  const double sx = static_cast<double>(new_width) / width;
  const double sy = static_cast<double>(new_height) / height;
  return {new_width, new_height, fx * sx, fy * sy, (cx + 0.5) * sx - 0.5, (cy + 0.5) * sy - 0.5};
}

ChildDimensions child_dimensions(double age_years) {
  if (!(age_years >= 4.0 && age_years <= 8.0)) {
    throw InputError(fmt::format("child age {} is outside the anthropometrics table", age_years), "age",
                     "4 to 8 years");
  }
  size_t i = 0;
  while (i + 2 < kChildTable.size() && age_years > kChildTable[i + 1].age) ++i;
  const ChildRow& a = kChildTable[i];
  const ChildRow& b = kChildTable[i + 1];
  const double f = (age_years - a.age) / (b.age - a.age);
  auto lerp = [f](double u, double v) { return 0.01 * (u + f * (v - u)); };
  return {age_years,
          lerp(a.stature, b.stature),
          lerp(a.sitting, b.sitting),
          lerp(a.eye, b.eye),
          lerp(a.shoulder, b.shoulder),
          lerp(a.biacromial, b.biacromial),
          lerp(a.upper_arm, b.upper_arm),
          lerp(a.forearm, b.forearm),
          lerp(a.hand, b.hand),
          lerp(a.hand_breadth, b.hand_breadth)};
}

mjModel* load_mjcf_file(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) {
    throw std::runtime_error(fmt::format("MJCF file '{}' does not exist", path.string()));
  }
  char error[1000] = "";
  mjModel* model = mj_loadXML(path.string().c_str(), nullptr, error, sizeof(error));
  if (model == nullptr) {
    throw std::runtime_error(fmt::format("MuJoCo could not load '{}': {}", path.string(), error));
  }
  return model;
}

StageModel::StageModel(const StageConfig& config) : config_(config), raw_(std::make_unique<Raw>()) {
  child_dimensions(config.child_age_years);  // validates the age before any work
  if (config.cushion_height < 0.0 || config.cushion_height > 0.3) {
    throw InputError("cushion height out of range", "cushion_height", "0 to 0.3 m");
  }
  if (config.arm_reach <= 0.0) throw InputError("arm reach must be positive", "arm_reach", "> 0 m");
  if (config.screen_texture_width < 16 || config.screen_texture_height < 16 ||
      config.screen_texture_width > 4096 || config.screen_texture_height > 4096) {
    throw InputError("screen texture size out of range", "screen_texture", "16 to 4096 px per side");
  }

  std::string nao_default, nao_asset, nao_body, nao_equality, nao_actuator;
  if (config.scene == SceneKind::child_robot) {
    const std::filesystem::path nao_path =
        config.nao_model.empty() ? assets_dir() / "nao" / "nao.xml" : config.nao_model;
    mj_deleteModel(load_mjcf_file(nao_path));  // MuJoCo validates the file and reports its own message
    const std::string text = read_file(nao_path);
    nao_default = nao_default_class(text, nao_path);
    nao_asset = section(text, "asset", nao_path);
    nao_body = section(text, "worldbody", nao_path);
    nao_equality = section(text, "equality", nao_path);
    nao_actuator = section(text, "actuator", nao_path);
  }

  std::string cameras;
  for (const auto& link : kSandtrayCameraLinks) cameras += camera_xml(link);
  std::string children = child_xml(ChildRole::purple, config);
  if (config.scene == SceneKind::child_child) children += child_xml(ChildRole::yellow, config);

  mjcf_ = fmt::format(
      R"(<mujoco model="freeplay_stage">
  <compiler angle="radian" inertiafromgeom="false"/>
  <option timestep="0.002" integrator="Euler"/>
  <size nkey="0"/>
  <statistic extent="2" center="0.3 -0.17 0"/>
  <visual>
    <global offwidth="1280" offheight="960"/>
    <quality shadowsize="2048" offsamples="4"/>
    <map znear="0.01" zfar="25"/>
    <headlight ambient="0.35 0.35 0.35" diffuse="0.45 0.45 0.45" specular="0.1 0.1 0.1"/>
  </visual>
  <default>
{nao_default}
    <geom contype="0" conaffinity="0"/>
    <joint limited="true"/>
  </default>
  <asset>
{nao_asset}
    <texture name="screen" type="2d" builtin="flat" width="{tw}" height="{th}" rgb1="0.3 0.6 0.3"/>
    <material name="screen" texture="screen" texrepeat="1 1" emission="0.7" specular="0.1"/>
    <texture name="sky" type="skybox" builtin="gradient" rgb1="0.95 0.95 0.97" rgb2="0.7 0.72 0.75" width="128" height="128"/>
    <texture name="floor" type="2d" builtin="checker" rgb1="0.72 0.66 0.58" rgb2="0.66 0.6 0.52" width="64" height="64"/>
    <material name="floor" texture="floor" texrepeat="8 8" reflectance="0.1"/>
    <material name="wall" rgba="0.88 0.88 0.85 1"/>
    <material name="table" rgba="0.95 0.95 0.93 1"/>
    <material name="bezel" rgba="0.12 0.12 0.13 1" specular="0.5"/>
    <material name="device" rgba="0.15 0.15 0.16 1"/>
    <material name="cushion" rgba="0.35 0.45 0.6 1"/>
    <material name="skin" rgba="0.96 0.8 0.68 1"/>
    <material name="hair" rgba="0.3 0.2 0.12 1"/>
    <material name="eye_white" rgba="1 1 1 1" emission="0.3"/>
    <material name="pupil" rgba="0.05 0.05 0.08 1"/>
    <material name="mouth" rgba="0.75 0.35 0.35 1"/>
    <material name="trousers" rgba="0.25 0.3 0.45 1"/>
    <material name="purple_shirt" rgba="0.7 0.75 0.8 1"/>
    <material name="yellow_shirt" rgba="0.7 0.75 0.8 1"/>
    <material name="purple_bib" rgba="0.55 0.2 0.65 1"/>
    <material name="yellow_bib" rgba="0.98 0.85 0.1 1"/>
  </asset>
  <worldbody>
    <light name="ceiling" pos="0.3 -0.17 2.2" dir="0 0 -1" diffuse="0.5 0.5 0.5" specular="0.1 0.1 0.1" castshadow="true"/>
    <geom name="floor" type="plane" pos="0 0 {floor}" size="3 3 0.5" material="floor"/>
    <geom name="wall_back" type="box" pos="-1.3 -0.17 0.75" size="0.02 2.5 1.0" material="wall"/>
    <geom name="wall_front" type="box" pos="2.3 -0.17 0.75" size="0.02 2.5 1.0" material="wall"/>
    <geom name="wall_purple" type="box" pos="0.5 -2.2 0.75" size="1.8 0.02 1.0" material="wall"/>
    <geom name="wall_yellow" type="box" pos="0.5 1.8 0.75" size="1.8 0.02 1.0" material="wall"/>
    <geom name="ceiling" type="box" pos="0.5 -0.17 1.75" size="1.8 2.5 0.02" material="wall"/>
{table}{cameras}    <camera name="top_view" pos="0.3 -0.1675 0.9" xyaxes="1 0 0 0 1 0" fovy="{topfovy:.4f}"/>
{children}{nao_body}
  </worldbody>
  <equality>
{nao_equality}
  </equality>
  <actuator>
{nao_actuator}
  </actuator>
</mujoco>
)",
      fmt::arg("nao_default", nao_default), fmt::arg("nao_asset", nao_asset),
      fmt::arg("tw", config.screen_texture_width), fmt::arg("th", config.screen_texture_height),
      fmt::arg("floor", SandtrayGeometry::floor_z), fmt::arg("table", table_xml()), fmt::arg("cameras", cameras),
      fmt::arg("topfovy", 2.0 * std::atan(0.5 * kTopView.height / kTopView.fy) * 180.0 / kPi),
      fmt::arg("children", children), fmt::arg("nao_body", nao_body), fmt::arg("nao_equality", nao_equality),
      fmt::arg("nao_actuator", nao_actuator));
  // MuJoCo rejects empty <equality>/<actuator> sections in 2.2: drop them in child-child scenes.
  if (config.scene == SceneKind::child_child) {
    for (const char* empty : {"  <equality>\n\n  </equality>\n", "  <actuator>\n\n  </actuator>\n"}) {
      const auto at = mjcf_.find(empty);
      if (at != std::string::npos) mjcf_.erase(at, std::strlen(empty));
    }
  }
  raw_->model = load_from_string(mjcf_);
  index_model();
  if (nao_.present) place_nao();
}

StageModel::~StageModel() = default;

std::shared_ptr<const StageModel> StageModel::create(const StageConfig& config) {
  return std::make_shared<const StageModel>(config);
}

const CameraSpec& StageModel::camera(std::string_view name) const {
  std::string names;
  for (const auto& spec : cameras_) {
    if (spec.name == name) return spec;
    names += (names.empty() ? "" : ", ") + spec.name;
  }
  throw InputError("unknown camera '" + std::string(name) + "'", "camera", names);
}

void StageModel::index_model() {
  const mjModel* m = raw_->model;
  auto add_camera = [&](std::string_view camera, const std::string& description, CameraIntrinsics color,
                        CameraIntrinsics depth, bool on_robot) {
    const std::string name(camera);
    cameras_.push_back({name, description, require_id(m, mjOBJ_CAMERA, name), color, depth, on_robot});
  };
  // The names come from camera_names.hpp, which the parser and the recorder read without linking the stage.
  const auto [camera_purple, camera_yellow, env_camera] = kRoomCameraNames;
  add_camera(camera_purple, "RealSense SR300 at the left short end, filming the purple child", kSr300Color,
             kSr300Depth, false);
  add_camera(camera_yellow, "RealSense SR300 at the left short end, filming the yellow child (or the NAO)",
             kSr300Color, kSr300Depth, false);
  add_camera(env_camera, "Kinect v2 (qHD) beyond the right short end, looking back over the table", kKinectQhd,
             kKinectQhd, false);

  screen_texture_ = require_id(m, mjOBJ_TEXTURE, "screen");
  screen_geom_ = require_id(m, mjOBJ_GEOM, "screen");

  for (ChildRole role : {ChildRole::purple, ChildRole::yellow}) {
    AvatarIndex& a = avatars_[static_cast<size_t>(role)];
    a.role = role;
    const std::string p{child_role_name(role)};
    a.present = mj_name2id(m, mjOBJ_BODY, (p + "_child").c_str()) >= 0;
    if (!a.present) continue;
    a.dims = child_dimensions(config_.child_age_years);
    a.sandtray_T_base = child_base_pose(role, config_);
    a.base_body = require_id(m, mjOBJ_BODY, p + "_child");
    a.pelvis_body = require_id(m, mjOBJ_BODY, p + "_pelvis");
    a.bib_geom = require_id(m, mjOBJ_GEOM, p + "_bib");
    a.eyes_site = require_id(m, mjOBJ_SITE, p + "_eyes");
    auto joint = [&](const std::string& name, int slot) {
      const int id = require_id(m, mjOBJ_JOINT, p + "_" + name);
      a.dofs[static_cast<size_t>(slot)] = m->jnt_dofadr[id];
      return m->jnt_qposadr[id];
    };
    a.lean = joint("lean", 0);
    a.head_yaw = joint("head_yaw", 1);
    a.head_pitch = joint("head_pitch", 2);
    for (int side = 0; side < 2; ++side) {
      const std::string s = side == 0 ? "r" : "l";
      a.shoulder_yaw[static_cast<size_t>(side)] = joint(s + "_shoulder_yaw", 3 + 3 * side);
      a.shoulder_pitch[static_cast<size_t>(side)] = joint(s + "_shoulder_pitch", 4 + 3 * side);
      a.elbow[static_cast<size_t>(side)] = joint(s + "_elbow", 5 + 3 * side);
      a.hand_tip_site[static_cast<size_t>(side)] = require_id(m, mjOBJ_SITE, p + "_" + s + "_hand_tip");
    }
  }

  nao_.present = mj_name2id(m, mjOBJ_BODY, "torso") >= 0;
  if (nao_.present) {
    for (int i = 0; i < kNaoJointCount; ++i) {
      const std::string name{kNaoJointNames[static_cast<size_t>(i)]};
      const int id = require_id(m, mjOBJ_JOINT, name);
      nao_.joint[static_cast<size_t>(i)] = id;
      nao_.qpos[static_cast<size_t>(i)] = m->jnt_qposadr[id];
      nao_.dof[static_cast<size_t>(i)] = m->jnt_dofadr[id];
      nao_.actuator[static_cast<size_t>(i)] =
          name == "RHipYawPitch" ? -1 : require_id(m, mjOBJ_ACTUATOR, name);
    }
    nao_.torso_body = require_id(m, mjOBJ_BODY, "torso");
    nao_.torso_mocap = m->body_mocapid[nao_.torso_body];
    if (nao_.torso_mocap < 0) throw std::runtime_error("stage model: NAO torso must be a mocap body");
    nao_.rshoulder_body = require_id(m, mjOBJ_BODY, "RShoulder");
    nao_.head_body = require_id(m, mjOBJ_BODY, "Head");
    nao_.neck_body = require_id(m, mjOBJ_BODY, "Neck");
    nao_.fingertip_site = require_id(m, mjOBJ_SITE, "r_fingertip");
    nao_.gaze_site = require_id(m, mjOBJ_SITE, "gaze");
    nao_.head_top_site = require_id(m, mjOBJ_SITE, "head_top");
    nao_.l_sole_site = require_id(m, mjOBJ_SITE, "l_sole");
    nao_.r_sole_site = require_id(m, mjOBJ_SITE, "r_sole");
    const auto [camera_top, camera_bottom] = kNaoCameraNames;
    add_camera(camera_top, "NAO V5 top camera (MT9M114, 47.6° vertical FOV)", kNaoCamera, kNaoCamera, true);
    add_camera(camera_bottom, "NAO V5 bottom camera (MT9M114, 47.6° vertical FOV)", kNaoCamera, kNaoCamera, true);
  }
  add_camera(kTopViewCameraName, "debug camera 0.9 m straight above the screen (not in the real setup)", kTopView,
             kTopView, false);
}

void StageModel::place_nao() {
  // The robot stands on the yellow side facing -y; its torso origin is `nao_table_gap` from the table edge in
  // StandInit. The soles' anchor is found by forward kinematics of StandInit with the soles flat on the floor.
  nao_.facing_yaw = -kPi / 2;
  mjData* d = mj_makeData(raw_->model);
  const NaoJointVector& q = posture_angles(NaoPosture::StandInit);
  for (int i = 0; i < kNaoJointCount; ++i) d->qpos[nao_.qpos[static_cast<size_t>(i)]] = q[static_cast<size_t>(i)];
  const int mocap = nao_.torso_mocap;
  d->mocap_pos[3 * mocap] = d->mocap_pos[3 * mocap + 1] = d->mocap_pos[3 * mocap + 2] = 0;
  d->mocap_quat[4 * mocap] = 1;
  d->mocap_quat[4 * mocap + 1] = d->mocap_quat[4 * mocap + 2] = d->mocap_quat[4 * mocap + 3] = 0;
  mj_kinematics(raw_->model, d);
  const Vector3d l_sole = Eigen::Map<const Vector3d>(d->site_xpos + 3 * nao_.l_sole_site);
  const Vector3d r_sole = Eigen::Map<const Vector3d>(d->site_xpos + 3 * nao_.r_sole_site);
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> sole_r =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->site_xmat + 9 * nao_.l_sole_site);
  mj_deleteData(d);
  // torso origin relative to the sole midpoint, expressed in the (flat) sole frame
  const Vector3d torso_in_sole = sole_r.transpose() * (Vector3d::Zero() - 0.5 * (l_sole + r_sole));
  const Matrix3d facing = Eigen::AngleAxisd(nao_.facing_yaw, Vector3d::UnitZ()).toRotationMatrix();
  const Vector3d torso_world_offset = facing * torso_in_sole;  // torso relative to the anchor, world axes
  const double torso_y = SandtrayGeometry::bezel_max_y + config_.nao_table_gap;
  nao_.sole_anchor = Vector3d(0.5 * SandtrayGeometry::screen_width - torso_world_offset.x(),
                              torso_y - torso_world_offset.y(), SandtrayGeometry::floor_z);
}

Eigen::Isometry3d camera_optical_pose(const mjModel* m, const mjData* d, int camera_id) {
  (void)m;
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> r(d->cam_xmat + 9 * camera_id);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Map<const Vector3d>(d->cam_xpos + 3 * camera_id);
  pose.linear().col(0) = r.col(0);
  pose.linear().col(1) = -r.col(1);
  pose.linear().col(2) = -r.col(2);
  return pose;
}

}  // namespace freeplay::stage
