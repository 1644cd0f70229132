#include "scenario_noise.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/scenario/scenario_config_json.hpp"

namespace stochnav::oracle {

ScenarioNoise read_scenario_noise(const std::filesystem::path& scenario_dir,
                                  plugin::SensorGroup group) {
  const std::filesystem::path file = scenario_dir / "scenario.json";
  std::ifstream stream(file);
  if (!stream) {
    throw InputError(file.string() +
                     ": cannot read; expected the folder of a scenario made by "
                     "`stochnav simulate scenario`");
  }
  const nlohmann::json document = nlohmann::json::parse(stream, nullptr, false);
  const std::string name(plugin::sensor_group_name(group));
  const nlohmann::json::json_pointer scheduled_pointer("/scheduled_noise_models/" + name);
  if (document.is_discarded() || !document.contains("config") || !document.contains("duration_s") ||
      !document["duration_s"].is_number() || !document.contains(scheduled_pointer) ||
      !document[scheduled_pointer].is_array() || document[scheduled_pointer].size() != 3) {
    throw InputError(file.string() +
                     ": not a scenario record; expected JSON with \"config\", \"duration_s\" and "
                     "\"scheduled_noise_models\"/" +
                     name + " (three models)");
  }
  // Names the file (and "/config/..." pointers) itself when the configuration is invalid.
  const ScenarioConfig config = scenario_config_from_json(document["config"], file.string());
  const SensorErrorConfig& sensor =
      group == plugin::SensorGroup::kGyro ? config.gyro : config.accel;
  ScenarioNoise noise;
  noise.rate_hz = config.imu.rate_hz;
  noise.duration_s = document["duration_s"].get<double>();
  try {
    for (std::size_t i = 0; i < 3; ++i) {
      noise.constant[i] = sensor.noise[i];
      noise.scheduled[i] = noise_model_from_json(
          document[scheduled_pointer][i], scheduled_pointer.to_string() + "/" + std::to_string(i));
    }
  } catch (const ConfigError& error) {
    throw InputError(file.string() + ": " + error.what());
  }
  return noise;
}

}  // namespace stochnav::oracle
