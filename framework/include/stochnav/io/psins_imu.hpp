#pragma once
// Reader of the PSINS toolbox's compact SIMU text format (Yan Gongmin's "*.imu"): '%' comment
// lines, then three header rows
//   pitch0 roll0 yaw0 (deg; yaw counter-clockwise from North) VE0 VN0 VU0 (m/s)
//   latitude0 longitude0 (deg) height0 (m) t0 (s) sampling interval (ms) g (m/s^2)
//   gyro scale x y z (arcsec/count) accelerometer scale x y z (ug*s/count)
// then one row per epoch of six integer increments (gyro x y z, accel x y z, counts), body axes
// x right, y forward, z up.

#include <array>
#include <string>
#include <vector>

namespace stochnav {

struct PsinsImuRecord {
  std::array<double, 3> attitude_deg{};  ///< pitch, roll, yaw (yaw CCW from North) as written
  std::array<double, 3> velocity_mps{};  ///< VE, VN, VU as written
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double height_m = 0.0;
  double start_time_s = 0.0;
  double interval_s = 0.0;  ///< sampling interval (s)
  double gravity_mps2 = 0.0;
  /// Per epoch: delta-theta x y z (rad) and delta-v x y z (m/s), body axes right-forward-up.
  std::vector<std::array<double, 6>> increments;
};

/// Reads the whole file (the format has no streaming use: records are minutes long). Throws
/// InputError "file:line: ..." for a missing header row or a malformed epoch.
PsinsImuRecord read_psins_imu(const std::string& path);

}  // namespace stochnav
