#pragma once
// A scratch folder per test and per test process, shared by the recording tests.

#include <unistd.h>

#include <filesystem>
#include <string>

namespace freeplay::recording::test_dirs {

/// An empty folder for `name`, one per test process (ctest runs the tests of one executable in parallel processes).
inline std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("freeplay-recording-" + name + "-" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace freeplay::recording::test_dirs
