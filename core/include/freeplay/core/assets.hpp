#pragma once
// Where the shipped assets (item catalogue, pictures, backgrounds, robot model, calibration) live.

#include <filesystem>
#include <string>

namespace freeplay {

/// The assets folder: $FREEPLAY_ASSETS_DIR if set, else the source tree's `assets/` recorded at build time.
std::filesystem::path assets_dir();
/// `assets_dir() / relative`, throwing std::runtime_error naming the path when it does not exist.
std::filesystem::path asset_path(const std::string& relative);

/// The program version (`git describe` at configure time).
const char* program_version();

}  // namespace freeplay
