#pragma once
// The name/value pairs of the enums that settings and run records write as text: a library declares
// `to_string(Enum)` and `from_string(text, Enum&)` next to its enum, and these helpers list and look up its names
// (found by argument-dependent lookup).

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace freeplay {

/// Sets `value` to the one of `values` whose name is `text`; false (and `value` unchanged) when none is.
template <typename Enum>
constexpr bool enum_from_string(std::string_view text, std::initializer_list<Enum> values, Enum& value) {
  for (const Enum candidate : values) {
    if (text == to_string(candidate)) {
      value = candidate;
      return true;
    }
  }
  return false;
}

/// The names of `values`, in this order (e.g. the allowed values of a `Schema::enumeration`).
template <typename Enum>
std::vector<std::string> enum_names(std::initializer_list<Enum> values) {
  std::vector<std::string> names;
  for (const Enum value : values) names.emplace_back(to_string(value));
  return names;
}

}  // namespace freeplay
