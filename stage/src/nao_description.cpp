#include "freeplay/stage/nao_description.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "freeplay/core/error.hpp"

namespace freeplay::stage {
namespace {

// nao-and-setup.md §1.9 (qiBullet NaoPosture values); StandZero from the same table.
const NaoJointVector kStandInit = {0, 0,   1.4, 0.3, -1.39, -1.01, 0, 0.25,  0, 0, -0.45, 0.7, -0.35, 0,
                                   0, 0, -0.45, 0.7, -0.35, 0,     1.4, -0.3, 1.39, 1.01, 0, 0.25};
const NaoJointVector kStand = {0,       -0.17,   1.4426, 0.2245, -1.2023, -0.4173, 0.1,    0.3,     -0.17,
                               0.1191,  0.1274,  -0.0923, 0.0874, -0.1108, -0.17,  -0.1191, 0.1274, -0.0923,
                               0.0874,  0.1108,  1.4426, -0.2245, 1.2023, 0.4173,  0.1,    0.3};
const NaoJointVector kStandZero = {0, 0, 0, 0.0087, 0, -0.0349, 0, 0, 0, 0, 0, 0, 0,
                                   0, 0, 0, 0, 0,      0, 0,       0, -0.0087, 0, 0.0349, 0, 0};
const NaoJointVector kCrouch = {0,     0.1,  1.3969, 0.1596, -0.7917, -1.0737, 0.15,  0,      -0.25,
                                -0.08, -0.7, 2.11,   -1.18,  0.077,   -0.25,   0.08,  -0.7,   2.11,
                                -1.18, -0.077, 1.3969, -0.1596, 0.7917, 1.0737, -0.15, 0};
const NaoJointVector kSit = {-0.0461, -0.0399, 0.8819,  0.2595,  -0.4521, -1.1905, -0.0169, 0.2892, -0.6074,
                             0.2731,  -1.5324, 1.3898,  0.8391,  -0.0122, -0.6074, -0.2592, -1.5359, 1.4021,
                             0.8483,  0.0231,  0.9383,  -0.3188, 0.5274,  1.2321,  0.0061,  0.2916};
const NaoJointVector kSitRelax = {-0.0246, 0.0184,  2.0857,  0.0887, -2.0817, -0.1995, -0.95,  0.1384, -0.5215,
                                  0.1320,  -1.1152, -0.0415, 0.922,  0,       -0.5215, -0.2209, -1.0600, -0.0920,
                                  0.922,   0,       2.0857,  -0.1546, 2.0755, 0.0431,  0.95,   0.1396};

// nao-and-setup.md §1.5 in rad: |yaw| ascending with the pitch range at each.
struct HeadLimitRow {
  double yaw, min, max;
};
constexpr std::array<HeadLimitRow, 7> kHeadLimits = {{{0.0, -0.671951, 0.515047},
                                                      {0.486074, -0.671951, 0.422021},
                                                      {0.756077, -0.548033, 0.370010},
                                                      {0.903033, -0.479965, 0.330041},
                                                      {1.089958, -0.430049, 0.300022},
                                                      {1.526988, -0.330041, 0.200015},
                                                      {2.086017, -0.449073, 0.330041}}};

}  // namespace

const NaoJointVector& posture_angles(NaoPosture posture) {
  switch (posture) {
    case NaoPosture::StandInit: return kStandInit;
    case NaoPosture::Stand: return kStand;
    case NaoPosture::StandZero: return kStandZero;
    case NaoPosture::Crouch: return kCrouch;
    case NaoPosture::Sit: return kSit;
    case NaoPosture::SitRelax: return kSitRelax;
  }
  return kStandInit;
}

NaoPosture posture_from_name(std::string_view name) {
  for (size_t i = 0; i < kNaoPostureNames.size(); ++i) {
    if (kNaoPostureNames[i] == name) return kAllNaoPostures[i];
  }
  throw InputError("unknown posture '" + std::string(name) + "'", "posture",
                   "StandInit, Stand, StandZero, Crouch, Sit, SitRelax");
}

HeadPitchRange head_pitch_range(double head_yaw) {
  const double yaw = std::min(std::abs(head_yaw), kHeadLimits.back().yaw);
  for (size_t i = 1; i < kHeadLimits.size(); ++i) {
    if (yaw <= kHeadLimits[i].yaw) {
      const auto& a = kHeadLimits[i - 1];
      const auto& b = kHeadLimits[i];
      const double f = (yaw - a.yaw) / (b.yaw - a.yaw);
      return {a.min + f * (b.min - a.min), a.max + f * (b.max - a.max)};
    }
  }
  return {kHeadLimits.back().min, kHeadLimits.back().max};
}

int nao_joint_index(std::string_view name) {
  const auto it = std::find(kNaoJointNames.begin(), kNaoJointNames.end(), name);
  return it == kNaoJointNames.end() ? -1 : static_cast<int>(it - kNaoJointNames.begin());
}

}  // namespace freeplay::stage
