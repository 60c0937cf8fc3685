// `freeplay compare RUN_A [RUN_B]`: every metric of two runs (or two variants of one run) side by side, with
// bootstrap CIs, effect sizes, Mann–Whitney U + Holm, and the paired analysis when the runs share seeds.

#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "command_registry.hpp"
#include "freeplay/analysis/compare.hpp"
#include "freeplay/core/error.hpp"

namespace freeplay::cli {
namespace {

struct CompareCommandOptions {
  std::vector<std::string> runs;
  std::vector<std::string> variants;
  analysis::CompareOptions compare;
  bool unpaired = false;
  bool json = false;
};

analysis::Sample sample_of(const analysis::RunData& run, const std::string& variant) {
  if (!run.has_variant(variant)) {
    throw InputError(fmt::format("the run '{}' has no variant '{}'", run.dir, variant), "--variant",
                     fmt::format("{}", fmt::join(run.variants, ", ")));
  }
  return {fmt::format("{} [{}]", run.dir, variant), run.of_variant(variant)};
}

/// Which samples to compare: see the command's footer.
std::vector<std::pair<analysis::Sample, analysis::Sample>> pairs_to_compare(const CompareCommandOptions& o) {
  if (o.runs.size() > 2) throw InputError("give one or two run folders", "RUN", "RUN_A [RUN_B]");
  if (o.variants.size() > 2) throw InputError("give at most two --variant", "--variant", "A [B]");
  const auto a = analysis::load_run(o.runs[0]);
  if (o.runs.size() == 1) {
    if (o.variants.size() != 2) {
      throw InputError("one run folder needs two --variant to compare", "--variant",
                       fmt::format("two of {}", fmt::join(a.variants, ", ")));
    }
    return {{sample_of(a, o.variants[0]), sample_of(a, o.variants[1])}};
  }
  const auto b = analysis::load_run(o.runs[1]);
  if (o.variants.size() == 2) return {{sample_of(a, o.variants[0]), sample_of(b, o.variants[1])}};
  if (o.variants.size() == 1) return {{sample_of(a, o.variants[0]), sample_of(b, o.variants[0])}};
  std::vector<std::pair<analysis::Sample, analysis::Sample>> out;
  for (const auto& v : a.variants) {
    if (b.has_variant(v)) out.emplace_back(sample_of(a, v), sample_of(b, v));
  }
  if (out.empty() && a.variants.size() == 1 && b.variants.size() == 1) {
    out.emplace_back(sample_of(a, a.variants[0]), sample_of(b, b.variants[0]));
  }
  if (out.empty()) {
    throw InputError("the runs share no variant", "--variant",
                     fmt::format("--variant A --variant B with A of {} and B of {}", fmt::join(a.variants, ", "),
                                 fmt::join(b.variants, ", ")));
  }
  return out;
}

void compare(CompareCommandOptions o) {
  o.compare.allow_paired = !o.unpaired;
  nlohmann::json all = nlohmann::json::array();
  bool first = true;
  for (const auto& [a, b] : pairs_to_compare(o)) {
    const auto comparison = analysis::compare_samples(a, b, o.compare);
    if (o.json) {
      all.push_back(analysis::comparison_json(comparison));
    } else {
      std::cout << (first ? "" : "\n") << analysis::comparison_table(comparison);
    }
    first = false;
  }
  if (o.json) std::cout << nlohmann::json{{"comparisons", all}}.dump(2) << "\n";
}

const RegisterCommand compare_command(70, [](CLI::App& program) {
  auto o = std::make_shared<CompareCommandOptions>();
  auto* cmd = program.add_subcommand("compare", "Compare the metrics of two runs or of two variants of one run");
  cmd->add_option("runs", o->runs, "RUN_A [RUN_B]: run folders")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--variant", o->variants, "Variant to compare (once: in both runs; twice: A then B)");
  cmd->add_option("--metric", o->compare.metrics, "Metric name or glob, e.g. 'metrics.label_share.*' (repeatable)");
  cmd->add_flag("--json", o->json, "Print JSON (every number) instead of the table");
  cmd->add_option("--confidence", o->compare.confidence, "Level of the bootstrap CIs")->capture_default_str();
  cmd->add_option("--alpha", o->compare.alpha, "Significance level for the Holm-adjusted p-values")
      ->capture_default_str();
  cmd->add_option("--resamples", o->compare.resamples, "Bootstrap resamples")->capture_default_str();
  cmd->add_option("--seed", o->compare.seed, "Bootstrap seed")->capture_default_str();
  cmd->add_flag("--unpaired", o->unpaired, "Never pair episodes by seed");
  cmd->footer(
      "B is compared against A (differences are B − A). Two runs: every variant they share (or --variant V in both,\n"
      "or --variant A --variant B across them). One run: --variant A --variant B. Episodes with the same seed (the\n"
      "same synthetic children) are paired: Wilcoxon signed-rank and a paired bootstrap CI are added.\n"
      "Exit status: 0, or 2 on bad input.");
  cmd->callback([o] { compare(*o); });
});

}  // namespace
}  // namespace freeplay::cli
