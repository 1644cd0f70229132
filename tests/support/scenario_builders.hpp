#pragma once
// Scenario configurations built in code for the ins and scenario tests (no sensor errors unless
// a test adds them).

#include <numbers>

#include "stochnav/ins/nav_state.hpp"
#include "stochnav/scenario/scenario_config.hpp"
#include "stochnav/scenario/true_motion.hpp"

namespace stochnav::testing {

inline constexpr double kDeg = std::numbers::pi / 180.0;
inline constexpr double kG = 9.80665;

inline SensorErrorConfig no_sensor_errors(Unit unit) {
  SensorErrorConfig sensor;
  for (auto& m : sensor.noise) m = NoiseModel{unit, 100.0, {}};
  for (auto& m : sensor.scheduled_noise) m = NoiseModel{unit, 100.0, {}};
  return sensor;
}

inline ScenarioConfig base_config(ScenarioKind kind) {
  ScenarioConfig config;
  config.kind = kind;
  config.imu.rate_hz = 100.0;
  config.imu.truth_rate_hz = 100.0;
  config.imu.aid_rate_hz = 1.0;
  config.site = {39.9778 * kDeg, 116.3448 * kDeg, 50.0};
  config.gyro = no_sensor_errors(Unit::kDegPerHour);
  config.accel = no_sensor_errors(Unit::kMeterPerSecondSquared);
  return config;
}

/// A vibration table at an attitude with the given phases.
inline ScenarioConfig table_config(MwdAttitude attitude, std::vector<TablePhaseConfig> phases) {
  ScenarioConfig config = base_config(ScenarioKind::kVibrationTable);
  config.vibration_table = VibrationTableConfig{attitude, std::move(phases)};
  return config;
}

inline TablePhaseConfig static_phase(double duration_s) {
  TablePhaseConfig phase;
  phase.name = "static";
  phase.duration_s = duration_s;
  return phase;
}

inline TablePhaseConfig sine_phase(double duration_s, double frequency_hz, double amplitude_g) {
  TablePhaseConfig phase;
  phase.name = "sine";
  phase.duration_s = duration_s;
  phase.motion = TableMotion::kSine;
  phase.sine = {frequency_hz, amplitude_g * kG};
  return phase;
}

inline TablePhaseConfig random_phase(double duration_s, double rms_g, int components) {
  TablePhaseConfig phase;
  phase.name = "random";
  phase.duration_s = duration_s;
  phase.motion = TableMotion::kRandom;
  phase.random.psd = {{20.0, 0.087 * kG * kG}, {2000.0, 0.087 * kG * kG}};
  phase.random.rms_mps2 = rms_g * kG;
  phase.random.components = components;
  return phase;
}

/// A fast drilling run: vertical, build at 10 deg/30 m from 40 m, 60 rpm, stands of 9 m drilled
/// at 120 m/h with 60 s connections, one axial vibration episode.
inline ScenarioConfig drilling_config(double duration_s) {
  ScenarioConfig config = base_config(ScenarioKind::kDrilling);
  DrillingConfig d;
  d.well = {40.0, 10.0 * kDeg / 30.0, 90.0 * kDeg, 60.0 * kDeg};
  d.start_md_m = 20.0;
  d.duration_s = duration_s;
  d.initial_static_s = 120.0;
  d.rop_mps = 120.0 / 3600.0;
  d.rotation_radps = 2.0 * std::numbers::pi;
  d.initial_toolface_rad = 0.3;
  d.stand_length_m = 9.0;
  d.connection_s = 60.0;
  d.ramp_s = 10.0;
  d.vibration_episodes = {{500.0, 620.0, 2.0 * kG, 12.0}};
  d.vibration_noise = {10.0, 3.0};
  config.drilling = d;
  return config;
}

/// The navigation state of a truth sample (to start a strapdown run on the truth).
inline NavState nav_state_of(const TruthSample& truth) {
  NavState state;
  state.t_s = truth.t_s;
  state.latitude_rad = truth.latitude_rad;
  state.longitude_rad = truth.longitude_rad;
  state.height_m = truth.height_m;
  state.v_n = truth.v_n;
  state.q_nb = Eigen::Quaterniond(truth.C_nb);
  return state;
}

}  // namespace stochnav::testing
