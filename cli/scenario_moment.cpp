#include "scenario_moment.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "freeplay/core/error.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "vocabulary.hpp"

namespace freeplay::cli {

void add_moment_options(CLI::App& command, MomentOptions& options) {
  command.add_option("--scenario", options.scenario,
                     "Scenario file: show a moment of one of its episodes (with --time) instead of a fresh tray");
  command.add_option("--time", options.time, "With --scenario: seconds since the stage started (default stage: free play)");
  command.add_option("--stage", options.stage, "With --scenario: greeting, tutorial, freeplay or debriefing")
      ->capture_default_str();
  command.add_option("--set", options.overrides, "With --scenario: override a scenario value, KEY.PATH=VALUE");
}

std::string capture_moment(const MomentOptions& options, std::optional<std::uint64_t> seed,
                           const std::function<void(const scenario::Scenario&, const runner::EpisodeSnapshot&)>& capture) {
  if (!options.time) throw InputError("missing --time with --scenario", "--time", "seconds since the stage started");
  const auto scenario = scenario::load_scenario(options.scenario, options.overrides, scenario_vocabulary());
  const std::uint64_t episode_seed = seed ? *seed : runner::episode_seed(scenario.seed, 0);
  const auto models = runner::SharedModels::load_default();
  const runner::EpisodeMoment moment{options.stage, *options.time};
  spdlog::info("running {} (seed {}) to {:g} s of {}", scenario.name, episode_seed, moment.seconds, moment.stage);
  const auto at = runner::capture_episode_moment(scenario, episode_seed, models, moment,
                                                 [&](const runner::EpisodeSnapshot& s) { capture(scenario, s); });
  return fmt::format("scenario {}, seed {}, {} {:.1f} s (episode clock {:.1f} s)", scenario.name, episode_seed,
                     moment.stage == "freeplay" ? "free play" : moment.stage, at.stage_t, at.t);
}

}  // namespace freeplay::cli
