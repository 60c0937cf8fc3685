// Experiments from Python: load and validate a scenario or suite with `--set`-style overrides, and run it through
// the same function as `freeplay run|suite` (cli/cmd_run.cpp), with the GIL released while episodes run.

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <pybind11/stl.h>
#include <spdlog/spdlog.h>

#include <csignal>

#include "bindings.hpp"
#include "command_registry.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/scenario/suite.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "freeplay/results/run_folder.hpp"
#include "run_command.hpp"
#include "vocabulary.hpp"

namespace freeplay::python {

namespace {

scenario::Suite load_any(const std::string& file, const std::vector<std::string>& overrides) {
  return scenario::is_suite_file(file) ? scenario::load_suite(file, overrides, python_vocabulary())
                                     : scenario::single_scenario_suite(file, overrides, python_vocabulary());
}

py::dict suite_data(const scenario::Suite& suite, bool is_suite) {
  py::dict out;
  out["name"] = suite.name;
  out["description"] = suite.description;
  out["file"] = suite.file;
  out["is_suite"] = is_suite;
  out["total_episodes"] = suite.total_episodes();
  py::list variants;
  for (const auto& v : suite.variants) {
    py::dict d;
    d["id"] = v.id;
    d["name"] = v.scenario.name;
    d["condition"] = std::string(scenario::to_string(v.scenario.condition));
    d["episodes"] = v.scenario.episodes;
    d["seed"] = v.scenario.seed;
    d["policy"] = v.scenario.condition == scenario::Condition::ChildRobot ? py::object(py::str(v.scenario.robot.policy)) : py::none();
    d["config_hash"] = v.scenario.config_hash;
    d["scenario"] = yaml_to_python(v.scenario.source);
    variants.append(d);
  }
  out["variants"] = variants;
  return out;
}

// A folder that does not exist yet: runs/<UTC time>-<name>, with -2, -3, … when runs start within one second.
std::string fresh_run_dir(const std::string& name) {
  const auto base = results::RunFolder::default_dir(name);
  auto dir = base;
  for (int k = 2; std::filesystem::exists(dir); ++k) dir = base.string() + fmt::format("-{}", k);
  return dir.string();
}

}  // namespace

scenario::ScenarioVocabulary python_vocabulary() { return cli::scenario_vocabulary(); }

void bind_experiments(py::module_& m) {
  m.def("_load", [](const std::string& file, const std::vector<std::string>& overrides) {
    scenario::Suite suite;
    bool is_suite = false;
    {
      py::gil_scoped_release release;
      is_suite = scenario::is_suite_file(file);
      suite = load_any(file, overrides);
    }
    return suite_data(suite, is_suite);
  }, py::arg("file"), py::arg("overrides"), "Loads and validates a scenario or suite file (see freeplay.load).");

  m.def("_run", [](const std::string& file, const std::vector<std::string>& overrides, std::optional<int> episodes,
                   std::optional<std::uint64_t> seed, int jobs, const std::string& out, const std::string& events,
                   bool quiet, const std::string& shard) {
    cli::RunCommandOptions o;
    o.file = file;
    o.overrides = overrides;
    o.episodes = episodes;
    o.seed = seed;
    o.jobs = std::max(1, jobs);
    o.out = out;
    o.events = events;
    o.quiet = quiet;
    o.shard = shard;
    if (!std::filesystem::exists(file)) {
      throw InputError(fmt::format("no such file '{}'", file), "file", "a scenario or suite YAML file");
    }
    if (o.out.empty()) o.out = fresh_run_dir(load_any(o.file, o.overrides).name);
    bool interrupted = false;
    {
      py::gil_scoped_release release;
      const auto previous = std::signal(SIGINT, SIG_DFL);
      std::signal(SIGINT, previous);
      try {
        cli::run_command(o, scenario::is_suite_file(o.file));
      } catch (const CLI::RuntimeError& e) {
        if (e.get_exit_code() != 130) {
          std::signal(SIGINT, previous);
          throw std::runtime_error(fmt::format("the run stopped with exit status {}", e.get_exit_code()));
        }
        interrupted = true;
      } catch (...) {
        std::signal(SIGINT, previous);
        throw;
      }
      std::signal(SIGINT, previous);
    }
    if (interrupted) {
      PyErr_SetString(PyExc_KeyboardInterrupt,
                      fmt::format("interrupted: the finished episodes are kept in {}; run again with out= to resume", o.out).c_str());
      throw py::error_already_set();
    }
    return o.out;
  }, py::arg("file"), py::arg("overrides"), py::arg("episodes"), py::arg("seed"), py::arg("jobs"), py::arg("out"),
     py::arg("events"), py::arg("quiet"), py::arg("shard"), "Runs a scenario or suite into a run folder (see freeplay.run).");

  m.def("_cli_main", [](std::vector<std::string> arguments) {
    std::vector<char*> argv;
    for (auto& a : arguments) argv.push_back(a.data());
    argv.push_back(nullptr);
    py::gil_scoped_release release;
    spdlog::drop("freeplay");  // run_program names its logger "freeplay"
    return cli::run_program(static_cast<int>(arguments.size()), argv.data());
  }, py::arg("argv"), "Runs `freeplay run|suite ARGS…` (python3 -m freeplay).");

  m.def("episode_seed", &runner::episode_seed, py::arg("scenario_seed"), py::arg("index"),
        "The root seed of episode `index` of a scenario with root seed `scenario_seed`.");
  m.def("policy_names", &policies::policy_names, "The C++ policies (Python policies are named python:MODULE:CLASS).");
}

}  // namespace freeplay::python
