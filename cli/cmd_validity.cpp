// `freeplay validity`: the validity panel end to end. Runs the asocial and social robots and the degenerate ones
// (timetables, the social policy's yoked control, idle) on the same children, then gates them (docs/validity.md).

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>

#include "command_registry.hpp"
#include "freeplay/analysis/validity.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "run_command.hpp"
#include "vocabulary.hpp"

namespace freeplay::cli {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kPanelSeed = 4242;  // not the calibration's fit seed (2017): the panel is out of sample

/// The options of `freeplay validity`.
struct ValidityOptions {
  int sessions = 200;
  std::uint64_t seed = kPanelSeed;
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string out = "runs/validity";
  std::string junit;
  bool quiet = false;
};

/// One robot of the panel: its name (and run folder), its scenario file under scenarios/, and its role.
struct PanelRobot {
  const char* name;
  const char* scenario;
  bool degenerate;
};

// In run order: the social run comes first because the yoked control replays it.
constexpr PanelRobot kPanel[] = {
    {"social", "child-robot-social.yaml", false},    {"asocial", "child-robot-asocial.yaml", false},
    {"chatterer", "validity/chatterer.yaml", true},  {"mover", "validity/mover.yaml", true},
    {"yoked-social", "validity/yoked-social.yaml", true}, {"idle", "validity/idle.yaml", true},
};

/// Runs (or resumes) one robot's sessions into `out`/<name>.
void run_robot(const PanelRobot& robot, const ValidityOptions& o, const fs::path& out) {
  RunCommandOptions run;
  run.file = (scenarios_dir() / robot.scenario).string();
  if (!fs::is_regular_file(run.file)) {
    throw InputError(fmt::format("the panel's scenario file {} is missing", run.file), "FREEPLAY_SCENARIOS_DIR",
                     "the scenarios/ folder of freeplay-sim (with scenarios/validity/)");
  }
  run.episodes = o.sessions;
  run.seed = o.seed;
  run.jobs = o.jobs;
  run.out = (out / robot.name).string();
  run.quiet = true;
  // The yoked control replays the social run's event logs; the other runs need only their records.
  run.events = std::string(robot.name) == "social" ? "all" : "none";
  if (std::string(robot.name) == "yoked-social") {
    run.overrides.push_back(fmt::format("robot.params.from={}", fs::absolute(out / "social").string()));
  }
  if (!o.quiet) std::cerr << fmt::format("validity: {} sessions of {} ({}) …\n", o.sessions, robot.name, robot.scenario);
  run_command(run, false);
}

analysis::Sample sample_of(const fs::path& out, const std::string& name) {
  const auto run = analysis::load_run(out / name);
  return {name, run.episodes};
}

void validity(const ValidityOptions& o) {
  const fs::path out = o.out;
  if (fs::exists(out) && !fs::is_directory(out)) {
    throw InputError(fmt::format("'{}' exists and is not a folder", o.out), "--out", "a new or earlier panel folder");
  }
  for (const auto& robot : kPanel) run_robot(robot, o, out);

  analysis::ValidityPanel panel;
  panel.asocial = sample_of(out, "asocial");
  panel.social = sample_of(out, "social");
  for (const auto& robot : kPanel) {
    if (robot.degenerate) panel.degenerate.push_back(sample_of(out, robot.name));
  }
  panel.yoked = sample_of(out, "yoked-social");
  const auto report = analysis::evaluate_panel(panel);
  const auto table = fmt::format("validity panel: {} sessions per robot, seed {} (the same children for every robot)\n\n{}",
                                 o.sessions, o.seed, analysis::validity_table(report));
  std::cout << table;
  auto json = analysis::validity_json(report);
  json["sessions"] = o.sessions;
  json["seed"] = o.seed;
  write_file_atomically(out / "validity.json", json.dump(2) + "\n");
  write_file_atomically(out / "validity.md", "```\n" + table + "```\n");
  write_file_atomically(o.junit.empty() ? out / "validity.xml" : fs::path(o.junit), analysis::validity_junit(report));
  if (report.failures() > 0) fail_with(1);
}

const RegisterCommand validity_command(74, [](CLI::App& program) {
  auto o = std::make_shared<ValidityOptions>();
  auto* cmd = program.add_subcommand(
      "validity", "Run the validity panel: robots that ignore the child must not win (docs/validity.md)");
  cmd->add_option("--sessions", o->sessions, "Sessions per robot (the same children for every robot)")
      ->check(CLI::Range(2, 100000))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Root seed of every robot's run (not the calibration's fit seed 2017)")
      ->capture_default_str();
  cmd->add_option("-j,--jobs", o->jobs, "Parallel episodes (default: all cores)")->check(CLI::Range(1, 1024));
  cmd->add_option("-o,--out", o->out, "Panel folder: one run folder per robot, validity.json/.md/.xml")
      ->capture_default_str();
  cmd->add_option("--junit", o->junit, "JUnit XML of the gates (default: OUT/validity.xml)");
  cmd->add_flag("-q,--quiet", o->quiet, "No progress lines (the report is still printed)");
  cmd->footer(
      "Runs, in order: social (with event logs), asocial, a timetable chatterer, a timetable mover, the social\n"
      "policy's yoked control (replaying the social run) and idle, each --sessions sessions with --seed, into\n"
      "OUT/<robot>/ (an interrupted panel resumes). Gates: each degenerate robot's coded cooperative share ≤ .05,\n"
      "associative share ≤ asocial's + .05 and mean duration ≤ asocial's + 2 min; social beats its yoked control\n"
      "on joint play (associative + cooperative) and duration with the paired 95 % CI excluding zero.\n"
      "Exit status: 0 every gate passes, 1 a gate fails, 2 bad input, 130 interrupted.");
  cmd->callback([o] { validity(*o); });
});

}  // namespace
}  // namespace freeplay::cli
