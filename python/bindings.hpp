// The module's parts (python/shpb_module.cpp calls them in this order when shpb._shpb is imported:
// pybind11 names a registered class in the signatures of what is bound after it).
#pragma once

#include <pybind11/pybind11.h>

namespace shpb::python {

namespace py = pybind11;

void bind_materials(py::module_& m);  // materials.cpp: Material and its law groups
void bind_scene(py::module_& m);      // scene.cpp: Scene and its bars
void bind_simulate(py::module_& m);   // simulate.cpp: _simulate and its result
void bind_process(py::module_& m);    // process.cpp: _process and its result
void bind_plan(py::module_& m);       // plan.cpp: _plan and its result
void bind_commands(py::module_& m);   // commands.cpp: compare, study, fit, calibrate, dispersion,
                                      // save

}  // namespace shpb::python
