// The Python module `svmp` (README, "Python"; docs/ecosystem.md): our SMO solver and decision functions
// on NumPy arrays, scenario files, and every registered planner run as svmp-plan runs it.
#include "cspace/scenario/parameters.hpp"
#include "python/bindings.hpp"

PYBIND11_MODULE(svmp, m) {
  m.doc() = "svmp: motion planning with support vector machines (SMO solver, scenarios, planners)";
  // A bad scenario file or planner parameter: a ValueError subclass carrying the library's message
  // (file, field and value).
  pybind11::register_exception<svmp::cspace::ScenarioError>(m, "ScenarioError", PyExc_ValueError);
  svmp::python::bindSvm(m);
  svmp::python::bindPlanning(m);
}
