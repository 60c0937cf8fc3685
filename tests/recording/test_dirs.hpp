#pragma once
// A scratch folder per test and per test process, and a file read whole, shared by the recording tests.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "../scratch_dir.hpp"

namespace freeplay::recording::test_dirs {

/// An empty folder for `name`, one per test process (ctest runs the tests of one executable in parallel processes).
inline std::filesystem::path fresh_dir(const std::string& name) {
  return test_support::fresh_dir("recording-" + name);
}

/// The whole of `file`, as bytes.
inline std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace freeplay::recording::test_dirs
