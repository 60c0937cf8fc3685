#pragma once
// The immutable 3-D stage: MuJoCo model of the sandtray table, the NAO, the child avatars and the cameras.

#include <Eigen/Geometry>
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/stage/nao_description.hpp"

namespace freeplay::stage {

/// Who plays at the sandtray.
enum class SceneKind { child_child, child_robot };

/// Parses "child-child" / "child-robot"; throws InputError naming the allowed values.
SceneKind scene_kind_from_name(std::string_view name);

/// The two child seats, named after the bib colour (yellow sits where the NAO stands in child-robot scenes).
enum class ChildRole { purple, yellow };
/// "purple" or "yellow".
std::string_view child_role_name(ChildRole role);

/// Fixed sandtray geometry in the `sandtray` frame (origin at the screen's top-left corner, z out of the screen).
struct SandtrayGeometry {
  static constexpr double screen_width = 0.600;    ///< active area along x (m)
  static constexpr double screen_height = 0.335;   ///< active area along -y (m)
  static constexpr double bezel_min_x = -0.070;    ///< table top extent (m)
  static constexpr double bezel_max_x = 0.667;     ///< table top extent (m)
  static constexpr double bezel_min_y = -0.426;    ///< table top extent, purple side (m)
  static constexpr double bezel_max_y = 0.070;     ///< table top extent, yellow side (m)
  static constexpr double bezel_top_z = 0.005;     ///< table top surface (m)
  static constexpr double floor_z = -0.250;        ///< floor height (table top ≈ 0.255 m above it)
};

/// Pinhole intrinsics of one image stream (pixel centres at integer coordinates).
struct CameraIntrinsics {
  int width = 0;    ///< image width (px)
  int height = 0;   ///< image height (px)
  double fx = 0;    ///< focal length along x (px)
  double fy = 0;    ///< focal length along y (px)
  double cx = 0;    ///< principal point x (px)
  double cy = 0;    ///< principal point y (px)
  /// The 3×3 camera matrix.
  Eigen::Matrix3d matrix() const;
  /// The same camera at another resolution (focal lengths and principal point scaled).
  CameraIntrinsics scaled_to(int new_width, int new_height) const;
};

/// One camera of the stage: the MuJoCo camera plus the streams the real sensor delivers.
struct CameraSpec {
  std::string name;            ///< e.g. "camera_purple"
  std::string description;     ///< what the real sensor is
  int camera_id = -1;          ///< index into the MuJoCo model's cameras
  CameraIntrinsics color;      ///< colour stream
  CameraIntrinsics depth;      ///< depth stream (equal to `color` where the sensor has no separate depth)
  bool on_robot = false;       ///< true for the NAO's head cameras (moves with the robot)
};

/// Child body dimensions (m) for a given age, from the seated anthropometrics table (ages 4–8).
struct ChildDimensions {
  double age_years;          ///< age the dimensions were interpolated for
  double stature;            ///< standing height
  double sitting_height;     ///< seat → vertex
  double eye_height;         ///< seat → eyes
  double shoulder_height;    ///< seat → acromion
  double biacromial;         ///< shoulder joint spacing
  double upper_arm;          ///< shoulder → elbow
  double forearm;            ///< elbow → wrist
  double hand;               ///< wrist → fingertip
  double hand_breadth;       ///< palm width
};

/// Interpolates the child table for `age_years` in [4, 8]; throws InputError outside.
ChildDimensions child_dimensions(double age_years);

/// Everything that fixes one stage model.
struct StageConfig {
  SceneKind scene = SceneKind::child_child;   ///< who is at the table
  double child_age_years = 7.0;               ///< age of both children (4–8; most PInSoRo children were 7)
  double cushion_height = 0.08;               ///< cushion thickness under each child (m)
  double child_table_gap = 0.20;              ///< table edge → child's seat centre (m)
  double nao_table_gap = 0.05;                ///< table edge → NAO torso origin in StandInit (m)
  double arm_reach = 0.5;                     ///< `arm_reach` parameter of the real system (m, RShoulder-centred)
  std::filesystem::path nao_model;            ///< NAO MJCF; empty = assets/nao/nao.xml
  int screen_texture_width = 1024;            ///< pixels of the screen texture (x)
  int screen_texture_height = 572;            ///< pixels of the screen texture (y), ≈ 0.600:0.335
};

/// MuJoCo indices of one child avatar.
struct AvatarIndex {
  ChildRole role = ChildRole::purple;   ///< bib colour
  bool present = false;                 ///< false when a NAO replaces this child
  int base_body = -1;                   ///< the avatar's root body (on the floor, x towards the table)
  int pelvis_body = -1;                 ///< body that carries the lean joint
  int bib_geom = -1;                    ///< the bib (coloured patch on the chest)
  int eyes_site = -1;                   ///< midpoint between the eyes
  std::array<int, 2> hand_tip_site{-1, -1};   ///< fingertip sites (0 = right, 1 = left)
  int lean = -1;                        ///< qpos address of the forward lean
  int head_yaw = -1;                    ///< qpos address
  int head_pitch = -1;                  ///< qpos address
  std::array<int, 2> shoulder_yaw{-1, -1};    ///< qpos addresses (right, left)
  std::array<int, 2> shoulder_pitch{-1, -1};  ///< qpos addresses (right, left)
  std::array<int, 2> elbow{-1, -1};           ///< qpos addresses (right, left)
  std::array<int, 9> dofs{};            ///< dof addresses of all avatar joints
  ChildDimensions dims{};               ///< body sizes
  Eigen::Isometry3d sandtray_T_base = Eigen::Isometry3d::Identity();   ///< seat pose on the floor
};

/// MuJoCo indices of the NAO.
struct NaoIndex {
  bool present = false;                          ///< true in child-robot scenes
  std::array<int, kNaoJointCount> joint{};       ///< joint ids in kNaoJointNames order
  std::array<int, kNaoJointCount> qpos{};        ///< qpos addresses
  std::array<int, kNaoJointCount> dof{};         ///< dof addresses
  std::array<int, kNaoJointCount> actuator{};    ///< actuator id per joint (-1 for RHipYawPitch)
  int torso_body = -1;                           ///< the (mocap) torso
  int torso_mocap = -1;                          ///< mocap index of the torso
  int rshoulder_body = -1;                       ///< RShoulder (origin = shoulder joint centre)
  int head_body = -1;                            ///< Head
  int neck_body = -1;                            ///< Neck (origin = HeadYaw / HeadPitch axes)
  int fingertip_site = -1;                       ///< r_fingertip
  int gaze_site = -1;                            ///< gaze (= CameraTop position)
  int head_top_site = -1;                        ///< head_top touch sensor
  int l_sole_site = -1;                          ///< l_sole
  int r_sole_site = -1;                          ///< r_sole
  /// Where the NAO's soles' midpoint stands (floor, sandtray frame) and which way it faces (rad about z).
  Eigen::Vector3d sole_anchor = Eigen::Vector3d::Zero();
  double facing_yaw = 0;                         ///< heading of the robot's x axis in the sandtray frame
};

/// Owns the MuJoCo model of the stage; loaded once, read-only afterwards and shareable across threads.
class StageModel {
 public:
  /// Builds the scene for `config`; throws InputError for bad values, std::runtime_error with MuJoCo's
  /// message when the NAO model file is missing or malformed.
  explicit StageModel(const StageConfig& config);
  ~StageModel();
  StageModel(const StageModel&) = delete;
  StageModel& operator=(const StageModel&) = delete;

