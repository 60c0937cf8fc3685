#pragma once
// What every fuzz target shares: bad input must end as an InputError; any other exception is a finding.

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

#include "freeplay/core/error.hpp"

namespace freeplay::fuzz {

/// Runs `parse`; an InputError is the expected answer to bad input, any other exception aborts (libFuzzer then
/// saves the input as a crash) after printing its type and message.
template <typename Parse>
void expect_input_errors_only(Parse&& parse) {
  try {
    parse();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "escaped exception %s: %s\n", typeid(e).name(), e.what());
    std::abort();
  }
}

/// The fuzzer's bytes as text.
inline std::string text_of(const unsigned char* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace freeplay::fuzz
