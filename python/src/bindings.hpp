#pragma once
// The parts of the stochnav Python module, each adding its functions and classes to the module
// (module.cpp calls them in order: later parts use the classes of earlier ones).

#include "pybind.hpp"

namespace stochnav::python {

void bind_errors(py::module_& module);      ///< InputError, ConfigError (both ValueError)
void bind_records(py::module_& module);     ///< read_record, Record
void bind_allan(py::module_& module);       ///< allan, AllanResult
void bind_davar(py::module_& module);       ///< davar, DavarResult
void bind_wv(py::module_& module);          ///< wv, WvResult
void bind_noise_model(py::module_& module);  ///< NoiseModel
void bind_fit(py::module_& module);          ///< fit
void bind_simulation(py::module_& module);   ///< simulate_noise, simulate_scenario
void bind_navigation(py::module_& module);   ///< run, compare
void bind_navigator(py::module_& module);    ///< Navigator
void bind_diagnose(py::module_& module);     ///< diagnose

}  // namespace stochnav::python
