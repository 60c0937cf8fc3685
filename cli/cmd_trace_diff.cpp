// `freeplay trace-diff A B [--tol X]`: compares controller golden traces (two trace files, or every trace of two run
// folders) checkpoint by checkpoint; bit-exact on the same machine kind, within a tolerance across machines.

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <set>

#include "command_registry.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/runner/controller_episode.hpp"

namespace freeplay::cli {
namespace {

namespace fs = std::filesystem;

struct TraceDiffOptions {
  std::string a;
  std::string b;
  double tolerance = 1e-6;
};

// The trace files to compare: A and B themselves, or traces/*.jsonl of two run folders matched by name.
std::vector<std::pair<fs::path, fs::path>> trace_pairs(const fs::path& a, const fs::path& b) {
  if (fs::is_regular_file(a) && fs::is_regular_file(b)) return {{a, b}};
  if (!fs::is_directory(a / "traces") || !fs::is_directory(b / "traces")) {
    throw InputError(fmt::format("'{}' and '{}' are not both trace files or both run folders with traces/", a.string(),
                                 b.string()),
                     "A B", "two traces/<id>.jsonl files, or two run folders of controller suites");
  }
  std::set<std::string> names_a;
  std::set<std::string> names_b;
  for (const auto& e : fs::directory_iterator(a / "traces")) names_a.insert(e.path().filename().string());
  for (const auto& e : fs::directory_iterator(b / "traces")) names_b.insert(e.path().filename().string());
  if (names_a != names_b) {
    throw InputError("the two runs hold different traces", "A B", "runs of the same controller suite");
  }
  std::vector<std::pair<fs::path, fs::path>> out;
  for (const auto& name : names_a) out.emplace_back(a / "traces" / name, b / "traces" / name);
  return out;
}

void trace_diff(const TraceDiffOptions& o) {
  if (!(o.tolerance >= 0.0)) throw InputError("the tolerance must be ≥ 0", "--tol", "a number ≥ 0, e.g. 1e-6");
  int different = 0;
  for (const auto& [pa, pb] : trace_pairs(o.a, o.b)) {
    const auto ta = runner::load_trace(pa);
    const auto tb = runner::load_trace(pb);
    const auto diff = runner::diff_traces(ta, tb, o.tolerance);
    std::cout << fmt::format("== {} vs {}\n", pa.string(), pb.string());
    if (ta.machine != tb.machine) {
      std::cout << fmt::format("machine kinds differ ('{}' vs '{}'): expect tolerance, not bit-exact equality\n",
                               ta.machine, tb.machine);
    }
    std::cout << runner::trace_diff_text(diff, o.tolerance);
    if (!diff.within_tolerance) ++different;
  }
  if (different > 0) {
    std::cout << fmt::format("{} trace(s) differ beyond the tolerance\n", different);
    fail_with(1);
  }
}

const RegisterCommand trace_diff_command(76, [](CLI::App& program) {
  auto o = std::make_shared<TraceDiffOptions>();
  auto* cmd = program.add_subcommand("trace-diff", "Compare controller golden traces with a tolerance");
  cmd->add_option("A", o->a, "A trace file (traces/<id>.jsonl) or a run folder of a controller suite")->required();
  cmd->add_option("B", o->b, "The trace file or run folder to compare with")->required();
  cmd->add_option("--tol", o->tolerance, "Largest allowed |difference| of any qpos (rad, m) or qvel value")
      ->capture_default_str();
  cmd->footer("Reports, per trace, whether it is bit-identical, the first checkpoint whose hash differs, the largest\n"
              "difference and the first value beyond the tolerance. Exit status 1 when any trace differs beyond it.");
  cmd->callback([o] { trace_diff(*o); });
});

}  // namespace
}  // namespace freeplay::cli
