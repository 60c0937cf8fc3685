// libFuzzer target: the PInSoRo annotation YAML reader (the children's calibration data and replay's annotations).

#include "freeplay/agents/annotations.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  freeplay::fuzz::expect_input_errors_only(
      [&] { freeplay::agents::parse_pinsoro_yaml(freeplay::fuzz::text_of(data, size), "fuzz-annotations.yaml"); });
  return 0;
}
