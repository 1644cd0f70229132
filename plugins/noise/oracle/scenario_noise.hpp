#pragma once
// The true sensor noise of a simulated scenario, read back from its scenario.json (written by
// scenario/scenario_writer.cpp): per axis the constant noise model of the sensor
// ("config"/"sensors"/<group>/"noise") and the scheduled model with its nonstationary term
// ("scheduled_noise_models"/<group>/<axis>), plus what fixes the simulator's flicker bank (the IMU
// rate and the duration).

#include <array>
#include <filesystem>

#include "stochnav/model/noise_model.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"

namespace stochnav::oracle {

struct ScenarioNoise {
  double rate_hz = 0.0;                 ///< IMU rate (Hz): the simulator's tau0 = 1 / rate_hz
  double duration_s = 0.0;              ///< the simulator's flicker band upper end (s)
  std::array<NoiseModel, 3> constant;   ///< per axis x, y, z, natural units
  std::array<NoiseModel, 3> scheduled;  ///< per axis, with the phases' nonstationary term
};

/// Reads <scenario_dir>/scenario.json for one sensor group. Throws InputError naming the file
/// (and the JSON pointer) when it is missing, unreadable or not a scenario's record.
ScenarioNoise read_scenario_noise(const std::filesystem::path& scenario_dir,
                                  plugin::SensorGroup group);

}  // namespace stochnav::oracle
