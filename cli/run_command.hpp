#pragma once
// `freeplay run` / `freeplay suite` as a function, for commands built on a suite run (`freeplay dataset`).

#include <cstdint>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace freeplay::cli {

/// The options of `freeplay run` and `freeplay suite`.
struct RunCommandOptions {
  std::string file;                      ///< scenario or suite YAML
  std::optional<int> episodes;           ///< episodes per scenario (override)
  std::optional<std::uint64_t> seed;     ///< root seed (override)
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));  ///< worker threads
  std::string out;                       ///< run folder (empty: runs/<time>-<name> or the unfinished run)
  std::vector<std::string> overrides;    ///< --set KEY.PATH=VALUE
  std::string shard;                     ///< I/N
  bool quiet = false;                    ///< no progress, no summary
  bool no_summary = false;               ///< no summary on the terminal
  bool record = false;                   ///< record every episode (as `record: true`)
  std::string events = "auto";           ///< event logs: auto, all, gz or none (see `--events`)
};

/// Runs (or resumes) the episodes of a scenario or suite into a run folder; exits 130 through CLI11 when
/// interrupted. `suite_command`: refuse a scenario file.
void run_command(const RunCommandOptions& o, bool suite_command);

}  // namespace freeplay::cli
