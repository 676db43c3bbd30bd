#pragma once
// The parts of the `svmp` Python module (python/module.cpp), one per area of the library.
#include <pybind11/pybind11.h>

namespace svmp::python {

void bindSvm(pybind11::module_& m);       // train, Model (svm_bindings.cpp)
void bindPlanning(pybind11::module_& m);  // load_scenario, Scenario, plan, planners (planning_bindings.cpp)

}  // namespace svmp::python
