#include "stochnav/plugin/plugin_registry.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <cstdlib>
#include <map>
#include <system_error>

#include "stochnav/core/errors.hpp"

namespace stochnav::plugin {
namespace fs = std::filesystem;
namespace {

constexpr const char* kInfoAlias = "stochnav_plugin_info";
constexpr const char* kNoiseFactoryAlias = "stochnav_noise_factory";
constexpr const char* kNoiseFitterAlias = "stochnav_noise_fitter";
constexpr const char* kDocumentationAlias = "stochnav_plugin_documentation";
constexpr const char* kAidFactoryAlias = "stochnav_aid_factory";
constexpr std::string_view kFilePrefix = "stochnav_";

using Library = boost::dll::shared_library;

struct LoadedPlugin {
  PluginDescriptor descriptor;
  std::shared_ptr<Library> library;
};

bool valid_type_name(const char* type) {
  if (type == nullptr || *type == '\0') return false;
  for (const char* c = type; *c != '\0'; ++c) {
    const bool ok = (*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '_';
    if (!ok) return false;
  }
  return true;
}

LoadedPlugin load_plugin(const fs::path& file) {
  const std::string name = file.string();
  std::error_code status_error;
  if (!fs::exists(file, status_error)) {
    throw ConfigError(name +
                      ": plugin library not found; check the file name, or build and "
                      "install the plugin");
  }
  if (!fs::is_regular_file(file, status_error)) {
    throw ConfigError(name + ": not a regular file; give the path of a plugin library (.so)");
  }
  auto library = std::make_shared<Library>();
  std::error_code load_error;
  ::dlerror();  // clear any stale message
  library->load(fs::absolute(file), boost::dll::load_mode::rtld_now, load_error);
  if (load_error) {
    // Boost.DLL reports every failure as "Bad file descriptor": dlerror() has the real reason.
    const char* reason = ::dlerror();
    throw ConfigError(name + ": cannot load plugin library: " +
                      (reason != nullptr ? std::string(reason) : load_error.message()) +
                      "; rebuild the plugin against this stochnav with stochnav_add_plugin() "
                      "(which links it with -Wl,--no-undefined)");
  }
  if (!library->has(kInfoAlias)) {
    throw ConfigError(name + ": not a stochnav plugin (no " + kInfoAlias +
                      " symbol); register it with STOCHNAV_NOISE_PLUGIN or STOCHNAV_AID_PLUGIN");
  }
  const PluginInfo* info = library->get_alias<const PluginInfo*()>(kInfoAlias)();
  if (info == nullptr)
    throw ConfigError(name + ": " + kInfoAlias + " returned null; fix the plugin");
  // The API version is read first and alone: nothing else of the struct is trusted before.
  const std::uint32_t api_version = info->api_version;
  if (api_version != kPluginApiVersion) {
    throw ConfigError(name + ": plugin API version " + std::to_string(api_version) +
                      ", this stochnav " + std::string(kVersion) + " needs version " +
                      std::to_string(kPluginApiVersion) +
                      "; rebuild the plugin against this stochnav");
  }
  PluginDescriptor descriptor;
  descriptor.api_version = api_version;
  descriptor.file = fs::absolute(file);
  if (!valid_type_name(info->type)) {
    throw ConfigError(name +
                      ": plugin type name must be non-empty, of a-z, 0-9 and _; fix the "
                      "registration macro");
  }
  descriptor.type = info->type;
  descriptor.description = info->description != nullptr ? info->description : "";
  descriptor.framework_version = info->framework_version != nullptr ? info->framework_version : "";
  const auto require = [&](const char* alias) {
    if (!library->has(alias)) {
      throw ConfigError(name + ": plugin '" + descriptor.type + "' lacks the symbol " + alias +
                        "; register it with its kind's STOCHNAV_*_PLUGIN macro");
    }
  };
  switch (static_cast<PluginKind>(info->kind)) {
    case PluginKind::kNoiseModel:
      descriptor.kind = PluginKind::kNoiseModel;
      require(kNoiseFactoryAlias);
      require(kNoiseFitterAlias);
      descriptor.can_fit =
          &library->get_alias<NoiseModelFitter>(kNoiseFitterAlias) != &fit_not_supported;
      break;
    case PluginKind::kAid:
      descriptor.kind = PluginKind::kAid;
      require(kAidFactoryAlias);
      break;
    default:
      throw ConfigError(name + ": unknown plugin kind " + std::to_string(info->kind) +
                        "; use STOCHNAV_NOISE_PLUGIN or STOCHNAV_AID_PLUGIN");
  }
  return {std::move(descriptor), std::move(library)};
}

bool is_candidate(const fs::path& file) {
  const std::string filename = file.filename().string();
  return filename.starts_with(kFilePrefix) && file.extension() == Library::suffix();
}

/// Wraps a plugin object so that its library stays loaded for as long as the object lives.
template <typename T>
std::shared_ptr<T> hold_library(std::unique_ptr<T> object, std::shared_ptr<Library> library) {
  if (object == nullptr) return nullptr;
  return std::shared_ptr<T>(object.release(), [library = std::move(library)](T* raw) {
    delete raw;  // runs the plugin's destructor while the library is still loaded
  });
}

}  // namespace

fs::path bundled_plugin_dir() {
  // The library this function is compiled into: libstochnav in the build tree or installed.
  std::error_code error;
  const fs::path library = boost::dll::symbol_location(bundled_plugin_dir, error);
  if (error) return {};
  const fs::path folder = library.parent_path() / "stochnav" / "plugins";
  const fs::path canonical = fs::weakly_canonical(folder, error);
  return error ? folder : canonical;
}

std::vector<fs::path> default_search_path(const fs::path& config_dir) {
  std::vector<fs::path> folders;
  if (!config_dir.empty()) folders.push_back(config_dir);
  if (const char* variable = std::getenv(std::string(kPluginPathVariable).c_str())) {
    std::string_view rest = variable;
    while (!rest.empty()) {
      const auto colon = rest.find(':');
      const std::string_view item = rest.substr(0, colon);
      if (!item.empty()) folders.emplace_back(item);
      if (colon == std::string_view::npos) break;
      rest.remove_prefix(colon + 1);
    }
  }
  if (auto bundled = bundled_plugin_dir(); !bundled.empty()) folders.push_back(bundled);
  return folders;
}

PluginDescriptor check_plugin_file(const fs::path& file) { return load_plugin(file).descriptor; }

struct PluginRegistry::Impl {
  std::vector<fs::path> search_path;
  std::vector<LoadedPlugin> loaded;
  std::vector<PluginProblem> problems;

