#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "freeplay/core/error.hpp"
#include "freeplay/policies/play_policy.hpp"

namespace freeplay::policies {

namespace {
std::vector<PolicyInfo>& registry() {
  static std::vector<PolicyInfo> policies;
  return policies;
}
}  // namespace

const ItemObservation* Observation::item(const std::string& name) const {
  for (const auto& i : items) {
    if (i.name == name) return &i;
  }
  return nullptr;
}

const std::vector<PolicyInfo>& registered_policies() { return registry(); }

bool register_policy(PolicyInfo info) {
  auto& all = registry();
  all.push_back(std::move(info));
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return true;
}

std::vector<std::string> policy_names() {
  std::vector<std::string> names;
  for (const auto& p : registry()) names.push_back(p.name);
  return names;
}

std::unique_ptr<PlayPolicy> make_policy(const std::string& name, const YAML::Node& params) {
  for (const auto& p : registry()) {
    if (p.name == name) return p.make(params);
  }
  throw InputError(fmt::format("unknown policy '{}'", name), "robot.policy", fmt::format("{}", fmt::join(policy_names(), ", ")));
}

}  // namespace freeplay::policies
