#pragma once
// The parts of the `freeplay` Python module (module.cpp puts them together): the policy's types, Python policies,
// experiments (load, validate, run) and the episode stepper behind `freeplay.Env`.

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "freeplay/policies/play_policy.hpp"
#include "freeplay/scenario/settings.hpp"

namespace freeplay::python {

namespace py = pybind11;

/// Binds Observation and its parts, the actions, ActionResult, PolicyContext and Rng.
void bind_types(py::module_& m);
/// Installs the `python:module:Class` policy family in the registry.
void bind_policies(py::module_& m);
/// Binds loading, validating and running scenarios and suites, and the `run`/`suite` command line.
void bind_experiments(py::module_& m);
/// Binds the episode stepper behind `freeplay.Env`.
void bind_env(py::module_& m);
/// Binds VecEnv's batched step (all environments' actions, waits and batched outputs in one call) and the built-in
/// rewards' C++ home.
void bind_vec_env(py::module_& m);

/// The actions a Python `decide` returned (a list of actions, one action, or None); throws InputError naming the
/// policy and the element that is not an action.
std::vector<policies::Action> actions_from_python(const py::handle& returned, const std::string& policy);
/// JSON as Python data (objects → dict, arrays → list; a non-finite number → None, as its JSON text reads back).
py::object json_to_python(const nlohmann::json& value);
/// A YAML node as Python data (maps → dict, sequences → list, scalars → bool, int, float or str).
py::object yaml_to_python(const YAML::Node& node);
/// The names a scenario may use in this module: the C++ policies and `python:*`.
scenario::ScenarioVocabulary python_vocabulary();

}  // namespace freeplay::python
