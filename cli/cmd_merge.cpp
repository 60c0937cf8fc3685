// `freeplay merge DIR… --out DIR`: joins the run folders of a suite's shards into the single-machine run.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <iostream>
#include <memory>

#include "command_registry.hpp"
#include "freeplay/analysis/merge.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "vocabulary.hpp"

namespace freeplay::cli {
namespace {

struct MergeOptions {
  std::vector<std::string> inputs;
  std::string out;
  std::string suite;
  std::vector<std::string> overrides;
  std::string title;
};

void merge(const MergeOptions& o) {
  std::optional<results::ExpectedRun> expected;
  if (!o.suite.empty()) {
    const auto suite = scenario::is_suite_file(o.suite)
                           ? scenario::load_suite(o.suite, o.overrides, scenario_vocabulary())
                           : scenario::single_scenario_suite(o.suite, o.overrides, scenario_vocabulary());
    expected = runner::expected_run(suite, o.title);
  }
  const std::vector<std::filesystem::path> inputs(o.inputs.begin(), o.inputs.end());
  const auto report = analysis::merge_runs(inputs, o.out, expected);
  for (const auto& w : report.warnings) spdlog::warn("{}", w);
  std::cout << fmt::format("merged {} episodes ({} per-episode files) from {} run folders into {}\n", report.episodes,
                           report.files, report.inputs, report.out.string());
}

const RegisterCommand merge_command(73, [](CLI::App& program) {
  auto o = std::make_shared<MergeOptions>();
  auto* cmd = program.add_subcommand("merge", "Join the run folders of a suite's shards into one run");
  cmd->add_option("dirs", o->inputs, "Shard run folders (from `freeplay suite SUITE --shard I/N`)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out", o->out, "Merged run folder (must not exist, or be empty)")->required();
  cmd->add_option("--suite", o->suite, "The suite the shards ran (needed only when they have no run.json)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", o->overrides, "The --set overrides the shards ran with (with --suite)");
  cmd->add_option("--title", o->title, "Heading of summary.md (with --suite; default: the suite name)");
  cmd->footer("Refuses (exit status 2, nothing written) duplicate, missing or unknown episodes, shards of different\n"
              "suites or overrides, and configuration-hash mismatches. The merged episodes.jsonl, summary.csv and\n"
              "summary.md equal a single-machine run of the suite, except each episode's wall_s.");
  cmd->callback([o] { merge(*o); });
});

}  // namespace
}  // namespace freeplay::cli
