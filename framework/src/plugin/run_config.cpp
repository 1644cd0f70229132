#include "stochnav/plugin/run_config.hpp"

#include <algorithm>
#include <fstream>

#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/params.hpp"

namespace stochnav::plugin {
namespace fs = std::filesystem;
namespace {

fs::path resolve(const fs::path& config_dir, const std::string& text) {
  const fs::path path(text);
  return path.is_absolute() ? path : config_dir / path;
}

fs::path existing_file(ParamReader& reader, std::string_view key, const fs::path& config_dir) {
  const fs::path path = resolve(config_dir, reader.text(key));
  std::error_code error;
  if (!fs::is_regular_file(path, error)) {
    throw ConfigError(reader.pointer(key) + ": file not found: " + path.string() +
                      "; give an existing file (relative paths start at the config's folder)");
  }
  return path;
}

const nlohmann::json& object_at(ParamReader& reader, std::string_view key, bool required) {
  const nlohmann::json& value = reader.raw(key);
  if (value.is_null() && !required) return value;
  if (!value.is_object()) {
    throw ConfigError(reader.pointer(key) + (value.is_null() ? ": missing" : ": not an object") +
                      "; expected an object");
  }
  return value;
}

DataConfig parse_data(const nlohmann::json& json, const std::string& pointer,
                      const fs::path& config_dir) {
  ParamReader reader(json, pointer);
  DataConfig data;
  const bool scenario = reader.has("scenario");
  const bool imu = reader.has("imu");
  if (scenario == imu) {
    throw ConfigError(
        pointer + ": " +
        (scenario ? std::string("both \"scenario\" and \"imu\" given") : std::string("no data")) +
        "; expected {\"scenario\": FOLDER} or {\"imu\": FILE, \"truth\": FILE, "
        "\"aids\": FILE}");
  }
  if (scenario) {
    data.scenario_dir = resolve(config_dir, reader.text("scenario"));
    std::error_code error;
    if (!fs::is_directory(data.scenario_dir, error)) {
      throw ConfigError(reader.pointer("scenario") +
                        ": folder not found: " + data.scenario_dir.string() +
                        "; give the folder written by `stochnav simulate scenario`");
    }
    data.imu = data.scenario_dir / kScenarioImuFile;
    if (!fs::is_regular_file(data.imu, error)) {
      throw ConfigError(reader.pointer("scenario") + ": no " + std::string(kScenarioImuFile) +
                        " in " + data.scenario_dir.string() +
                        "; give the folder written by `stochnav simulate scenario`");
    }
    if (fs::is_regular_file(data.scenario_dir / kScenarioTruthFile, error)) {
      data.truth = data.scenario_dir / kScenarioTruthFile;
    }
    if (fs::is_regular_file(data.scenario_dir / kScenarioAidsFile, error)) {
      data.aids = data.scenario_dir / kScenarioAidsFile;
    }
  } else {
    data.imu = existing_file(reader, "imu", config_dir);
    if (reader.has("truth")) data.truth = existing_file(reader, "truth", config_dir);
    if (reader.has("aids")) data.aids = existing_file(reader, "aids", config_dir);
  }
  reader.finish();
  return data;
}

PluginConfig parse_plugin_entry(ParamReader& reader, const std::string& pointer) {
  PluginConfig entry;
  entry.pointer = pointer;
  entry.type = reader.text("plugin");
  const nlohmann::json& params = reader.raw("params");
  if (!params.is_null()) {
    if (!params.is_object()) {
      throw ConfigError(reader.pointer("params") +
                        ": not an object; expected the plugin's "
                        "parameters as an object");
    }
    entry.params = params;
  }
  return entry;
}

FitConfig parse_fit(const nlohmann::json& json, const std::string& pointer, SensorGroup group,
                    const fs::path& config_dir, const fs::path& default_record) {
  ParamReader reader(json, pointer);
  FitConfig fit;
  fit.record = reader.has("record") ? existing_file(reader, "record", config_dir) : default_record;
  fit.start_s = reader.number_or("start_s", 0.0, Bound::kNonNegative, "s");
  if (reader.has("end_s")) {
    fit.end_s = reader.number("end_s", Bound::kPositive, "s");
    if (!(*fit.end_s > fit.start_s)) {
      throw ConfigError(reader.pointer("end_s") + ": " + std::to_string(*fit.end_s) +
                        " s is not after start_s; expected end_s > start_s");
    }
  }
  const auto& defaults = group == SensorGroup::kGyro ? kGyroColumns : kAccelColumns;
  for (std::size_t i = 0; i < 3; ++i) fit.columns[i] = std::string(defaults[i]);
  const nlohmann::json& columns = reader.raw("columns");
  if (!columns.is_null()) {
    const bool ok = columns.is_array() && columns.size() == 3 &&
                    std::all_of(columns.begin(), columns.end(), [](const nlohmann::json& c) {
                      return c.is_string() && !c.get<std::string>().empty();
                    });
    if (!ok) {
      throw ConfigError(reader.pointer("columns") + ": found " + columns.dump() +
                        "; expected three column names [x, y, z]");
    }
    for (std::size_t i = 0; i < 3; ++i) fit.columns[i] = columns[i].get<std::string>();
  }
  reader.finish();
  return fit;
}

std::array<double, 3> axes_or(ParamReader& reader, std::string_view key,
                              const std::array<double, 3>& fallback, std::string_view unit) {
  return reader.axes_or(key, fallback, Bound::kNonNegative, unit);
}

}  // namespace

NoiseSection parse_noise_section(const nlohmann::json& json, const std::string& pointer,
                                 const fs::path& config_dir, const fs::path& default_record) {
  ParamReader section(json, pointer);
  NoiseSection noise;
  for (SensorGroup group : {SensorGroup::kGyro, SensorGroup::kAccel}) {
    const std::string key(sensor_group_name(group));
    const nlohmann::json& entry_json = object_at(section, key, true);
    ParamReader entry(entry_json, section.pointer(key));
    NoiseConfig config;
    static_cast<PluginConfig&>(config) = parse_plugin_entry(entry, section.pointer(key));
    const nlohmann::json& fit = entry.raw("fit");
    if (!fit.is_null()) {
      config.fit = parse_fit(fit, entry.pointer("fit"), group, config_dir, default_record);
    }
    entry.finish();
    (group == SensorGroup::kGyro ? noise.gyro : noise.accel) = std::move(config);
  }
  section.finish();
  return noise;
}

std::vector<PluginConfig> parse_aids_section(const nlohmann::json& json,
                                             const std::string& pointer) {
  if (!json.is_array()) {
    throw ConfigError(pointer + ": found " + json.dump().substr(0, 40) +
                      "; expected an array of {\"plugin\": TYPE, \"params\": {...}}");
  }
  std::vector<PluginConfig> aids;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const std::string item_pointer = pointer + "/" + std::to_string(i);
    if (!json[i].is_object()) {
      throw ConfigError(item_pointer +
                        ": not an object; expected {\"plugin\": TYPE, \"params\": {...}}");
    }
    ParamReader entry(json[i], item_pointer);
    aids.push_back(parse_plugin_entry(entry, item_pointer));
    entry.finish();
  }
  return aids;
}

