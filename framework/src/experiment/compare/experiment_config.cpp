#include "stochnav/experiment/experiment_config.hpp"

#include <fmt/format.h>

#include <fstream>
#include <set>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/nearest_name.hpp"
#include "stochnav/core/work_limits.hpp"
#include "stochnav/io/json_document.hpp"
#include "stochnav/plugin/run_config.hpp"

namespace stochnav {
namespace {

namespace fs = std::filesystem;

std::string type_name(const nlohmann::json& value) { return value.type_name(); }

void reject_unknown_keys(const nlohmann::json& object, const std::string& pointer,
                         std::initializer_list<std::string_view> known) {
  for (const auto& [key, value] : object.items()) {
    bool found = false;
    for (auto name : known) found |= key == name;
    if (!found) {
      const std::vector<std::string> names(known.begin(), known.end());
      if (const auto nearest = nearest_name(key, names)) {
        throw ConfigError(fmt::format("{}/{}: unknown key '{}'; did you mean '{}'?", pointer, key,
                                      key, *nearest));
      }
      std::string list;
      for (auto name : known) list += (list.empty() ? "" : ", ") + std::string(name);
      throw ConfigError(fmt::format("{}/{}: unknown key; expected one of {}", pointer, key, list));
    }
  }
}

const nlohmann::json& member(const nlohmann::json& object, const std::string& pointer,
                             std::string_view key, nlohmann::json::value_t type,
                             std::string_view expected) {
  const auto it = object.find(key);
  if (it == object.end()) {
    throw ConfigError(fmt::format("{}/{}: missing; expected {}", pointer, key, expected));
  }
  if (it->type() != type && !(type == nlohmann::json::value_t::number_unsigned &&
                              it->is_number_integer() && it->get<std::int64_t>() >= 0)) {
    throw ConfigError(fmt::format("{}/{}: found {}; expected {}", pointer, key, type_name(*it),
                                  expected));
  }
  return *it;
}

std::vector<std::uint64_t> parse_seeds(const nlohmann::json& seeds) {
  std::vector<std::uint64_t> out;
  const bool too_many = seeds.is_array() ? seeds.size() > limits::kMaxCompareSeeds
                                         : seeds.is_number_unsigned() &&
                                               seeds.get<std::uint64_t>() > limits::kMaxCompareSeeds;
  if (too_many) {
    throw ConfigError(fmt::format("/data/seeds: {} seeds, above the limit of {} per comparison; "
                                  "use fewer seeds (docs/reliability.md, Limits on work)",
                                  seeds.is_array() ? seeds.size() : seeds.get<std::uint64_t>(),
                                  limits::kMaxCompareSeeds));
  }
  if (seeds.is_number_integer() && seeds.get<std::int64_t>() >= 1) {
    for (std::uint64_t s = 1; s <= seeds.get<std::uint64_t>(); ++s) out.push_back(s);
    return out;
  }
  if (seeds.is_array() && !seeds.empty()) {
    std::set<std::uint64_t> unique;
    for (const auto& seed : seeds) {
      if (!seed.is_number_integer() || seed.get<std::int64_t>() < 0) break;
      out.push_back(seed.get<std::uint64_t>());
      unique.insert(out.back());
    }
    if (out.size() == seeds.size() && unique.size() == out.size()) return out;
  }
  throw ConfigError("/data/seeds: expected a count >= 1 or an array of distinct non-negative "
                    "integers");
}

// Rewrites the leading JSON pointer of a run-config error to the variant's place in the
// experiment: "/noise/gyro/params/N: ..." -> "/variants/2/noise/gyro/params/N: ...".
std::string variant_pointer(const std::string& message, std::size_t index,
                            const nlohmann::json& variant) {
  for (std::string_view section : {"/noise", "/aids", "/filter"}) {
    if (message.rfind(section, 0) == 0) {
      const bool own = variant.contains(std::string(section.substr(1)));
      return (own ? fmt::format("/variants/{}", index) : std::string()) + message;
    }
  }
  return fmt::format("/variants/{}: ", index) + message;
}

void check_name(const std::string& name, std::size_t index) {
  const bool ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
  if (!ok) {
    throw ConfigError(fmt::format("/variants/{}/name: '{}' is not a usable name; expected "
                                  "letters, digits, '_', '-' or '.'",
                                  index, name));
  }
}

ExperimentConfig parse_experiment(const nlohmann::json& document, const fs::path& file) {
  if (!document.is_object()) throw ConfigError("/: expected a JSON object (an experiment)");
  reject_unknown_keys(document, "",
                      {"description", "comments", "data", "baseline", "aids", "filter", "variants",
                       "threads", "pairs", "sweep"});
  ExperimentConfig config;
  config.document = document;
  config.file = file;
  // Absolute, so that a bare file name ("compare exp.json") finds its scenario and plugins.
  config.config_dir = fs::absolute(file).parent_path();
  if (document.contains("description")) {
    config.description = member(document, "", "description", nlohmann::json::value_t::string,
                                "a string")
                             .get<std::string>();
  }
  const auto& data = member(document, "", "data", nlohmann::json::value_t::object,
                            "an object: {\"scenario_config\", \"seeds\"} or a run config's data");
  if (data.contains("scenario_config")) {
    reject_unknown_keys(data, "/data", {"scenario_config", "seeds", "scenario_overrides"});
    const fs::path path =
        config.config_dir / member(data, "/data", "scenario_config",
                                   nlohmann::json::value_t::string, "a scenario config file")
                                .get<std::string>();
    std::error_code error;
    if (!fs::is_regular_file(path, error)) {
      throw ConfigError("/data/scenario_config: " + path.string() +
                        " does not exist; give a scenario config (configs/scenarios/)");
    }
    config.scenario_config = path;
    if (!data.contains("seeds")) {
      throw ConfigError("/data/seeds: missing; expected a count >= 1 or an array of seeds");
    }
    config.seeds = parse_seeds(data.at("seeds"));
    if (data.contains("scenario_overrides")) {
      config.scenario_overrides = data.at("scenario_overrides");
      if (!config.scenario_overrides.is_object()) {
        throw ConfigError("/data/scenario_overrides: expected an object {JSON pointer: value}");
      }
      for (const auto& [pointer, value] : config.scenario_overrides.items()) {
        if (pointer.empty() || pointer.front() != '/') {
          throw ConfigError("/data/scenario_overrides: key '" + pointer +
                            "' is not a JSON pointer; expected e.g. \"/drilling/duration_s\"");
        }
      }
    }
  } else {
    config.fixed_data = data;
    config.seeds = {0};
  }
  const auto& variants = member(document, "", "variants", nlohmann::json::value_t::array,
                                "an array of {\"name\", \"noise\", ...}");
  if (variants.empty()) throw ConfigError("/variants: empty; expected at least one variant");
  std::set<std::string> names;
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const std::string pointer = fmt::format("/variants/{}", i);
    const auto& variant = variants[i];
    if (!variant.is_object()) {
      throw ConfigError(pointer + ": expected an object {\"name\", \"noise\", ...}");
    }
    reject_unknown_keys(variant, pointer, {"name", "noise", "aids", "filter"});
    ExperimentVariant v;
    v.name = member(variant, pointer, "name", nlohmann::json::value_t::string, "a string")
                 .get<std::string>();
    check_name(v.name, i);
    if (!names.insert(v.name).second) {
      throw ConfigError(pointer + "/name: '" + v.name + "' is used twice; give unique names");
    }
    v.run_config = nlohmann::json::object();
    v.run_config["noise"] = member(variant, pointer, "noise", nlohmann::json::value_t::object,
                                   "{\"gyro\": {...}, \"accel\": {...}}");
    for (std::string_view section : {"aids", "filter"}) {
      const std::string key(section);
      if (variant.contains(key)) {
        v.run_config[key] = variant[key];
      } else if (document.contains(key)) {
        v.run_config[key] = document[key];
      }
    }
    // Validate as the run config it becomes, the data section aside (the seeds' folders do not
    // exist yet): the experiment file's name stands in for the data, which is not opened here,
    // so a document that never was a file (the Python module's dicts) validates too.
    try {
      const auto run = plugin::parse_run_config(variant_run_document(v, nullptr),
                                                config.config_dir,
                                                plugin::DataConfig{.imu = fs::absolute(file)});
      v.gyro_plugin = run.noise.gyro.type;
    } catch (const ConfigError& error) {
      throw ConfigError(variant_pointer(error.what(), i, variant));
    }
    config.variants.push_back(std::move(v));
  }
  config.baseline = member(document, "", "baseline", nlohmann::json::value_t::string,
                           "the name of a variant")
                        .get<std::string>();
  if (!names.contains(config.baseline)) {
    throw ConfigError("/baseline: '" + config.baseline + "' is not a variant name");
  }
  if (document.contains("threads")) {
    config.threads = member(document, "", "threads", nlohmann::json::value_t::number_unsigned,
                            "a non-negative integer")
                         .get<unsigned>();
  }
  if (document.contains("pairs")) {
    const auto& pairs = document["pairs"];
    if (!pairs.is_array()) {
      throw ConfigError("/pairs: expected an array of [A, B] variant-name pairs");
    }
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const auto& pair = pairs[i];
      if (!pair.is_array() || pair.size() != 2 || !pair[0].is_string() || !pair[1].is_string()) {
        throw ConfigError(fmt::format("/pairs/{}: expected [\"A\", \"B\"] (two variant names)", i));
      }
      for (std::size_t k = 0; k < 2; ++k) {
        if (!names.contains(pair[k].get<std::string>())) {
          throw ConfigError(fmt::format("/pairs/{}/{}: '{}' is not a variant name", i, k,
                                        pair[k].get<std::string>()));
        }
      }
      if (pair[0] == pair[1]) {
        throw ConfigError(fmt::format("/pairs/{}: a variant compared with itself; give two names", i));
      }
      config.pairs.emplace_back(pair[0].get<std::string>(), pair[1].get<std::string>());
    }
  } else {
    for (const auto& variant : config.variants) {
      if (variant.name != config.baseline) config.pairs.emplace_back(variant.name, config.baseline);
    }
  }
  if (document.contains("sweep")) {
    const auto& sweep = member(document, "", "sweep", nlohmann::json::value_t::object,
                               "{\"name\", \"set\": [pointers], \"values\": [...]}");
    reject_unknown_keys(sweep, "/sweep", {"name", "set", "values"});
    ExperimentSweep parsed;
    parsed.name =
        member(sweep, "/sweep", "name", nlohmann::json::value_t::string, "a string").get<std::string>();
    const auto& set = member(sweep, "/sweep", "set", nlohmann::json::value_t::array,
                             "an array of JSON pointers (/scenario/... or /variants/<i>/...)");
    const auto& values = member(sweep, "/sweep", "values", nlohmann::json::value_t::array,
                                "an array of values, one per level");
    if (set.empty()) throw ConfigError("/sweep/set: empty; expected at least one pointer");
    if (values.empty()) throw ConfigError("/sweep/values: empty; expected at least one level");
    for (std::size_t i = 0; i < set.size(); ++i) {
      const bool ok = set[i].is_string() &&
                      (set[i].get<std::string>().rfind("/scenario/", 0) == 0 ||
                       set[i].get<std::string>().rfind("/variants/", 0) == 0);
      if (!ok) {
        throw ConfigError(fmt::format("/sweep/set/{}: expected a JSON pointer starting "
                                      "/scenario/ or /variants/<i>/",
                                      i));
      }
      if (set[i].get<std::string>().rfind("/scenario/", 0) == 0 && !config.scenario_config) {
        throw ConfigError(fmt::format("/sweep/set/{}: /scenario/ pointers need simulated data "
                                      "(data/scenario_config)",
                                      i));
      }
      parsed.set.push_back(set[i].get<std::string>());
    }
    parsed.values.assign(values.begin(), values.end());
    config.sweep = std::move(parsed);
  }
  return config;
}

