// `freeplay`: answers `--version` and `validate` itself, linking only the scenario parsers, and hands every other
// subcommand to `freeplay-full` beside it (execv: same process, arguments and signals). Loading the simulation's
// shared libraries (OpenCV and what it pulls in, MuJoCo, OMPL, rosbag: about 270) costs most of a second's tenth.

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <iostream>
#include <string_view>

#include "command_registry.hpp"

int main(int argc, char** argv) {
  std::string_view command = argc > 1 ? argv[1] : "";
  if (command != "--version" && command != "validate") {
    std::error_code error;
    const auto full = std::filesystem::read_symlink("/proc/self/exe", error).parent_path() / "freeplay-full";
    execv(full.c_str(), argv);
    std::cerr << "error: cannot start " << full.string() << ": " << std::strerror(errno) << "\n";
    return 1;
  }
  return freeplay::cli::run_program(argc, argv);
}
