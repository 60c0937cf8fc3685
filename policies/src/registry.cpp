#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>

#include "freeplay/core/error.hpp"
#include "freeplay/policies/play_policy.hpp"

namespace freeplay::policies {

namespace {
std::vector<PolicyInfo>& registry() {
  static std::vector<PolicyInfo> policies;
  return policies;
}

std::map<std::string, PolicyFamilyFactory>& families() {
  static std::map<std::string, PolicyFamilyFactory> builders;
  return builders;
}

const PolicyInfo* registered_policy(const std::string& name) {
  for (const auto& p : registry()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

const PolicyFamilyFactory* family_of(const std::string& name) {
  for (const auto& [prefix, make] : families()) {
    if (name.starts_with(prefix)) return &make;
  }
  return nullptr;
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

void register_policy_family(std::string prefix, PolicyFamilyFactory make) { families()[std::move(prefix)] = std::move(make); }

std::vector<std::string> policy_name_patterns() {
  std::vector<std::string> patterns{std::string(kPythonPolicyPrefix) + "*"};
  for (const auto& [prefix, make] : families()) {
    if (prefix != kPythonPolicyPrefix) patterns.push_back(prefix + "*");
  }
  return patterns;
}

void check_policy_available(const std::string& name) {
  if (registered_policy(name) != nullptr || family_of(name) != nullptr) return;
  if (name.starts_with(kPythonPolicyPrefix)) {
    throw InputError(fmt::format("policy '{}' is written in Python: run it with `python3 -m freeplay run|suite …` "
                                 "instead of this program (docs/python.md)", name),
                     "robot.policy", fmt::format("{}", fmt::join(policy_names(), ", ")));
  }
  throw InputError(fmt::format("unknown policy '{}'", name), "robot.policy", fmt::format("{}", fmt::join(policy_names(), ", ")));
}

std::unique_ptr<PlayPolicy> make_policy(const std::string& name, const YAML::Node& params) {
  if (const auto* p = registered_policy(name)) return p->make(params);
  if (const auto* make = family_of(name)) return (*make)(name, params);
  check_policy_available(name);  // throws the reason
  return nullptr;
}

}  // namespace freeplay::policies
