#pragma once
// Survey QC without truth, as gyro-MWD practice checks a station: from the connection's own
// static data alone (the raw IMU increments of its stationary span, no filter), the inclination
// the accelerometers give, the azimuth a gyrocompass gives, the gravity total and the Earth-rate
// total, each with its 1-sigma from the sensor error budget; then the continuous solution's
// inclination and azimuth at the station against them.
//
// Static solution: coarse_alignment (filter/alignment.hpp) of the span's mean rate and specific
// force: inclination from the specific force (levelling), azimuth from the horizontal Earth rate
// (gyrocompass). Sigmas by first-order propagation (central differences) of the mean rate's
// error, sigma_b_g^2 + q_g / T per body axis, and the mean specific force's, sigma_b_a^2 +
// (sigma_s g)^2 + q_a / T: sigma_b the sensor's bias 1-sigma before any estimation (the run
// config's initial sigmas: the check must not lean on the filter it checks), sigma_s the scale
// factor's, q the white-noise PSD of the noise models, T the span. A heading error from a
// gyro bias across the Earth rate is bias / (W cos lat): the gyrocompass sigma is large near
// the poles and in an east-west hole for the along-hole bias, and says so.
//
// Flag: |inclination_continuous - inclination_static| > 3 sqrt(sigma_c^2 + sigma_s^2), or the
// same for the azimuth (where the hole is more than kMinimumInclination_deg off vertical). The
// continuous and static solutions share the span's data through the ZUPTs, so the test is
// conservative (it would be sharper with the correlation). The gravity and Earth-rate totals
// check the sensors, not the solution: reported with their sigmas, not flagged.
//
// Units: degrees, m/s^2, deg/h in the outputs; radians and SI inside.

#include <Eigen/Core>

namespace stochnav {

/// The raw increments of a stationary span, summed (body frame).
struct StaticSpan {
  Eigen::Vector3d delta_theta_b = Eigen::Vector3d::Zero();  ///< rad
  Eigen::Vector3d delta_v_b = Eigen::Vector3d::Zero();      ///< m/s
  double duration_s = 0.0;                                  ///< s
  void add(const Eigen::Vector3d& delta_theta, const Eigen::Vector3d& delta_v, double dt_s) {
    delta_theta_b += delta_theta;
    delta_v_b += delta_v;
    duration_s += dt_s;
  }
  void add(const StaticSpan& other) { add(other.delta_theta_b, other.delta_v_b, other.duration_s); }
};

/// The sensor error budget of the QC (1-sigma, body axes, SI). The bias variance at a station
/// elapsed_s after the start is bias_sigma^2 + bias_walk_psd * elapsed_s: the turn-on bias and
/// the stationary variance of the noise model's correlated states (a flicker bank), plus its
/// bias random walk.
struct StationQcBudget {
  double latitude_rad = 0.0;
  double height_m = 0.0;
  double start_t_s = 0.0;  ///< when the biases had the sigmas below (s)
  Eigen::Vector3d gyro_bias_sigma_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias_sigma_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias_walk_psd = Eigen::Vector3d::Zero();   ///< (rad/s)^2 / s
  Eigen::Vector3d accel_bias_walk_psd = Eigen::Vector3d::Zero();  ///< (m/s^2)^2 / s
  Eigen::Vector3d accel_scale_factor_sigma = Eigen::Vector3d::Zero();  ///< dimensionless
  Eigen::Vector3d gyro_white_psd = Eigen::Vector3d::Zero();            ///< (rad/s)^2 / Hz
  Eigen::Vector3d accel_white_psd = Eigen::Vector3d::Zero();           ///< (m/s^2)^2 / Hz
};

/// Spans shorter than this give no QC (s).
inline constexpr double kMinimumStaticSpan_s = 10.0;
/// Below this inclination the azimuth is not checked (deg).
inline constexpr double kMinimumInclination_deg = 3.0;

/// One station's QC; NaN where not defined (a span too short, a hole near vertical).
struct StationQc {
  double static_duration_s = 0.0;
  double static_inclination_deg = 0.0;
  double static_inclination_sigma_deg = 0.0;
  double gyrocompass_azimuth_deg = 0.0;
  double gyrocompass_azimuth_sigma_deg = 0.0;
  double gravity_total_m_s2 = 0.0;  ///< |mean f|
  double gravity_model_m_s2 = 0.0;  ///< normal gravity at the tie-on latitude and height
  double gravity_sigma_m_s2 = 0.0;
  double earth_rate_total_deg_h = 0.0;         ///< |mean omega|
  double earth_rate_sigma_deg_h = 0.0;         ///< against 15.041 deg/h
  double inclination_difference_sigmas = 0.0;  ///< |continuous - static| / combined sigma
  double azimuth_difference_sigmas = 0.0;
  bool flagged = false;  ///< a difference or a total beyond 3 sigma
  bool checked = false;  ///< the span was long enough for a QC
};

/// The QC of a station at t_s from its span, against the continuous solution's angles (deg) and
/// their 1-sigmas.
StationQc station_qc(const StaticSpan& span, const StationQcBudget& budget, double t_s,
                     double continuous_inclination_deg, double continuous_inclination_sigma_deg,
                     double continuous_azimuth_deg, double continuous_azimuth_sigma_deg);

}  // namespace stochnav
