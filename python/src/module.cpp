// The `freeplay._freeplay` extension module (the `freeplay` package in python/freeplay wraps it): InputError as a
// Python exception with file, line, column, key and allowed values, and the parts bound in the other files.

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "bindings.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/memory.hpp"

namespace freeplay::python {
namespace {

PyObject* g_input_error = nullptr;  // freeplay.InputError (lives as long as the interpreter)

void translate_input_error(std::exception_ptr error) {
  try {
    if (error) std::rethrow_exception(error);
  } catch (const InputError& e) {
    py::object instance = py::reinterpret_borrow<py::object>(g_input_error)(e.what());
    instance.attr("problem") = e.problem();
    instance.attr("file") = e.where().file.empty() ? py::object(py::none()) : py::object(py::str(e.where().file));
    instance.attr("line") = e.where().line == 0 ? py::object(py::none()) : py::object(py::int_(e.where().line));
    instance.attr("column") = e.where().column == 0 ? py::object(py::none()) : py::object(py::int_(e.where().column));
    instance.attr("key") = e.key();
    instance.attr("allowed") = e.allowed();
    PyErr_SetObject(g_input_error, instance.ptr());
  }
}

}  // namespace
}  // namespace freeplay::python

PYBIND11_MODULE(_freeplay, m) {
  namespace py = pybind11;
  using namespace freeplay::python;
  m.doc() = "freeplay-sim's C++ engine (use the `freeplay` package)";
  g_input_error = PyErr_NewExceptionWithDoc(
      "freeplay.InputError",
      "Bad input (scenario, suite, override, action): attributes problem, file, line, column, key, allowed.",
      PyExc_ValueError, nullptr);
  m.attr("InputError") = py::handle(g_input_error);
  py::register_exception_translator(translate_input_error);
  freeplay::keep_freed_memory_for_reuse();
  if (!spdlog::get("freeplay-python")) {  // logs go to stderr, as from the command line
    spdlog::set_default_logger(spdlog::stderr_color_mt("freeplay-python"));
  }
  bind_types(m);
  bind_policies(m);
  bind_experiments(m);
  bind_env(m);
  bind_vec_env(m);
}
