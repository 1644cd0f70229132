#pragma once
// The output folder of `stochnav simulate scenario`, written by streaming (memory independent of
// the duration) and atomically: every file goes to a temporary beside its final name and all are
// renamed into place only after the whole run succeeded.
//
//   imu.csv       t,dtheta_x,dtheta_y,dtheta_z,dv_x,dv_y,dv_z (increments) or
//                 t,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z (rates) at the IMU rate. t is the end of the epoch's interval (s).
//                 output "increments": delta-theta (rad) and delta-v (m/s) over the interval;
//                 output "rates": their means, rad/s and m/s^2. Body frame of ins/nav_state.hpp.
//   truth.csv     t,lat,lon,h,ve,vn,vu,inclination,toolface,azimuth at truth_rate_hz from t = 0:
//                 s, deg, deg, m (ellipsoidal), m/s (ENU), deg (ins/mwd_attitude.hpp; near
//                 vertical azimuth 0 and the gyro toolface).
//   aids.csv      t,measured_depth_m,rop_mph,zupt,measured_depth_true_m,rop_true_mph at
//                 aid_rate_hz from t = 0: measured depth with the pipe-tally error
//                 md (1 + depth_scale_error) + white noise, ROP with white noise, zupt 1 when
//                 the tool is stationary, then the true values. When the gyro or accelerometer
//                 noise has aux_sensitivity terms, their channels follow, one column each (the
//                 term's `column`, e.g. temperature_c): its profile at t (model/noise_term.hpp),
//                 the channel the simulated bias follows; without such terms the file is as above.
//                 Aid timing (aids in scenario_config.hpp): rows are sampled at true times
//                 k / aid_rate_hz; t is written as true time + clock_offset_s; the measured
//                 columns and zupt are those of true time max(0, t - latency_s), the *_true
//                 columns and the channels those of the true time; no rows at true times inside
//                 a dropout (the aid noise is drawn for them all the same, so the other rows are
//                 those of the run without dropouts).
//   scenario.json the configuration with every default filled in and the seed used, the column
//                 units, the turn-on biases drawn, the phases, the noise schedule (per phase and
//                 axis, the exact noise model in force) and the derived truth parameters.
// Numbers are written in the shortest form that reads back to the same double.

#include <cstdint>
#include <filesystem>
#include <string>

#include "stochnav/scenario/scenario_config.hpp"

namespace stochnav {

struct ScenarioOutputOptions {
  std::filesystem::path out_dir;  ///< created if missing
  std::uint64_t seed = 0;         ///< seed of this run (overrides the configuration's)
  bool progress = false;          ///< draw a progress bar on stderr
  std::string source;             ///< where the configuration came from (echoed)
};

struct ScenarioRunSummary {
  std::uint64_t epochs = 0;
  double seconds = 0.0;  ///< wall time
};

/// Runs the scenario and writes the four files. Throws InputError when the folder or a file
/// cannot be written (no output file is left behind), ConfigError for unusable noise models.
ScenarioRunSummary write_scenario_outputs(const ScenarioConfig& config,
                                          const ScenarioOutputOptions& options);

}  // namespace stochnav
