// The compiled part of the Python package `stochnav` (python/stochnav/__init__.py re-exports it):
// the library's statistics, fit, simulation and navigation on numpy arrays, with the library's
// input errors as ValueError subclasses.

#include "bindings.hpp"
#include "stochnav/version.hpp"

PYBIND11_MODULE(_stochnav, module) {
  namespace sp = stochnav::python;
  module.doc() = "stochnav's compiled functions; use the package `stochnav`.";
  module.attr("__version__") = std::string(stochnav::kVersion);
  sp::bind_errors(module);
  sp::bind_records(module);
  sp::bind_allan(module);
  sp::bind_davar(module);
  sp::bind_wv(module);
  sp::bind_noise_model(module);
  sp::bind_fit(module);
  sp::bind_simulation(module);
  sp::bind_navigation(module);
  sp::bind_navigator(module);
  sp::bind_diagnose(module);
}
