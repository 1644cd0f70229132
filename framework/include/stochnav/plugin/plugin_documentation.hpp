#pragma once
// A plugin's parameter reference, exported by the plugin from the ParamTables it parses with, so
// that `stochnav plugins doc` (docs/config-reference.md) cannot drift from the code.
//
// Optional export (plugin_api.hpp): a library may define, at global scope, beside its
// registration macro,
//   STOCHNAV_PLUGIN_DOCUMENTATION(kMyTable)                    params only
//   STOCHNAV_PLUGIN_DOCUMENTATION_WITH_FIT(kMyTable, kFitTable)  params and the fitter's options
// which exports stochnav_plugin_documentation. A library without it loads and runs as before;
// `plugins doc` says it documents nothing.

#include <string>
#include <vector>

#include "stochnav/core/units.hpp"
#include "stochnav/plugin/plugin_api.hpp"

namespace stochnav::plugin {

/// One line per key, as ParamTable::documentation() writes them, e.g.
/// "tau_c: correlation time; a number > 0 (s), per axis (a number or [x, y, z]), required".
struct PluginDocumentation {
  std::vector<std::string> params;       ///< the factory's "params"
  std::vector<std::string> fit_options;  ///< the fitter's params; empty when it cannot fit
};

/// The export: the reference in the reporting units of `quantity` (noise models:
/// kAngularRate for a gyro, kSpecificForce for an accelerometer; aids: kPlain).
using PluginDocumentationFunction = PluginDocumentation(Quantity quantity);

}  // namespace stochnav::plugin

#define STOCHNAV_PLUGIN_DOCUMENTATION_WITH_FIT(PARAM_TABLE, FIT_TABLE)                        \
  static ::stochnav::plugin::PluginDocumentation stochnav_plugin_documentation_function(     \
      ::stochnav::Quantity quantity) {                                                       \
    return {(PARAM_TABLE).documentation(quantity), (FIT_TABLE).documentation(quantity)};    \
  }                                                                                          \
  BOOST_DLL_ALIAS(stochnav_plugin_documentation_function, stochnav_plugin_documentation)

#define STOCHNAV_PLUGIN_DOCUMENTATION(PARAM_TABLE)                                          \
  static ::stochnav::plugin::PluginDocumentation stochnav_plugin_documentation_function(   \
      ::stochnav::Quantity quantity) {                                                     \
    return {(PARAM_TABLE).documentation(quantity), {}};                                    \
  }                                                                                        \
  BOOST_DLL_ALIAS(stochnav_plugin_documentation_function, stochnav_plugin_documentation)
