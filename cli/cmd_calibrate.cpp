// `freeplay calibrate`: simulate a synthetic-child population and compare it with the PInSoRo targets;
// `--fit` runs the documented fitting procedure and writes the fitted parameters atomically.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "command_registry.hpp"
#include "freeplay/agents/calibration.hpp"
#include "freeplay/core/assets.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"

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
  int rounds = 3;
  int evaluations = 60;
  int fit_sessions = 120;
};

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
    fit.duration_evaluations = o.evaluations;
    fit.threads = o.threads;
    fit.log = [](const std::string& line) { spdlog::info("fit: {}", line); };
    const agents::FitResult result = agents::fit_child_model(params, fit);
    params = result.params;
    const std::filesystem::path out = o.output.empty() ? params_path : std::filesystem::path(o.output);
    const std::string header = fmt::format(
        "Synthetic child model (freeplay::agents), fitted by `freeplay calibrate --fit` (seed {}, {} sessions per\n"
        "condition per evaluation, {} rounds). Duration loss {:.3f} -> {:.3f}; label loss {:.3f} -> {:.3f}.",
        o.seed, o.fit_sessions, o.rounds, result.duration_loss_before, result.duration_loss_after,
        result.label_loss_before, result.label_loss_after);
    write_file_atomically(out, agents::child_model_params_to_yaml(params, header));
    spdlog::info("wrote fitted parameters to {}", out.string());
  }

  std::optional<agents::PopulationStats> cc;
  std::optional<agents::PopulationStats> cr;
  if (o.condition != "cr") {
    cc = agents::summarise(agents::simulate_population(params, agents::Condition::ChildChild, o.sessions, o.seed,
                                                       o.threads),
                           agents::Condition::ChildChild);
  }
  if (o.condition != "cc") {
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
    std::cout << nlohmann::json{{"sessions", o.sessions}, {"seed", o.seed}, {"outside", outside}, {"rows", out}}.dump(2)
              << "\n";
  } else {
    std::cout << fmt::format("{} sessions per condition, seed {}, parameters {}\n", o.sessions, o.seed,
                             params_path.string());
    std::cout << agents::format_comparison(rows);
    std::cout << fmt::format("{} checked rows outside their bound\n", outside);
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
  cmd->add_option("--rounds", options->rounds, "Fit: outer rounds")->capture_default_str();
  cmd->add_option("--evaluations", options->evaluations, "Fit: Nelder–Mead evaluations per round")
      ->capture_default_str();
  cmd->add_option("--fit-sessions", options->fit_sessions, "Fit: sessions per condition per evaluation")
      ->capture_default_str();
  cmd->callback([options] { run_calibrate(*options); });
});

}  // namespace
}  // namespace freeplay::cli
