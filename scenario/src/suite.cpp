#include "freeplay/scenario/suite.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <limits>
#include <set>

namespace freeplay::scenario {

namespace {

using S = Schema;

std::shared_ptr<const Schema> suite_schema() {
  const auto entry = S::map({
      required("scenario", S::string(), "scenario file, relative to the suite file"),
      optional("episodes", S::integer(1, 1000000), "episodes of this entry (overrides the scenario's)"),
      optional("seed", S::integer(0, std::numeric_limits<long long>::max()), "root seed of this entry"),
      optional("set", S::dictionary(S::any()), "KEY.PATH: VALUE overrides"),
      optional("sweep", S::dictionary(S::list(S::any(), 1)), "KEY.PATH: [values…], one variant per combination"),
  });
  return S::map({
      required("suite", S::string(), "suite name"),
      with_default("description", S::string(), "\"\""),
      required("scenarios", S::list(entry, 1)),
  });
}

std::string scalar_text(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter e;
  e << YAML::Flow << node;
  return e.c_str();
}

}  // namespace

int Suite::total_episodes() const {
  int total = 0;
  for (const auto& v : variants) total += v.scenario.episodes;
  return total;
}

bool is_suite_file(const std::filesystem::path& path) {
  const auto doc = load_yaml_file(path);
  return doc.root.IsMap() && doc.root["suite"].IsDefined();
}

Suite load_suite(const std::filesystem::path& path, const std::vector<std::string>& overrides,
                 const ScenarioVocabulary& vocabulary) {
  return suite_from_document(load_yaml_file(path), path.parent_path(), overrides, vocabulary);
}

Suite suite_from_document(YamlDocument doc, const std::filesystem::path& base,
                          const std::vector<std::string>& overrides, const ScenarioVocabulary& vocabulary) {
  ValidationErrors errors;
  if (!doc.root.IsDefined() || doc.root.IsNull()) {
    throw InputError("the file is empty; a suite needs 'suite' and 'scenarios'", {}, {}, {doc.file, 1, 1});
  }
  suite_schema()->validate(doc.root, "", doc.file, errors);
  errors.throw_if_any();

  Suite suite;
  suite.file = doc.file;
  suite.name = doc.root["suite"].as<std::string>();
  suite.description = doc.root["description"].as<std::string>();
  std::set<std::string> ids;
  const auto entries = doc.root["scenarios"];
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const auto entry = entries[i];
    const std::string key = fmt::format("scenarios[{}]", i);
    const auto scenario_path = base / entry["scenario"].as<std::string>();
    std::error_code error;  // e.g. a name too long for the file system: reported, never thrown
    const auto type = std::filesystem::status(scenario_path, error).type();
    if (type != std::filesystem::file_type::regular) {
      std::string problem = fmt::format("scenario file '{}' does not exist", scenario_path.string());
      if (type != std::filesystem::file_type::not_found && error) {
        problem = fmt::format("scenario file '{}' cannot be read: {}", scenario_path.string(), error.message());
      } else if (type != std::filesystem::file_type::not_found) {
        problem = fmt::format("scenario '{}' is not a file", scenario_path.string());
      }
      errors.add(InputError(problem, key + ".scenario", "an existing file, relative to the suite file",
                            location_of(entry["scenario"], doc.file)));
      continue;
    }
    std::vector<std::string> entry_overrides;
    if (entry["episodes"].IsDefined()) entry_overrides.push_back("episodes=" + entry["episodes"].Scalar());
    if (entry["seed"].IsDefined()) entry_overrides.push_back("seed=" + entry["seed"].Scalar());
    if (entry["set"].IsDefined()) {
      for (const auto& kv : entry["set"]) {
        entry_overrides.push_back(kv.first.as<std::string>() + "=" + scalar_text(kv.second));
      }
    }
    // Cartesian product of the sweep axes, in file order.
    std::vector<std::pair<std::string, std::vector<std::string>>> axes;
    if (entry["sweep"].IsDefined()) {
      for (const auto& kv : entry["sweep"]) {
        std::vector<std::string> values;
        for (const auto& v : kv.second) values.push_back(scalar_text(v));
        axes.emplace_back(kv.first.as<std::string>(), values);
      }
    }
    std::vector<std::vector<std::string>> combos = {{}};
    for (const auto& [axis_key, values] : axes) {
      std::vector<std::vector<std::string>> next;
      for (const auto& combo : combos) {
        for (const auto& v : values) {
          auto extended = combo;
          extended.push_back(axis_key + "=" + v);
          next.push_back(extended);
        }
      }
      combos = next;
    }
    for (const auto& combo : combos) {
      auto all = entry_overrides;
      all.insert(all.end(), combo.begin(), combo.end());
      all.insert(all.end(), overrides.begin(), overrides.end());
      try {
        auto scenario = load_scenario(scenario_path, all, vocabulary);
        std::string id = scenario.name;
        if (!combo.empty()) id += fmt::format("[{}]", fmt::join(combo, ","));
        if (!ids.insert(id).second) {
          errors.add(InputError(fmt::format("two entries expand to the same variant '{}'", id), key, {},
                                location_of(entry, doc.file)));
          continue;
        }
        suite.variants.push_back({id, std::move(scenario)});
      } catch (const InputError& e) {
        errors.add(InputError(fmt::format("{} (from {})", e.what(), key), key, {}, location_of(entry, doc.file)));
      }
    }
  }
  errors.throw_if_any();
  return suite;
}

Suite single_scenario_suite(const std::filesystem::path& path, const std::vector<std::string>& overrides,
                            const ScenarioVocabulary& vocabulary) {
  Suite suite;
  auto scenario = load_scenario(path, overrides, vocabulary);
  suite.name = scenario.name;
  suite.description = scenario.description;
  suite.file = path.string();
  suite.variants.push_back({scenario.name, std::move(scenario)});
  return suite;
}

}  // namespace freeplay::scenario
