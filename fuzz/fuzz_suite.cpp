// libFuzzer target: a suite document (YAML text) whose entries name the shipped scenarios (expanded and validated).

#include "freeplay/scenario/suite.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  freeplay::fuzz::expect_input_errors_only([&] {
    freeplay::scenario::suite_from_document(freeplay::parse_yaml(freeplay::fuzz::text_of(data, size), "fuzz-suite.yaml"),
                                          FREEPLAY_SCENARIOS_DIR);
  });
  return 0;
}