// Sets `value` at `pointer` of `document`, creating missing keys.
void set_at(nlohmann::json& document, const std::string& pointer, const nlohmann::json& value,
            const std::string& where) {
  try {
    document[nlohmann::json::json_pointer(pointer)] = value;
  } catch (const nlohmann::json::exception& error) {
    throw ConfigError(where + ": cannot set '" + pointer + "' (" + error.what() +
                      "); give a pointer into the document's objects and arrays");
  }
}

}  // namespace

ExperimentConfig experiment_config_from_json(const nlohmann::json& document,
                                             const fs::path& file) {
  try {
    return parse_experiment(document, file);
  } catch (const ConfigError& error) {
    throw ConfigError(file.string() + ": " + error.what());
  }
}

ExperimentConfig sweep_level(const ExperimentConfig& config, std::size_t level) {
  if (!config.sweep || level >= config.sweep->values.size()) {
    throw ConfigError("sweep_level: no such level");
  }
  nlohmann::json document = config.document;
  document.erase("sweep");
  const nlohmann::json& value = config.sweep->values[level];
  nlohmann::json scenario_values = nlohmann::json::object();
  for (std::size_t i = 0; i < config.sweep->set.size(); ++i) {
    const std::string& pointer = config.sweep->set[i];
    const std::string where = fmt::format("{}: /sweep/set/{}", config.file.string(), i);
    if (pointer.rfind("/scenario/", 0) == 0) {
      scenario_values[pointer.substr(std::string("/scenario").size())] = value;
    } else {
      set_at(document, pointer, value, where);
    }
  }
  ExperimentConfig out = experiment_config_from_json(document, config.file);
  out.scenario_overrides = config.scenario_overrides;  // keeps --full-scenario's choice
  if (out.scenario_config) out.seeds = config.seeds;    // and --seeds
  out.scenario_sweep_values = std::move(scenario_values);
  out.document = config.document;  // keep the original for messages
  out.document.erase("sweep");
  return out;
}


nlohmann::json variant_run_document(const ExperimentVariant& variant, const nlohmann::json& data) {
  nlohmann::json document = variant.run_config;
  document["data"] = data;
  return document;
}

ExperimentConfig read_experiment_config(const fs::path& file) {
  const nlohmann::json document = read_json_document(file, "the experiment config");
  return experiment_config_from_json(document, file);
}

}  // namespace stochnav
