#include "sibling_program.hpp"

#include <unistd.h>

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
  std::cerr << "error: cannot start " << sibling.string() << ": " << std::strerror(errno) << "\n";
  return 1;
}

}  // namespace freeplay::cli
