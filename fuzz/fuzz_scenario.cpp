// libFuzzer target: a scenario document (YAML text) through the complete validation of `freeplay validate`.

#include "freeplay/scenario/scenario.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  freeplay::fuzz::expect_input_errors_only([&] {
    freeplay::scenario::scenario_from_document(freeplay::parse_yaml(freeplay::fuzz::text_of(data, size), "fuzz.yaml"));
  });
  return 0;
}
