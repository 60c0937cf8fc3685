#pragma once
// A suite: a list of scenarios with per-entry overrides and parameter sweeps, expanded into variants.

#include <filesystem>
#include <string>
#include <vector>

#include "freeplay/scenario/scenario.hpp"

namespace freeplay::scenario {

/// One expanded scenario of a suite (a sweep produces several variants of one entry).
struct SuiteVariant {
  std::string id;       ///< unique within the suite: the scenario name, plus "[key=value,…]" for sweeps
  Scenario scenario;    ///< validated scenario with every override applied
};

/// A validated, expanded suite.
struct Suite {
  std::string name;                    ///< suite name
  std::string description;             ///< one line for people
  std::string file;                    ///< where it was loaded from
  std::vector<SuiteVariant> variants;  ///< in file order, sweeps expanded in order

  /// Total episodes over every variant.
  int total_episodes() const;
};

/// Loads a suite file (`suite:`, `scenarios: [{scenario: FILE, episodes:, set: {K: V}, sweep: {K: [V…]}}]`),
/// resolving scenario paths relative to the suite file; `overrides` apply to every scenario.
Suite load_suite(const std::filesystem::path& path, const std::vector<std::string>& overrides = {},
                 const ScenarioVocabulary& vocabulary = {});

/// Same, from a parsed document whose scenario paths are relative to `base`.
Suite suite_from_document(YamlDocument document, const std::filesystem::path& base,
                          const std::vector<std::string>& overrides = {}, const ScenarioVocabulary& vocabulary = {});

/// A one-scenario suite (for `freeplay run SCENARIO`).
Suite single_scenario_suite(const std::filesystem::path& path, const std::vector<std::string>& overrides = {},
                            const ScenarioVocabulary& vocabulary = {});

/// True when the YAML file at `path` is a suite (has a top-level `suite:` key) rather than a scenario.
bool is_suite_file(const std::filesystem::path& path);

}  // namespace freeplay::scenario
