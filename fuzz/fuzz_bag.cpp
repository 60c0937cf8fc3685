// libFuzzer target: a bag file read back by `freeplay replay` (read_session, then every metric recomputed).

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "freeplay/recording/replay.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  // rosbag reads files only: one scratch file per fuzzing process, rewritten for every input.
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("freeplay-fuzz-" + std::to_string(getpid()) + ".bag");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  freeplay::fuzz::expect_input_errors_only(
      [&] { freeplay::recording::recompute_metrics(freeplay::recording::read_session(file)); });
  return 0;
}
