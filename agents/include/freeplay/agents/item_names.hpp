#pragma once
// The names of the free-play items (header-only, so that the scenario parser and the light `freeplay` binary know
// them without the agents library): the children's perception indexes items by them, the scenario vocabulary
// accepts them.

#include <array>
#include <string_view>

namespace freeplay::agents {

/// Items of the free-play set, in the order of the real play policy's ITEMS list.
inline constexpr std::array<std::string_view, 10> kItemNames = {"zebra",   "elephant",  "ball", "lion", "giraffe",
                                                                 "caravan", "crocodile", "hippo", "boy", "girl"};

}  // namespace freeplay::agents
