// `freeplay validate FILE…` and `freeplay list scenarios|policies`.

#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/scenario/suite.hpp"
#include "vocabulary.hpp"

namespace freeplay::cli {
namespace {

struct ValidateOptions {
  std::vector<std::string> files;
  std::vector<std::string> overrides;
};

void validate(const ValidateOptions& options) {
  int bad = 0;
  for (const auto& file : options.files) {
    try {
      const auto suite = scenario::is_suite_file(file)
                             ? scenario::load_suite(file, options.overrides, scenario_vocabulary())
                             : scenario::single_scenario_suite(file, options.overrides, scenario_vocabulary());
      std::cout << fmt::format("ok      {} ({} variant{}, {} episodes)\n", file, suite.variants.size(),
                               suite.variants.size() == 1 ? "" : "s", suite.total_episodes());
    } catch (const InputError& e) {
      ++bad;
      std::cout << fmt::format("invalid {}\n", file);
      std::cerr << "error: " << e.what() << "\n";
    }
  }
  if (bad > 0) fail_with(2);
}

const RegisterCommand validate_command(40, [](CLI::App& program) {
  auto options = std::make_shared<ValidateOptions>();
  auto* cmd = program.add_subcommand("validate", "Check scenario and suite files completely, without running them");
  cmd->add_option("files", options->files, "Scenario or suite YAML files")->required()->check(CLI::ExistingFile);
  cmd->add_option("--set", options->overrides, "Override KEY.PATH=VALUE before validating (repeatable)");
  cmd->footer("Exit status: 0 when every file is valid, 2 otherwise (each error names file:line:column and key).");
  cmd->callback([options] { validate(*options); });
});

void list_scenarios(bool json) {
  nlohmann::json out = nlohmann::json::array();
  std::vector<std::filesystem::path> files;
  if (std::filesystem::exists(scenarios_dir())) {
    for (const auto& entry : std::filesystem::directory_iterator(scenarios_dir())) {
      if (entry.path().extension() == ".yaml") files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    nlohmann::json row{{"file", f.string()}};
    try {
      if (scenario::is_suite_file(f)) {
        const auto suite = scenario::load_suite(f, {}, scenario_vocabulary());
        row["kind"] = "suite";
        row["name"] = suite.name;
        row["description"] = suite.description;
        row["episodes"] = suite.total_episodes();
      } else {
        const auto s = scenario::load_scenario(f, {}, scenario_vocabulary());
        row["kind"] = "scenario";
        row["name"] = s.name;
        row["description"] = s.description;
        row["episodes"] = s.episodes;
      }
    } catch (const InputError& e) {
      row["kind"] = "invalid";
      row["description"] = e.what();
    }
    out.push_back(row);
  }
  if (json) {
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::cout << fmt::format("{:<26} {:<9} {:>8}  {}\n", "file", "kind", "episodes", "description");
  for (const auto& row : out) {
    std::cout << fmt::format("{:<26} {:<9} {:>8}  {}\n", std::filesystem::path(row["file"].get<std::string>()).filename().string(),
                             row["kind"].get<std::string>(), row.value("episodes", 0),
                             row.value("description", ""));
  }
}

void list_policies(bool json) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : policies::registered_policies()) out.push_back({{"name", p.name}, {"description", p.description}});
  if (json) {
    std::cout << out.dump(2) << "\n";
    return;
  }
  for (const auto& p : policies::registered_policies()) std::cout << fmt::format("{:<10} {}\n", p.name, p.description);
}

const RegisterLister scenarios_lister("scenarios", "Scenario and suite files shipped in scenarios/", list_scenarios);
const RegisterLister policies_lister("policies", "Registered robot play policies", list_policies);

}  // namespace
}  // namespace freeplay::cli
