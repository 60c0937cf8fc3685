#pragma once
// One scratch folder helper for every test executable (included by relative path: "../scratch_dir.hpp").

#include <unistd.h>

#include <filesystem>
#include <string>

namespace freeplay::test_support {

/// An empty folder for `name` under the system's temporary folder, one per test process (ctest may run the tests
/// of one executable in parallel processes), emptied if it was left over from an earlier run.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("freeplay-test-" + name + "-" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace freeplay::test_support