  /// Convenience: a shared, immutable model.
  static std::shared_ptr<const StageModel> create(const StageConfig& config);

  /// The configuration it was built from.
  const StageConfig& config() const { return config_; }
  /// The assembled MJCF text.
  const std::string& mjcf() const { return mjcf_; }

  /// Every camera (real ones first, then the NAO's in child-robot scenes, then `top_view`).
  const std::vector<CameraSpec>& cameras() const { return cameras_; }
  /// The camera called `name`; throws InputError listing the names.
  const CameraSpec& camera(std::string_view name) const;

  /// The NAO's indices (present only in child-robot scenes).
  const NaoIndex& nao() const { return nao_; }
  /// A child's indices.
  const AvatarIndex& avatar(ChildRole role) const { return avatars_[static_cast<size_t>(role)]; }

  /// MuJoCo texture id of the sandtray screen.
  int screen_texture() const { return screen_texture_; }
  /// MuJoCo geom id of the sandtray screen.
  int screen_geom() const { return screen_geom_; }

 private:
  friend struct RawMujoco;   // stage/src/raw_mujoco.hpp: the raw model, for stage/'s sources only
  struct Raw;                // the MuJoCo model (stage/src/raw_mujoco.hpp)

  void index_model();
  void place_nao();

  StageConfig config_;
  std::string mjcf_;
  std::unique_ptr<Raw> raw_;
  std::vector<CameraSpec> cameras_;
  NaoIndex nao_;
  std::array<AvatarIndex, 2> avatars_;
  int screen_texture_ = -1;
  int screen_geom_ = -1;
};

}  // namespace freeplay::stage
