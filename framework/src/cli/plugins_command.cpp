// stochnav plugins list | check LIB | show CONFIG: what the plugin search path offers, whether one
// library loads (exit code 2 with the real reason when it does not), and the plugins a run config
// builds (validated, fitted where asked) with the error-state layout they give.

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/plugin/run_config.hpp"
#include "stochnav/plugin/runtime.hpp"

namespace stochnav::cli {
namespace {

struct PluginsArguments {
  std::string config;                // a config file: its folder leads the search path
  std::vector<std::string> folders;  // extra folders, searched first
  std::string library;               // check: the library file
};

std::string row(const plugin::PluginDescriptor& plugin) {
  return fmt::format(
      "{:<6} {:<20} {:<4} {:<4} {}\n", plugin::plugin_kind_name(plugin.kind), plugin.type,
      plugin.api_version,
      plugin.kind == plugin::PluginKind::kNoiseModel ? (plugin.can_fit ? "yes" : "no") : "-",
      plugin.file.string());
}

constexpr const char* kHeader = "kind   type                 api  fit  file\n";

void run_list(const PluginsArguments& arguments) {
  std::vector<std::filesystem::path> path(arguments.folders.begin(), arguments.folders.end());
  const std::filesystem::path config_dir =
      arguments.config.empty() ? std::filesystem::path()
                               : std::filesystem::absolute(arguments.config).parent_path();
  for (auto& folder : plugin::default_search_path(config_dir)) path.push_back(std::move(folder));
  const plugin::PluginRegistry registry(path);
  std::string out = kHeader;
  for (const auto& descriptor : registry.plugins()) out += row(descriptor);
  std::cout << out;
  std::string folders;
  for (const auto& folder : registry.search_path()) {
    folders += (folders.empty() ? "" : ":") + folder.string();
  }
  std::cout << "search path: " << folders << '\n' << std::flush;
  const auto& problems = registry.problems();
  if (problems.empty()) return;
  std::string message = problems.front().reason;
  if (problems.size() > 1) {
    message = fmt::format("{} plugin problems: ", problems.size());
    for (std::size_t i = 0; i < problems.size(); ++i) {
      message += (i == 0 ? "" : " | ") + problems[i].reason;
    }
  }
  throw ConfigError(message);
}

void run_check(const PluginsArguments& arguments) {
  const auto descriptor = plugin::check_plugin_file(arguments.library);
  std::cout << kHeader << row(descriptor) << "description: " << descriptor.description
            << "\nbuilt against stochnav " << descriptor.framework_version << '\n';
}

void run_show(const PluginsArguments& arguments) {
  const plugin::RunConfig config = plugin::read_run_config(arguments.config);
  const plugin::PluginRegistry registry(plugin::default_search_path(config.config_dir));
  const plugin::AidData aids =
      config.data.aids ? plugin::read_aid_data(*config.data.aids) : plugin::AidData();
  const plugin::RunPlugins plugins =
      plugin::build_run_plugins(config, registry, aids, NavState(), 0.0);
  std::string out;
  out += "noise gyro:  " + plugins.gyro->describe() + "\n";
  out += "noise accel: " + plugins.accel->describe() + "\n";
  for (const auto& aid : plugins.aids) out += "aid: " + aid->describe() + "\n";
  out += fmt::format("error state: {} states\n", plugins.layout.size());
  for (const auto& block : plugins.layout.blocks()) {
    out += fmt::format("  {:<36} offset {:>3}  size {}\n", block.name, block.offset, block.size);
  }
  std::cout << out;
}

}  // namespace

void add_plugins_command(CLI::App& app) {
  auto arguments = std::make_shared<PluginsArguments>();
  CLI::App* command = app.add_subcommand("plugins", "List or check plugin libraries");
  command->require_subcommand(1);
  CLI::App* list = command->add_subcommand(
      "list", "Every plugin on the search path: kind, type, API version, fit support, file");
  list->add_option("--config", arguments->config, "Config file whose folder leads the search path");
  list->add_option("--path", arguments->folders, "Extra plugin folders, searched first");
  list->callback([arguments] { run_list(*arguments); });
  CLI::App* check = command->add_subcommand("check", "Load one plugin library and report it");
  check->add_option("library", arguments->library, "Plugin library file (.so)")->required();
  check->callback([arguments] { run_check(*arguments); });
  CLI::App* show = command->add_subcommand(
      "show", "Validate a run config, build its plugins and print them and the state layout");
  show->add_option("config", arguments->config, "Run config (JSON)")->required();
  show->callback([arguments] { run_show(*arguments); });
}

}  // namespace stochnav::cli
