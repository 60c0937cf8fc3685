#pragma once
// Numbers that describe the NAO H25 V5 outside the MJCF: joint order, postures, head anti-collision limits. The
// names are header-only, so that the scenario parser lists the postures without linking the stage.

#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

namespace freeplay::stage {

/// Number of NAO joints (HipYawPitch counted twice, as in NAOqi's `Body` chain).
inline constexpr int kNaoJointCount = 26;
/// Number of NAO motors (RHipYawPitch is coupled to LHipYawPitch).
inline constexpr int kNaoMotorCount = 25;
/// Whole-robot mass of the V5 (kg), the sum of the link masses.
inline constexpr double kNaoTotalMass = 5.30535;

/// The 26 joint names in NAOqi `Body` order (Head, LArm, LLeg, RLeg, RArm), as in the posture table.
inline constexpr std::array<std::string_view, kNaoJointCount> kNaoJointNames = {
    "HeadYaw",      "HeadPitch",   "LShoulderPitch", "LShoulderRoll", "LElbowYaw",    "LElbowRoll",
    "LWristYaw",    "LHand",       "LHipYawPitch",   "LHipRoll",      "LHipPitch",    "LKneePitch",
    "LAnklePitch",  "LAnkleRoll",  "RHipYawPitch",   "RHipRoll",      "RHipPitch",    "RKneePitch",
    "RAnklePitch",  "RAnkleRoll",  "RShoulderPitch", "RShoulderRoll", "RElbowYaw",    "RElbowRoll",
    "RWristYaw",    "RHand"};

/// Joint angles (rad; hands 0 = closed … 1 = open) in `kNaoJointNames` order.
using NaoJointVector = std::array<double, kNaoJointCount>;

/// The predefined NAOqi postures.
enum class NaoPosture { StandInit, Stand, StandZero, Crouch, Sit, SitRelax };

/// Every posture, for listings and tests.
inline constexpr std::array<NaoPosture, 6> kAllNaoPostures = {NaoPosture::StandInit, NaoPosture::Stand,
                                                              NaoPosture::StandZero, NaoPosture::Crouch,
                                                              NaoPosture::Sit,       NaoPosture::SitRelax};

/// The NAOqi names of the postures, in `kAllNaoPostures` order (header-only: the scenario parser lists them).
inline constexpr std::array<std::string_view, 6> kNaoPostureNames = {"StandInit", "Stand", "StandZero",
                                                                     "Crouch",    "Sit",   "SitRelax"};

/// The joint angles of a posture.
const NaoJointVector& posture_angles(NaoPosture posture);
/// The NAOqi name of a posture (e.g. "StandInit").
constexpr std::string_view posture_name(NaoPosture posture) {
  return kNaoPostureNames.at(static_cast<std::size_t>(posture));
}
/// Parses a NAOqi posture name; throws InputError listing the allowed names.
NaoPosture posture_from_name(std::string_view name);

/// Head pitch range allowed at one head yaw.
struct HeadPitchRange {
  double min;  ///< lowest pitch (rad; negative = up)
  double max;  ///< highest pitch (rad; positive = down)
};

/// NAOqi's yaw-dependent head pitch limits (anti-collision table), linearly interpolated in |yaw|.
HeadPitchRange head_pitch_range(double head_yaw);

/// Index of a joint in `kNaoJointNames`, or -1.
int nao_joint_index(std::string_view name);

}  // namespace freeplay::stage
