#pragma once
// What the property fixtures of noise models (noise_model_case.hpp) and aids (aid_case.hpp)
// share: one plugin registry per search path, and failure lines as one GoogleTest message.

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "stochnav/plugin/plugin_registry.hpp"

namespace stochnav::testing {

/// The registry of a search path, loaded once per test executable; empty: the default search
/// path ($STOCHNAV_PLUGIN_PATH, then the plugin folder of the stochnav library in use).
inline const plugin::PluginRegistry& registry_for(
    const std::vector<std::filesystem::path>& search_path) {
  static std::map<std::vector<std::filesystem::path>, std::unique_ptr<plugin::PluginRegistry>>
      registries;
  auto& registry = registries[search_path];
  if (registry == nullptr) {
    registry = std::make_unique<plugin::PluginRegistry>(
        search_path.empty() ? plugin::default_search_path() : search_path);
  }
  return *registry;
}

/// Lines of failures as one message.
inline std::string failure_lines(const std::vector<std::string>& failures) {
  std::string text;
  for (const auto& line : failures) text += line + "\n";
  return text;
}

}  // namespace stochnav::testing
