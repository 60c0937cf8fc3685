#pragma once
// The names of the play policies this library ships (header-only, so that the scenario parser and the light
// `freeplay` binary know them without linking the policies): the default of the scenario vocabulary's policies.
// A test holds the list to the registry (FREEPLAY_REGISTER_POLICY); a program may register more of its own.

#include <algorithm>
#include <array>
#include <string_view>

namespace freeplay::policies {

/// The shipped policies, sorted as the registry lists them.
inline constexpr std::array<std::string_view, 5> kPolicyNames = {"asocial", "idle", "scripted", "social", "yoked"};

/// True when `name` is one of the shipped policies.
constexpr bool is_policy_name(std::string_view name) {
  return std::find(kPolicyNames.begin(), kPolicyNames.end(), name) != kPolicyNames.end();
}

}  // namespace freeplay::policies