  const LoadedPlugin& find(PluginKind kind, std::string_view type,
                           std::string_view type_pointer) const {
    const LoadedPlugin* found = nullptr;
    for (const auto& plugin : loaded) {
      if (plugin.descriptor.kind != kind || plugin.descriptor.type != type) continue;
      if (found != nullptr) {
        throw ConfigError(std::string(type_pointer) + ": plugin type '" + std::string(type) +
                          "' is provided by two libraries, " + found->descriptor.file.string() +
                          " and " + plugin.descriptor.file.string() +
                          "; remove one or take its folder off the plugin search path");
      }
      found = &plugin;
    }
    if (found == nullptr) {
      // A library that failed to load may be the one that provides the type: its loader
      // error (dlerror: a missing symbol, a bad ELF file) says more than "unknown type".
      for (const auto& problem : problems) {
        const std::string stem = problem.file.stem().string();
        if (stem.size() >= type.size() && stem.ends_with("_" + std::string(type))) {
          throw ConfigError(std::string(type_pointer) + ": " +
                            std::string(plugin_kind_name(kind)) + " plugin type '" +
                            std::string(type) + "' is not available: " + problem.reason);
        }
      }
      std::string known;
      for (const auto& plugin : loaded) {
        if (plugin.descriptor.kind != kind) continue;
        known += (known.empty() ? "" : ", ") + plugin.descriptor.type;
      }
      std::string folders;
      for (const auto& folder : search_path) {
        folders += (folders.empty() ? "" : ", ") + folder.string();
      }
      throw ConfigError(
          std::string(type_pointer) + ": unknown " + std::string(plugin_kind_name(kind)) +
          " plugin type '" + std::string(type) +
          "'; expected one of: " + (known.empty() ? std::string("(none found)") : known) +
          " (searched " + folders + "; add folders with " + std::string(kPluginPathVariable) + ")" +
          failed_libraries());
    }
    return *found;
  }

  // "; N plugin libraries failed to load, first: REASON" when any did, else "".
  std::string failed_libraries() const {
    if (problems.empty()) return {};
    return "; " + std::to_string(problems.size()) + " plugin librar" +
           (problems.size() == 1 ? "y" : "ies") + " failed to load, first: " +
           problems.front().reason;
  }
};

PluginRegistry::PluginRegistry(std::vector<fs::path> search_path)
    : impl_(std::make_unique<Impl>()) {
  impl_->search_path = std::move(search_path);
  std::vector<fs::path> seen;
  for (const auto& folder : impl_->search_path) {
    std::error_code error;
    if (!fs::is_directory(folder, error)) continue;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder, error)) {
      if (entry.is_regular_file(error) && is_candidate(entry.path())) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
      const fs::path canonical = fs::weakly_canonical(file, error);
      if (std::find(seen.begin(), seen.end(), canonical) != seen.end()) continue;
      seen.push_back(canonical);
      try {
        impl_->loaded.push_back(load_plugin(file));
      } catch (const ConfigError& failure) {
        impl_->problems.push_back({file, failure.what()});
      }
    }
  }
  std::map<std::pair<PluginKind, std::string>, const LoadedPlugin*> first;
  for (const auto& plugin : impl_->loaded) {
    const auto key = std::make_pair(plugin.descriptor.kind, plugin.descriptor.type);
    const auto [it, inserted] = first.emplace(key, &plugin);
    if (!inserted) {
      impl_->problems.push_back(
          {plugin.descriptor.file, plugin.descriptor.file.string() + ": duplicate " +
                                       std::string(plugin_kind_name(plugin.descriptor.kind)) +
                                       " plugin type '" + plugin.descriptor.type + "', also in " +
                                       it->second->descriptor.file.string() +
                                       "; remove one of them"});
    }
  }
}

