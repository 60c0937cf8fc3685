#pragma once
// Synthetic run folders for the analysis tests: episodes.jsonl records like `freeplay suite` writes, with
// per-child (per-seed) effects so that conditions sharing seeds are correlated (common random numbers).

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "freeplay/results/run_folder.hpp"

#include "../scratch_dir.hpp"

namespace freeplay::analysis::testing {

/// How to make one synthetic variant.
struct SyntheticVariant {
  std::string id;                  ///< variant id
  std::string policy;              ///< "asocial" / "social"
  int episodes = 20;               ///< episodes
  std::uint64_t scenario_seed = 2017;  ///< root seed (same seed = same children)
  double moves_per_min = 2.0;      ///< mean of metrics.robot_item_moves_per_min
  double cooperative = 0.30;       ///< mean of metrics.label_share.purple.cooperative
  std::uint64_t config_hash = 42;  ///< configuration hash
};

/// One episodes.jsonl record of a synthetic variant.
inline nlohmann::json synthetic_record(const SyntheticVariant& v, int index) {
  const auto seed = runner::episode_seed(v.scenario_seed, index);
  Rng child(seed);                                 // the same child in every condition with this seed
  Rng noise(seed ^ fnv1a64(v.id));                 // condition-specific noise
  const double engagement = child.normal(0.0, 1.0);
  nlohmann::json r;
  r["variant"] = v.id;
  r["scenario"] = v.id;
  r["condition"] = "child-robot";
  r["policy"] = v.policy;
  r["episode"] = index;
  r["episode_id"] = results::RunFolder::episode_file_id(v.id, index);
  r["seed"] = seed;
  r["config_hash"] = v.config_hash;
  r["program_version"] = "test";
  r["duration_s"] = 1100.0 + 300.0 * engagement + 60.0 * noise.normal(0.0, 1.0);
  r["ended_by"] = "quit";
  r["simulated_s"] = 1500.0;
  r["wall_s"] = 0.5;
  r["metrics"]["robot_item_moves_per_min"] = v.moves_per_min + 0.4 * engagement + 0.2 * noise.normal(0.0, 1.0);
  r["metrics"]["label_share"]["purple"]["cooperative"] = v.cooperative + 0.05 * engagement + 0.03 * noise.normal(0.0, 1.0);
  r["metrics"]["constant_zero"] = 0.0;
  return r;
}

/// Writes a run folder holding the given variants (episodes.jsonl only).
inline void write_synthetic_run(const std::filesystem::path& dir, const std::vector<SyntheticVariant>& variants,
                                const std::function<void(nlohmann::json&)>& edit = {}) {
  std::filesystem::create_directories(dir);
  std::string lines;
  for (const auto& v : variants) {
    for (int i = 0; i < v.episodes; ++i) {
      auto r = synthetic_record(v, i);
      if (edit) edit(r);
      lines += r.dump() + "\n";
    }
  }
  write_file_atomically(dir / "episodes.jsonl", lines);
}

/// A fresh, empty temporary folder for one test.
inline std::filesystem::path fresh_dir(const std::string& name) {
  return test_support::fresh_dir("analysis-" + name);
}

}  // namespace freeplay::analysis::testing
