#pragma once
// Joining the run folders of the shards of one suite into the run a single machine would have written:
// duplicates, missing or unknown episodes, configuration mismatches and different suites are refused.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/results/run_folder.hpp"

namespace freeplay::analysis {

/// What a merge did.
struct MergeReport {
  std::filesystem::path out;          ///< the merged folder
  int inputs = 0;                     ///< run folders joined
  int episodes = 0;                   ///< episodes in the merged run
  int files = 0;                      ///< per-episode files copied (events, annotations, …)
  std::vector<std::string> warnings;  ///< e.g. different program versions
};

/// Joins the run folders `inputs` into `out` (which must not exist, or be empty): episodes.jsonl sorted like a
/// single-machine run (suite variant order, then episode index), every per-episode file copied, summaries
/// regenerated, run.json written. The expected episodes come from `expected` or else from the inputs' run.json.
/// Throws InputError listing every problem (nothing is written then): not a run folder, run.json of different
/// suites or overrides, the same shard twice, a duplicate, missing or unknown episode, a configuration-hash
/// mismatch, or a per-episode file that differs between inputs.
MergeReport merge_runs(const std::vector<std::filesystem::path>& inputs, const std::filesystem::path& out,
                       const std::optional<results::ExpectedRun>& expected = std::nullopt);

}  // namespace freeplay::analysis
