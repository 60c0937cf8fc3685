// Policies written in Python: `python:module:Class` names a subclass of freeplay.Policy; the adapter below is a
// C++ PlayPolicy that holds the GIL only while it calls the Python methods.

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "env_channel.hpp"
#include "freeplay/core/error.hpp"

namespace freeplay::python {

namespace {

/// A PlayPolicy whose methods are those of a Python freeplay.Policy instance.
class PythonPolicy final : public policies::PlayPolicy {
 public:
  /// Wraps `instance` (a freeplay.Policy), registered as `name`.
  PythonPolicy(std::string name, py::object instance) : name_(std::move(name)), instance_(std::move(instance)) {
    perceives_children_ = py::bool_(instance_.attr("perceives_children"));
  }
  /// Drops the Python instance under the GIL (episodes end on worker threads).
  ~PythonPolicy() override {
    py::gil_scoped_acquire gil;
    instance_ = py::object();
  }
  PythonPolicy(const PythonPolicy&) = delete;
  PythonPolicy& operator=(const PythonPolicy&) = delete;

  std::string name() const override { return name_; }

  void reset(const policies::PolicyContext& context, Rng rng) override {
    py::gil_scoped_acquire gil;
    call("reset", py::cast(context, py::return_value_policy::copy), py::cast(rng));
  }

  std::vector<policies::Action> decide(const policies::Observation& observation) override {
    py::gil_scoped_acquire gil;
    t_ = observation.t;
    const auto returned = call("decide", py::cast(observation, py::return_value_policy::copy));
    return actions_from_python(returned, name_);
  }

  void on_result(const policies::ActionResult& result) override {
    py::gil_scoped_acquire gil;
    call("on_result", py::cast(result, py::return_value_policy::copy));
  }

  bool perceives_children() const override { return perceives_children_; }

 private:
  // Calls a method; a Python exception keeps its type and traceback and gains a note naming the policy and time.
  template <class... Args>
  py::object call(const char* method, Args&&... args) {
    try {
      return instance_.attr(method)(std::forward<Args>(args)...);
    } catch (py::error_already_set& e) {
      const auto note = fmt::format("raised in {}() of policy '{}' at free-play t = {:.1f} s", method, name_, t_);
      if (py::hasattr(e.value(), "add_note")) e.value().attr("add_note")(note);
      throw;
    }
  }

  std::string name_;
  py::object instance_;
  bool perceives_children_ = false;
  double t_ = 0.0;
};

std::unique_ptr<policies::PlayPolicy> make_python_policy(const std::string& name, const YAML::Node& params) {
  if (auto env_policy = make_env_channel_policy()) return env_policy;  // this thread steps a freeplay.Env
  const std::string spec = name.substr(std::string_view(policies::kPythonPolicyPrefix).size());
  const auto colon = spec.rfind(':');
  const std::string allowed = "python:MODULE:CLASS, MODULE importable from PYTHONPATH, CLASS a freeplay.Policy";
  if (colon == std::string::npos || colon == 0 || colon + 1 == spec.size()) {
    throw InputError(fmt::format("policy '{}' does not name a module and a class", name), "robot.policy", allowed);
  }
  const auto module_name = spec.substr(0, colon);
  const auto class_name = spec.substr(colon + 1);
  py::gil_scoped_acquire gil;
  py::module_ module;
  try {
    module = py::module_::import(module_name.c_str());
  } catch (py::error_already_set& e) {
    throw InputError(fmt::format("policy '{}': cannot import Python module '{}' ({})", name, module_name, e.what()),
                     "robot.policy", allowed);
  }
  if (!py::hasattr(module, class_name.c_str())) {
    throw InputError(fmt::format("policy '{}': module '{}' has no class '{}'", name, module_name, class_name),
                     "robot.policy", allowed);
  }
  const auto policy_class = module.attr(class_name.c_str());
  const auto base = py::module_::import("freeplay").attr("Policy");
  if (!py::isinstance<py::type>(policy_class) || !PyObject_IsSubclass(policy_class.ptr(), base.ptr())) {
    throw InputError(fmt::format("policy '{}': '{}.{}' is not a subclass of freeplay.Policy", name, module_name, class_name),
                     "robot.policy", allowed);
  }
  auto instance = policy_class(yaml_to_python(params));
  return std::make_unique<PythonPolicy>(name, std::move(instance));
}

}  // namespace

py::object yaml_to_python(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return py::none();
  if (node.IsMap()) {
    py::dict out;
    for (const auto& kv : node) out[py::str(kv.first.as<std::string>())] = yaml_to_python(kv.second);
    return out;
  }
  if (node.IsSequence()) {
    py::list out;
    for (const auto& element : node) out.append(yaml_to_python(element));
    return out;
  }
  const auto& text = node.Scalar();
  if (node.Tag() == "!") return py::str(text);  // quoted in the file
  bool flag = false;
  long long integer = 0;
  double number = 0.0;
  if (YAML::convert<bool>::decode(node, flag)) return py::bool_(flag);
  if (YAML::convert<long long>::decode(node, integer)) return py::int_(integer);
  if (YAML::convert<double>::decode(node, number)) return py::float_(number);
  return py::str(text);
}

void bind_policies(py::module_& m) {
  (void)m;
  policies::register_policy_family(policies::kPythonPolicyPrefix, make_python_policy);
}

}  // namespace freeplay::python
