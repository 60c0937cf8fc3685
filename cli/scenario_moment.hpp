#pragma once
// `--scenario FILE --time T [--stage S] [--seed N] [--set K=V]` of `freeplay render` and `freeplay screen`: one
// moment of one episode of a scenario.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/runner/episode_capture.hpp"

namespace freeplay::cli {

/// The command-line choice of a moment of an episode.
struct MomentOptions {
  std::string scenario;                    ///< scenario file (empty: not in scenario mode)
  std::optional<double> time;              ///< seconds since the stage started
  std::string stage = "freeplay";          ///< protocol stage the time counts from
  std::vector<std::string> overrides;      ///< `--set KEY.PATH=VALUE`
};

/// Adds --scenario, --time, --stage and --set to `command` (the command keeps its own --seed).
void add_moment_options(CLI::App& command, MomentOptions& options);

/// Loads the scenario (validated, with overrides), picks the seed (default: episode 0's), runs the episode to the
/// moment and calls `capture` there; returns a one-line description ("scenario X, seed N, free play 12.3 s").
std::string capture_moment(const MomentOptions& options, std::optional<std::uint64_t> seed,
                           const std::function<void(const scenario::Scenario&, const runner::EpisodeSnapshot&)>& capture);

}  // namespace freeplay::cli
