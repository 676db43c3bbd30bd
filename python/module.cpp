// The Python module `svmp` (README, "Python"; docs/ecosystem.md): our SMO solver and decision functions
// on NumPy arrays, scenario files, and every registered planner run as svmp-plan runs it.
#include <exception>
#include <string>

#include "cspace/scenario/parameters.hpp"
#include "python/bindings.hpp"

PYBIND11_MODULE(svmp, m) {
  m.doc() = "svmp: motion planning with support vector machines (SMO solver, scenarios, planners)";
  // A bad scenario file or planner parameter: a ValueError subclass carrying the library's message
  // (file, field and value). The message is decoded with replacement: a file name not in UTF-8 had
  // left it empty.
  static pybind11::exception<svmp::cspace::ScenarioError> scenario_error(m, "ScenarioError", PyExc_ValueError);
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const svmp::cspace::ScenarioError& e) {
      const std::string what = e.what();
      PyObject* message = PyUnicode_DecodeUTF8(what.data(), static_cast<Py_ssize_t>(what.size()), "replace");
      PyErr_SetObject(scenario_error.ptr(), message);
      Py_XDECREF(message);
    }
  });
  svmp::python::bindSvm(m);
  svmp::python::bindPlanning(m);
}
