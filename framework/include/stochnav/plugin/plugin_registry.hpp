#pragma once
// Finding and loading plugin libraries (Boost.DLL, RTLD_NOW), and creating plugin objects that
// keep their library loaded: every object returned holds a reference to its library, so it may
// outlive the registry.
//
// Search path, in order: the config file's folder, each folder of $STOCHNAV_PLUGIN_PATH
// (':'-separated), then the plugin folder of the stochnav library in use
// (<libdir>/stochnav/plugins, both in the build tree and in an installed package). A folder
// contributes its files named stochnav_*.so (not recursive). A file found twice through
// different folders is loaded once.
//
// Errors are ConfigError with one line: the file or JSON pointer, the real reason (missing
// file, dlerror() text such as an undefined symbol, wrong API version, unknown or duplicate
// type, the factory's own message) and how to fix it. The CLI maps them to exit code 2.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/plugin_api.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"

namespace stochnav::plugin {

/// Name of the environment variable adding plugin folders.
inline constexpr std::string_view kPluginPathVariable = "STOCHNAV_PLUGIN_PATH";

/// The plugin folder beside the stochnav library in use: <folder of libstochnav>/stochnav/plugins.
std::filesystem::path bundled_plugin_dir();

/// [config_dir (if not empty), $STOCHNAV_PLUGIN_PATH folders..., bundled_plugin_dir()].
std::vector<std::filesystem::path> default_search_path(
    const std::filesystem::path& config_dir = {});

/// What a plugin library declares, as loaded.
struct PluginDescriptor {
  PluginKind kind = PluginKind::kNoiseModel;
  std::string type;
  std::uint32_t api_version = 0;
  std::string description;
  std::string framework_version;  ///< stochnav version the plugin was built against
  std::filesystem::path file;
  bool can_fit = false;  ///< noise models: has a fitter (not fit_not_supported)
};

/// A library that could not be used, or a type offered twice.
struct PluginProblem {
  std::filesystem::path file;
  std::string reason;  ///< one line, as ConfigError would say it
};

/// Loads one library and checks it as the registry would. Throws ConfigError.
PluginDescriptor check_plugin_file(const std::filesystem::path& file);

class PluginRegistry {
 public:
  /// Scans the folders now (missing folders are skipped). Libraries that fail to load are
  /// recorded in problems(), not thrown.
  explicit PluginRegistry(std::vector<std::filesystem::path> search_path);
  ~PluginRegistry();
  PluginRegistry(PluginRegistry&&) noexcept;
  PluginRegistry& operator=(PluginRegistry&&) noexcept;

  /// A registry of the one library `file` (e.g. `stochnav plugins check`), whatever its folder
  /// holds besides. Throws ConfigError when the library does not load (check_plugin_file).
  static PluginRegistry of_file(const std::filesystem::path& file);

  const std::vector<std::filesystem::path>& search_path() const;
  /// Every plugin loaded, in search-path order.
  std::vector<PluginDescriptor> plugins() const;
  /// Libraries that failed to load, and duplicate types.
  const std::vector<PluginProblem>& problems() const;

  /// The plugin of `kind` called `type`. Throws ConfigError "<type_pointer>: ..." for an unknown
  /// type (listing the known ones and the search path) or a type offered by two libraries.
  const PluginDescriptor& find(PluginKind kind, std::string_view type,
                               std::string_view type_pointer) const;

  /// Builds a noise model with the plugin's factory. Throws ConfigError (see find, plus the
  /// factory's errors; any other exception from the factory is wrapped in a ConfigError).
  std::shared_ptr<NoiseModelPlugin> create_noise_model(std::string_view type,
                                                       const nlohmann::json& params,
                                                       const NoiseModelContext& context,
                                                       std::string_view type_pointer) const;

  /// Fits a noise model with the plugin's fitter. Throws ConfigError or InputError.
  std::shared_ptr<NoiseModelPlugin> fit_noise_model(std::string_view type,
                                                    const CalibrationRecord& record,
                                                    const nlohmann::json& params,
                                                    const NoiseModelContext& context,
                                                    std::string_view type_pointer) const;

  /// The parameter reference the plugin exports (plugin_documentation.hpp), in the reporting
  /// units of `quantity`; nullopt when the library exports none. Throws ConfigError as find.
  std::optional<PluginDocumentation> documentation(PluginKind kind, std::string_view type,
                                                   Quantity quantity) const;

  /// Builds an aid with the plugin's factory. Throws ConfigError.
  std::shared_ptr<AidPlugin> create_aid(std::string_view type, const nlohmann::json& params,
                                        const AidContext& context,
                                        std::string_view type_pointer) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stochnav::plugin