RunConfig parse_run_config(const nlohmann::json& document, const fs::path& config_dir) {
  if (!document.is_object()) {
    throw ConfigError(
        "/: the run config is not a JSON object; expected {\"data\": ..., "
        "\"noise\": ..., ...}");
  }
  ParamReader root(document, "");
  RunConfig config;
  config.config_dir = config_dir;
  config.data = parse_data(object_at(root, "data", true), root.pointer("data"), config_dir);
  config.noise = parse_noise_section(object_at(root, "noise", true), root.pointer("noise"),
                                     config_dir, config.data.imu);
  if (const auto& aids = root.raw("aids"); !aids.is_null()) {
    config.aids = parse_aids_section(aids, root.pointer("aids"));
  }
  if (const auto& filter = object_at(root, "filter", false); !filter.is_null()) {
    ParamReader reader(filter, root.pointer("filter"));
    if (const auto& sigma = object_at(reader, "initial_sigma", false); !sigma.is_null()) {
      ParamReader s(sigma, reader.pointer("initial_sigma"));
      auto& out = config.filter.initial_sigma;
      out.position_m = axes_or(s, "position_m", out.position_m, "m");
      out.velocity_m_s = axes_or(s, "velocity_m_s", out.velocity_m_s, "m/s");
      out.attitude_deg = axes_or(s, "attitude_deg", out.attitude_deg, "deg");
      out.accel_bias_m_s2 = axes_or(s, "accel_bias_m_s2", out.accel_bias_m_s2, "m/s^2");
      out.gyro_bias_deg_h = axes_or(s, "gyro_bias_deg_h", out.gyro_bias_deg_h, "deg/h");
      s.finish();
    }
    constexpr std::string_view kModes[] = {"closed_loop", "open_loop"};
    config.filter.feedback = reader.choice_or("feedback", "closed_loop", kModes) == "open_loop"
                                 ? FeedbackMode::kOpenLoop
                                 : FeedbackMode::kClosedLoop;
    reader.finish();
  }
  if (const auto& output = object_at(root, "output", false); !output.is_null()) {
    ParamReader reader(output, root.pointer("output"));
    if (reader.has("decimation")) {
      const auto& value = reader.raw("decimation");
      if (!value.is_number_integer() || value.get<long long>() < 1) {
        throw ConfigError(reader.pointer("decimation") + ": found " + value.dump() +
                          "; expected an integer >= 1");
      }
      config.output.decimation = value.get<std::size_t>();
    }
    config.output.covariance = reader.boolean_or("covariance", config.output.covariance);
    config.output.nees = reader.boolean_or("nees", config.output.nees);
    reader.finish();
  }
  root.finish();
  return config;
}

RunConfig read_run_config(const fs::path& file) {
  std::ifstream stream(file);
  if (!stream) {
    throw InputError(file.string() + ": cannot read the run config; check the path");
  }
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(stream);
  } catch (const nlohmann::json::parse_error& error) {
    throw InputError(file.string() + ": not valid JSON (" + error.what() + "); fix the syntax");
  }
  return parse_run_config(document, fs::absolute(file).parent_path());
}

}  // namespace stochnav::plugin