PluginRegistry PluginRegistry::of_file(const fs::path& file) {
  LoadedPlugin plugin = load_plugin(file);
  PluginRegistry registry({});
  registry.impl_->search_path = {file.parent_path()};
  registry.impl_->loaded.push_back(std::move(plugin));
  return registry;
}

PluginRegistry::~PluginRegistry() = default;
PluginRegistry::PluginRegistry(PluginRegistry&&) noexcept = default;
PluginRegistry& PluginRegistry::operator=(PluginRegistry&&) noexcept = default;

const std::vector<fs::path>& PluginRegistry::search_path() const { return impl_->search_path; }

std::vector<PluginDescriptor> PluginRegistry::plugins() const {
  std::vector<PluginDescriptor> result;
  for (const auto& plugin : impl_->loaded) result.push_back(plugin.descriptor);
  return result;
}

const std::vector<PluginProblem>& PluginRegistry::problems() const { return impl_->problems; }

const PluginDescriptor& PluginRegistry::find(PluginKind kind, std::string_view type,
                                             std::string_view type_pointer) const {
  return impl_->find(kind, type, type_pointer).descriptor;
}

namespace {

/// Runs a factory; its ConfigError and InputError pass through, anything else becomes a
/// ConfigError naming the plugin.
template <typename Call>
auto run_factory(const PluginDescriptor& plugin, std::string_view pointer, Call&& call) {
  try {
    auto object = call();
    if (object == nullptr) {
      throw ConfigError(std::string(pointer) + ": plugin '" + plugin.type + "' (" +
                        plugin.file.string() + ") returned no object; fix the plugin's factory");
    }
    return object;
  } catch (const ConfigError&) {
    throw;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& failure) {
    throw ConfigError(std::string(pointer) + ": plugin '" + plugin.type + "' (" +
                      plugin.file.string() + ") failed: " + failure.what() + "; check its params");
  }
}

}  // namespace

std::shared_ptr<NoiseModelPlugin> PluginRegistry::create_noise_model(
    std::string_view type, const nlohmann::json& params, const NoiseModelContext& context,
    std::string_view type_pointer) const {
  const LoadedPlugin& plugin = impl_->find(PluginKind::kNoiseModel, type, type_pointer);
  auto& factory = plugin.library->get_alias<NoiseModelFactory>(kNoiseFactoryAlias);
  auto object = run_factory(plugin.descriptor, context.params_pointer,
                            [&] { return factory(params, context); });
  return hold_library(std::move(object), plugin.library);
}

std::shared_ptr<NoiseModelPlugin> PluginRegistry::fit_noise_model(
    std::string_view type, const CalibrationRecord& record, const nlohmann::json& params,
    const NoiseModelContext& context, std::string_view type_pointer) const {
  const LoadedPlugin& plugin = impl_->find(PluginKind::kNoiseModel, type, type_pointer);
  auto& fitter = plugin.library->get_alias<NoiseModelFitter>(kNoiseFitterAlias);
  auto object = run_factory(plugin.descriptor, context.params_pointer,
                            [&] { return fitter(record, params, context); });
  return hold_library(std::move(object), plugin.library);
}

std::shared_ptr<AidPlugin> PluginRegistry::create_aid(std::string_view type,
                                                      const nlohmann::json& params,
                                                      const AidContext& context,
                                                      std::string_view type_pointer) const {
  const LoadedPlugin& plugin = impl_->find(PluginKind::kAid, type, type_pointer);
  auto& factory = plugin.library->get_alias<AidFactory>(kAidFactoryAlias);
  auto object = run_factory(plugin.descriptor, context.params_pointer,
                            [&] { return factory(params, context); });
  return hold_library(std::move(object), plugin.library);
}

std::optional<PluginDocumentation> PluginRegistry::documentation(PluginKind kind,
                                                                 std::string_view type,
                                                                 Quantity quantity) const {
  const LoadedPlugin& plugin = impl_->find(kind, type, "plugins doc");
  if (!plugin.library->has(kDocumentationAlias)) return std::nullopt;
  return plugin.library->get_alias<PluginDocumentationFunction>(kDocumentationAlias)(quantity);
}

}  // namespace stochnav::plugin
