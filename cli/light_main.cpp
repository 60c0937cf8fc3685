// `freeplay`: answers `--version` and `validate` itself, linking only the scenario parsers, and hands every other
// subcommand to the executable beside it that has it (execv: same process, arguments and signals): `run` and
// `suite` to `freeplay-run` (the simulation's libraries only), the rest to `freeplay-full`. Loading all of
// `freeplay-full`'s shared libraries (OpenCV's codecs and what they pull in, rosbag, roscpp: about 300) costs most
// of a second's fifth; `freeplay-run` starts in a few milliseconds.

#include <string_view>

#include "program.hpp"
#include "sibling_program.hpp"

int main(int argc, char** argv) {
  std::string_view command = argc > 1 ? argv[1] : "";
  if (command == "--version" || command == "validate") return freeplay::cli::run_program(argc, argv);
  const bool episodes = command == "run" || command == "suite";
  return freeplay::cli::exec_sibling_program(episodes ? "freeplay-run" : "freeplay-full", argv);
}
