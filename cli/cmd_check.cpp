// `freeplay check RUN --baseline FILE.yaml [--junit FILE.xml]` (regression gates) and
// `freeplay baseline RUN --out FILE.yaml` (a baseline from a run).

#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "command_registry.hpp"
#include "freeplay/analysis/baseline.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"

namespace freeplay::cli {
namespace {

struct CheckOptions {
  std::string run;
  std::string baseline;
  std::string junit;
  int resamples = 2000;
  std::uint64_t seed = 1;
};

void check(const CheckOptions& o) {
  const auto run = analysis::load_run(o.run);
  const auto baseline = analysis::load_baseline(o.baseline);
  const auto report = analysis::check_run(run, baseline, o.resamples, o.seed);
  std::cout << analysis::check_table(report);
  if (!o.junit.empty()) {
    write_file_atomically(o.junit, analysis::junit_xml(report));
    std::cout << fmt::format("JUnit XML: {}\n", o.junit);
  }
  if (report.failures() > 0) fail_with(1);
}

struct BaselineCommandOptions {
  std::string run;
  std::string out;
  std::optional<double> rel;
  std::optional<double> abs;
  std::string not_worse_than;
  double ci = 0.95;
  std::vector<std::string> metrics;
  std::vector<std::string> variants;
};

void make_baseline(const BaselineCommandOptions& o) {
  analysis::BaselineOptions options;
  options.metrics = o.metrics;
  options.variants = o.variants;
  const int bands = (o.rel ? 1 : 0) + (o.abs ? 1 : 0) + (o.not_worse_than.empty() ? 0 : 1);
  if (bands > 1) throw InputError("give one band", "--rel/--abs/--not-worse-than", "one of them");
  if (o.abs) {
    options.kind = analysis::BandKind::Absolute;
    options.width = *o.abs;
  } else if (!o.not_worse_than.empty()) {
    options.kind = analysis::BandKind::NotWorseThan;
    options.direction = o.not_worse_than == "higher_is_better" ? analysis::Direction::HigherIsBetter
                                                               : analysis::Direction::LowerIsBetter;
    options.confidence = o.ci;
  } else if (o.rel) {
    options.width = *o.rel;
  }
  const auto run = analysis::load_run(o.run);
  const auto baseline = analysis::make_baseline(run, options, run.program_version);
  write_file_atomically(o.out, analysis::baseline_yaml(baseline));
  std::cout << fmt::format("wrote {} gates for {} variant(s) to {}\n", baseline.gates.size(),
                           options.variants.empty() ? run.variants.size() : options.variants.size(), o.out);
}

const RegisterCommand check_command(71, [](CLI::App& program) {
  auto o = std::make_shared<CheckOptions>();
  auto* cmd = program.add_subcommand("check", "Check a run against a baseline's regression gates");
  cmd->add_option("run", o->run, "Run folder")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--baseline", o->baseline, "Baseline YAML file (see `freeplay baseline`)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--junit", o->junit, "Also write JUnit XML (one testsuite per variant, one testcase per gate)");
  cmd->add_option("--resamples", o->resamples, "Bootstrap resamples for not_worse_than gates")->capture_default_str();
  cmd->add_option("--seed", o->seed, "Bootstrap seed")->capture_default_str();
  cmd->footer("Exit status: 0 when every gate passes, 1 when any fails, 2 on bad input (malformed baseline, a\n"
              "variant or metric the run lacks).");
  cmd->callback([o] { check(*o); });
});

const RegisterCommand baseline_command(72, [](CLI::App& program) {
  auto o = std::make_shared<BaselineCommandOptions>();
  auto* cmd = program.add_subcommand("baseline", "Write a baseline (expected values and bands) from a run");
  cmd->add_option("run", o->run, "Run folder")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--out", o->out, "Baseline YAML file to write")->required();
  cmd->add_option("--rel", o->rel, "Relative band for every gate (default 0.25; metrics expected at 0 get an "
                                   "absolute band of 3 standard errors)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--abs", o->abs, "Absolute band for every gate")->check(CLI::NonNegativeNumber);
  cmd->add_option("--not-worse-than", o->not_worse_than, "Not-worse-than gates in this direction")
      ->check(CLI::IsMember({"higher_is_better", "lower_is_better"}));
  cmd->add_option("--ci", o->ci, "CI level of not-worse-than gates")->capture_default_str()->check(CLI::Range(0.5, 0.9999));
  cmd->add_option("--metric", o->metrics, "Metric name or glob to gate (repeatable; default: all)");
  cmd->add_option("--variant", o->variants, "Variant to gate (repeatable; default: all)");
  cmd->footer("Exit status: 0, or 2 on bad input.");
  cmd->callback([o] { make_baseline(*o); });
});

}  // namespace
}  // namespace freeplay::cli
