#include "freeplay/runner/versions.hpp"

#include <box2d/b2_common.h>
#include <fmt/format.h>
#include <ompl/config.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>

#include <opencv2/core/version.hpp>

#include "freeplay/core/assets.hpp"
#include "freeplay/stage/stage_state.hpp"

namespace freeplay::runner {

nlohmann::json library_versions() {
  return {{"freeplay", program_version()},
          {"box2d", fmt::format("{}.{}.{}", b2_version.major, b2_version.minor, b2_version.revision)},
          {"opencv", CV_VERSION},
          {"ompl", fmt::format("{}.{}.{}", OMPL_MAJOR_VERSION, OMPL_MINOR_VERSION, OMPL_PATCH_VERSION)},
          {"mujoco", stage::mujoco_version()},
          {"eigen", fmt::format("{}.{}.{}", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION)}};
}

nlohmann::json provenance_fields(const EventLog& log) {
  return {{"events", log.size()},
          {"event_log_hash", fmt::format("{:016x}", log.hash())},
          {"gl_renderer", nullptr},
          {"libraries", library_versions()}};
}

}  // namespace freeplay::runner
