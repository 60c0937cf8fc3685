// `freeplay calibrate`: simulate a synthetic-child population and compare it with the PInSoRo targets;
// `--fit` runs the documented fitting procedure and writes the fitted parameters atomically.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <array>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "command_registry.hpp"
#include "freeplay/agents/calibration.hpp"
#include "freeplay/core/assets.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/runner/population.hpp"
#include "freeplay/scenario/scenario.hpp"
#include "vocabulary.hpp"

namespace freeplay::cli {
namespace {

struct CalibrateOptions {
  std::string condition = "both";
  int sessions = 200;
  std::uint64_t seed = 2017;
  std::string params_file;
  std::string output;
  bool json = false;
  bool fit = false;
  int threads = 1;
  int rounds = 4;
  int fit_sessions = 120;
  bool full = false;
  bool check = false;
  std::string cc_scenario;
  std::string cr_scenario;
  std::vector<std::string> policies;
  std::vector<std::string> fit_only;
};

/// A shipped scenario: `name` in ./scenarios, else beside the assets folder (the repository's scenarios/).
std::filesystem::path shipped_scenario(const std::string& name) {
  const std::filesystem::path local = std::filesystem::path("scenarios") / name;
  if (std::filesystem::exists(local)) return local;
  return asset_path(".").parent_path().parent_path() / "scenarios" / name;
}

/// The child-child scenario of `--full` (`--cc-scenario`, else the shipped one).
std::filesystem::path cc_scenario_file(const CalibrateOptions& o) {
  return o.cc_scenario.empty() ? shipped_scenario("child-child.yaml") : std::filesystem::path(o.cc_scenario);
}

/// The child-robot scenario of `--full` (`--cr-scenario`, else the shipped asocial one).
std::filesystem::path cr_scenario_file(const CalibrateOptions& o) {
  return o.cr_scenario.empty() ? shipped_scenario("child-robot-asocial.yaml") : std::filesystem::path(o.cr_scenario);
}

/// Runs `episodes` full episodes of a scenario (with `overrides`), printing progress on stderr.
std::vector<agents::SessionResult> full_population(const std::filesystem::path& file,
                                                   const std::vector<std::string>& overrides, int episodes,
                                                   std::uint64_t seed, int threads, const runner::SharedModels& models) {
  std::vector<std::string> sets = overrides;
  sets.push_back(fmt::format("seed={}", seed));
  const scenario::Scenario scenario = scenario::load_scenario(file, sets, scenario_vocabulary());
  std::string label = scenario.name;
  for (const auto& o : overrides) label += " " + o;
  const auto progress = [&](int done) {
    if (done == episodes || done % 10 == 0) std::cerr << fmt::format("\r{}: {}/{} episodes", label, done, episodes) << std::flush;
    if (done == episodes) std::cerr << "\n";
  };
  return runner::run_population(scenario, episodes, threads, models, progress);
}

/// Child-robot social-engagement shares of the purple child per policy (the same children: same seeds).
std::string policy_share_table(const std::vector<std::pair<std::string, agents::PopulationStats>>& by_policy) {
  std::string out = fmt::format("\nchild-robot label shares by robot policy (per-child mean share; predictions, not fitted)\n{:<18}",
                                "label");
  for (const auto& [policy, stats] : by_policy) out += fmt::format(" {:>10}", policy);
  out += "\n";
  for (const agents::Axis axis : agents::kAxes) {
    const auto a = static_cast<std::size_t>(axis);
    for (std::size_t j = 0; j < agents::label_count(axis); ++j) {
      out += fmt::format("{:<18}", agents::label_name(axis, j));
      for (const auto& entry : by_policy) out += fmt::format(" {:>10.3f}", entry.second.labels.share[a][j]);
      out += "\n";
    }
  }
  out += fmt::format("{:<18}", "duration (min)");
  for (const auto& entry : by_policy) out += fmt::format(" {:>10.2f}", entry.second.duration.mean_min);
  static constexpr std::array<const char*, agents::kAxisCount> kAgreementRow = {"coded=own task", "coded=own social",
                                                                                "coded=own attitude"};
  for (const agents::Axis axis : agents::kAxes) {
    out += "\n" + fmt::format("{:<18}", kAgreementRow[static_cast<std::size_t>(axis)]);
    for (const auto& entry : by_policy) {
      out += fmt::format(" {:>10.3f}", entry.second.labels.coder_agreement_by_axis[static_cast<std::size_t>(axis)]);
    }
  }
  return out + "\n";
}

void run_calibrate(const CalibrateOptions& o) {
  if (o.condition != "cc" && o.condition != "cr" && o.condition != "both") {
    throw InputError("unknown condition '" + o.condition + "'", "--condition", "cc, cr, both");
  }
  if (o.sessions < 2) throw InputError("need at least 2 sessions", "--sessions", ">= 2");
  const std::filesystem::path params_path =
      o.params_file.empty() ? asset_path("agents/child-model.yaml") : std::filesystem::path(o.params_file);
  agents::ChildModelParams params = agents::load_child_model_params(params_path);

  if (o.fit) {
    agents::FitOptions fit;
    fit.sessions = o.fit_sessions;
    fit.seed = o.seed;
    fit.rounds = o.rounds;
    fit.threads = o.threads;
    fit.log = [](const std::string& line) { spdlog::info("fit: {}", line); };
    fit.only = o.fit_only;
    if (o.full) {
      // Fit on the product itself: every evaluation runs full episodes of both scenarios on the fit seed.
      fit.simulate = [&o](const agents::ChildModelParams& trial) {
        runner::SharedModels models = runner::SharedModels::shipped();
        models.child_params = std::make_shared<const agents::ChildModelParams>(trial);
        return std::pair{agents::summarise(full_population(cc_scenario_file(o), {}, o.fit_sessions, o.seed,
                                                           o.threads, models),
                                           agents::Condition::ChildChild),
                         agents::summarise(full_population(cr_scenario_file(o), {}, o.fit_sessions, o.seed,
                                                           o.threads, models),
                                           agents::Condition::ChildRobot)};
      };
    }
    const agents::FitResult result = agents::fit_child_model(params, fit);
    params = result.params;
    const std::filesystem::path out = o.output.empty() ? params_path : std::filesystem::path(o.output);
    const std::string header = fmt::format(
        "Synthetic child model (freeplay::agents), fitted by `freeplay calibrate --fit` (seed {}, {} sessions per\n"
        "condition per evaluation, {} rounds of the coordinate search). Fit loss {:.2f} -> {:.2f}; checked rows\n"
        "outside their bands on the fit seed {} -> {}.",
        o.seed, o.fit_sessions, o.rounds, result.loss_before, result.loss_after, result.outside_before,
        result.outside_after);
    write_file_atomically(out, agents::child_model_params_to_yaml(params, header));
    spdlog::info("wrote fitted parameters to {}", out.string());
  }

  std::optional<agents::PopulationStats> cc;
  std::optional<agents::PopulationStats> cr;
  std::vector<std::pair<std::string, agents::PopulationStats>> by_policy;
  if (o.full) {
    runner::SharedModels models = runner::SharedModels::shipped();
    models.child_params = std::make_shared<const agents::ChildModelParams>(params);
    const std::filesystem::path cc_file = cc_scenario_file(o);
    const std::filesystem::path cr_file = cr_scenario_file(o);
    if (o.condition != "cr") {
      cc = agents::summarise(full_population(cc_file, {}, o.sessions, o.seed, o.threads, models), agents::Condition::ChildChild);
    }
    if (o.condition != "cc") {
      cr = agents::summarise(full_population(cr_file, {}, o.sessions, o.seed, o.threads, models), agents::Condition::ChildRobot);
      const std::string scenario_policy = scenario::load_scenario(cr_file, {}, scenario_vocabulary()).robot.policy;
      if (!o.policies.empty()) by_policy.emplace_back(scenario_policy, *cr);
      for (const auto& policy : o.policies) {
        if (policy == scenario_policy) continue;  // the scenario's own policy ran above, on the same seeds
        by_policy.emplace_back(policy, agents::summarise(full_population(cr_file, {"robot.policy=" + policy},
                                                                         o.sessions, o.seed, o.threads, models),
                                                         agents::Condition::ChildRobot));
      }
    }
  } else if (o.condition != "cr") {
    cc = agents::summarise(agents::simulate_population(params, agents::Condition::ChildChild, o.sessions, o.seed,
                                                       o.threads),
                           agents::Condition::ChildChild);
  }
  if (!o.full && o.condition != "cc") {
    cr = agents::summarise(agents::simulate_population(params, agents::Condition::ChildRobot, o.sessions, o.seed,
                                                       o.threads),
                           agents::Condition::ChildRobot);
  }
  const auto rows = agents::compare_with_targets(cc ? &*cc : nullptr, cr ? &*cr : nullptr);
  int outside = 0;
  for (const auto& r : rows) outside += r.within() ? 0 : 1;
  if (o.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& r : rows) {
      out.push_back({{"group", r.group}, {"statistic", r.name}, {"simulated", r.simulated}, {"target", r.target},
                     {"checked", r.checked}, {"lo", r.lo}, {"hi", r.hi}, {"within", r.within()}});
    }
    nlohmann::json policies = nlohmann::json::object();
    for (const auto& [policy, stats] : by_policy) {
      for (const agents::Axis axis : agents::kAxes) {
        for (std::size_t j = 0; j < agents::label_count(axis); ++j) {
          policies[policy]["share"][std::string(agents::axis_name(axis))][std::string(agents::label_name(axis, j))] =
              stats.labels.share[static_cast<std::size_t>(axis)][j];
        }
      }
      policies[policy]["duration_mean_min"] = stats.duration.mean_min;
      for (const agents::Axis axis : agents::kAxes) {
        policies[policy]["coder_agreement"][std::string(agents::axis_name(axis))] =
            stats.labels.coder_agreement_by_axis[static_cast<std::size_t>(axis)];
      }
    }
    std::cout << nlohmann::json{{"sessions", o.sessions}, {"seed", o.seed},     {"full", o.full},
                                {"outside", outside},     {"rows", out},        {"policies", policies}}
                     .dump(2)
              << "\n";
  } else {
    std::cout << fmt::format("{} sessions per condition ({}), seed {}, parameters {}\n", o.sessions,
                             o.full ? "full episodes" : "logic-only simulator", o.seed, params_path.string());
    std::cout << agents::format_comparison(rows);
    if (!by_policy.empty()) std::cout << policy_share_table(by_policy);
    std::cout << fmt::format("{} checked rows outside their bound\n", outside);
  }
  if (o.check && outside > 0) {
    std::cerr << fmt::format("calibration check failed: {} checked rows outside their PInSoRo bound\n", outside);
    throw CLI::RuntimeError(1);
  }
}

const RegisterCommand kRegister(60, [](CLI::App& program) {
  auto options = std::make_shared<CalibrateOptions>();
  auto* cmd = program.add_subcommand(
      "calibrate", "Simulate synthetic children and compare with the PInSoRo targets (or fit the parameters)");
  cmd->add_option("--condition", options->condition, "cc, cr or both")->capture_default_str();
  cmd->add_option("--sessions", options->sessions, "Sessions simulated per condition")->capture_default_str();
  cmd->add_option("--seed", options->seed, "Root seed of the population")->capture_default_str();
  cmd->add_option("--params", options->params_file, "Parameter YAML (default: assets/agents/child-model.yaml)");
  cmd->add_option("--threads", options->threads, "Worker threads")->capture_default_str();
  cmd->add_flag("--json", options->json, "Print JSON instead of a table");
  cmd->add_flag("--fit", options->fit, "Run the fitting procedure first and write the fitted parameters");
  cmd->add_option("--output", options->output, "Where --fit writes (default: the --params file)");
  cmd->add_option("--rounds", options->rounds, "Fit: sweeps of the coordinate search over the fitted parameters")
      ->capture_default_str();
  cmd->add_option("--fit-sessions", options->fit_sessions, "Fit: sessions per condition per evaluation")
      ->capture_default_str();
  cmd->add_option("--fit-only", options->fit_only,
                  "Fit: move only these fitted parameters (e.g. drives.decay_per_min "
                  "expression.noplay_speech_share; a wrong name lists them all); default: all of them");
  cmd->add_flag("--full", options->full,
                "Run full episodes (sandtray, policies, planner, robot) instead of the logic-only simulator; with "
                "--fit, every fit evaluation runs --fit-sessions full episodes per condition on --seed");
  cmd->add_flag("--check", options->check, "Exit with status 1 when a checked row lies outside its PInSoRo bound");
  cmd->add_option("--cc-scenario", options->cc_scenario, "--full: child-child scenario (default scenarios/child-child.yaml)");
  cmd->add_option("--cr-scenario", options->cr_scenario,
                  "--full: child-robot scenario (default scenarios/child-robot-asocial.yaml)");
  cmd->add_option("--policies", options->policies,
                  "--full: also run the child-robot scenario with these robot policies and print the children's "
                  "social-engagement shares side by side (e.g. asocial idle social)");
  cmd->callback([options] { run_calibrate(*options); });
});

}  // namespace
}  // namespace freeplay::cli
