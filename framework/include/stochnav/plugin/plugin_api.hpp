#pragma once
// The binary interface between stochnav and its plugins (MODULE libraries loaded with Boost.DLL).
//
// A plugin library exports, through BOOST_DLL_ALIAS:
//   stochnav_plugin_info    const PluginInfo* ()          always; read first
//   stochnav_noise_factory  NoiseModelFactory             kind kNoiseModel
//   stochnav_noise_fitter   NoiseModelFitter              kind kNoiseModel
//   stochnav_aid_factory    AidFactory                    kind kAid
// Write exactly one registration macro per library, at global scope: STOCHNAV_NOISE_PLUGIN
// (noise_model_plugin.hpp) or STOCHNAV_AID_PLUGIN (aid_plugin.hpp); it defines all of them.
//
// Versioning: the loader reads PluginInfo::api_version before anything else and refuses a
// library whose version differs from kPluginApiVersion. PluginInfo is frozen: its layout never
// changes, whatever the API version. Everything else (the factory signatures, the interfaces
// of noise_model_plugin.hpp and aid_plugin.hpp, the C++ types passed) is covered by the version:
// any change to them increments kPluginApiVersion (set in the top-level CMakeLists.txt, also
// exported to CMake as stochnav_PLUGIN_API_VERSION). Plugins must be built with the same
// compiler family and standard library as stochnav, since C++ types cross the boundary.

#include <boost/dll/alias.hpp>
#include <cstdint>
#include <memory>
#include <string_view>

#include "stochnav/version.hpp"

namespace stochnav::plugin {

/// Version of the plugin interface these headers describe.
inline constexpr std::uint32_t kPluginApiVersion = STOCHNAV_PLUGIN_API_VERSION;

enum class PluginKind : std::uint32_t {
  kNoiseModel = 1,  ///< noise model of one sensor group (noise_model_plugin.hpp)
  kAid = 2,         ///< aiding measurement (aid_plugin.hpp)
};

/// "noise" or "aid" (as `stochnav plugins list` prints them); "unknown" otherwise.
std::string_view plugin_kind_name(PluginKind kind);

/// What a plugin says about itself. FROZEN: the layout never changes; api_version stays first.
/// Strings are NUL-terminated, static, owned by the plugin library.
struct PluginInfo {
  std::uint32_t api_version;      ///< kPluginApiVersion the plugin was built with
  std::uint32_t kind;             ///< a PluginKind value
  const char* type;               ///< the name configs use, e.g. "gauss_markov"; [a-z0-9_]+
  const char* description;        ///< one line
  const char* framework_version;  ///< stochnav version of the headers used (kVersion)
};

}  // namespace stochnav::plugin

// Common part of the registration macros: the info struct and its exported accessor. Use it at
// global scope, once per library.
#define STOCHNAV_PLUGIN_INFO_(KIND, TYPE, DESCRIPTION)                                            \
  namespace {                                                                                     \
  const ::stochnav::plugin::PluginInfo stochnav_plugin_info_value{                                \
      ::stochnav::plugin::kPluginApiVersion, static_cast<std::uint32_t>(KIND), TYPE, DESCRIPTION, \
      ::stochnav::kVersion.data()};                                                               \
  }                                                                                               \
  static const ::stochnav::plugin::PluginInfo* stochnav_plugin_info_function() {                  \
    return &stochnav_plugin_info_value;                                                           \
  }                                                                                               \
  BOOST_DLL_ALIAS(stochnav_plugin_info_function, stochnav_plugin_info)

// The per-kind registration macros, STOCHNAV_NOISE_PLUGIN and STOCHNAV_AID_PLUGIN, live beside
// their interfaces (noise_model_plugin.hpp, aid_plugin.hpp) and check the factory signatures.
