#include "sibling_program.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

namespace freeplay::cli {

int exec_sibling_program(const char* name, char** argv) {
  std::error_code error;
  const auto sibling = std::filesystem::read_symlink("/proc/self/exe", error).parent_path() / name;
  std::cout.flush();
  std::cerr.flush();
  execv(sibling.c_str(), argv);
  const int exec_error = errno;
  if (exec_error == ENOENT) {  // the main job's build (scripts/build.sh --main) has freeplay and freeplay-run only
    std::cerr << "error: '" << (argv[1] != nullptr ? argv[1] : "") << "' needs " << sibling.string()
              << ", which this build does not have (scripts/build.sh --main builds the main job only); build "
                 "everything from the repository root with: scripts/setup.sh && scripts/build.sh\n";
    return 1;
  }
  std::cerr << "error: cannot start " << sibling.string() << ": " << std::strerror(exec_error) << "\n";
  return 1;
}

}  // namespace freeplay::cli
