#include "freeplay/core/assets.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <stdexcept>

#ifndef FREEPLAY_SOURCE_ASSETS_DIR
#error "FREEPLAY_SOURCE_ASSETS_DIR must be defined by the build"
#endif

namespace freeplay {

std::filesystem::path assets_dir() {
  if (const char* env = std::getenv("FREEPLAY_ASSETS_DIR"); env != nullptr && *env != '\0') {
    return std::filesystem::path(env);
  }
  return std::filesystem::path(FREEPLAY_SOURCE_ASSETS_DIR);
}

std::filesystem::path asset_path(const std::string& relative) {
  auto path = assets_dir() / relative;
  if (!std::filesystem::exists(path)) {
    throw std::runtime_error(fmt::format("asset not found: {} (assets folder: {}; set FREEPLAY_ASSETS_DIR to "
                                         "point elsewhere)", path.string(), assets_dir().string()));
  }
  return path;
}

}  // namespace freeplay
