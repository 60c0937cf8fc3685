// libFuzzer target: `--set KEY.PATH=VALUE` overrides (one per line of the input) applied to a shipped scenario.

#include <sstream>

#include "freeplay/scenario/scenario.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  static const freeplay::YamlDocument base =
      freeplay::load_yaml_file(std::string(FREEPLAY_SCENARIOS_DIR) + "/child-robot-social.yaml");
  std::vector<std::string> overrides;
  std::istringstream lines(freeplay::fuzz::text_of(data, size));
  for (std::string line; std::getline(lines, line);) overrides.push_back(line);
  freeplay::fuzz::expect_input_errors_only([&] {
    freeplay::scenario::scenario_from_document({base.file, YAML::Clone(base.root)}, overrides);
  });
  return 0;
}
