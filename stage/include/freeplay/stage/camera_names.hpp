#pragma once
// The names of the stage's cameras, in the order the stage model adds them: header-only, so that the scenario parser,
// the recorder and the command-line help list them without linking MuJoCo. The stage model (stage_model.cpp)
// builds its cameras from these lists.

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace freeplay::stage {

/// The cameras of the real room, in every scene: two RealSense SR300s and the Kinect v2.
inline constexpr std::array<std::string_view, 3> kRoomCameraNames = {"camera_purple", "camera_yellow", "env_camera"};
/// The cameras of the NAO's head (child-robot scenes only).
inline constexpr std::array<std::string_view, 2> kNaoCameraNames = {"CameraTop", "CameraBottom"};
/// The debug camera above the screen (not in the real setup, never recorded).
inline constexpr std::string_view kTopViewCameraName = "top_view";

/// The cameras of the real setup: the room's, then the NAO's (what scenarios may record).
inline std::vector<std::string> real_camera_names() {
  std::vector<std::string> names(kRoomCameraNames.begin(), kRoomCameraNames.end());
  names.insert(names.end(), kNaoCameraNames.begin(), kNaoCameraNames.end());
  return names;
}

/// Whether `name` is one of the NAO's head cameras.
constexpr bool is_nao_camera(std::string_view name) {
  for (const std::string_view nao : kNaoCameraNames) {
    if (name == nao) return true;
  }
  return false;
}

}  // namespace freeplay::stage
