#pragma once
// The true motion of a scenario: truth samples and the exact IMU increments it produces.
//
// Kinematics (frames of ins/nav_state.hpp): with position (lat, lon, h), velocity v_n with
// components v_E = (R_N + h) cos(lat) dlon/dt, v_N = (R_M + h) dlat/dt, v_U = dh/dt, their
// time derivatives a_n, and attitude C_nb with omega_nb_b, the ideal IMU measures
//   omega_ib_b = omega_nb_b + C_bn (omega_ie_n + omega_en_n)                    (rad/s)
//   f_b        = C_bn (a_n + (2 omega_ie_n + omega_en_n) x v_n - g_n)          (m/s^2)
// and its increments are the integrals of these over each interval. Both motion models compute
// the integrals exactly (closed forms or Gauss-Legendre sub-quadrature resolving every frequency
// of the motion to ~1e-12 relative); the exceptions, documented with each model, are far below
// any sensor's resolution.

#include <Eigen/Core>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stochnav/scenario/scenario_config.hpp"

namespace stochnav {

/// A time span of a scenario with one motion kind and one noise scale.
struct ScenarioPhase {
  /// "static", "sine", "random", "drilling", "orienting", "connection", "vibration"
  std::string name;
  double start_s = 0.0;            ///< s
  double end_s = 0.0;              ///< s
  bool stationary = false;         ///< the tool does not move relative to Earth (ZUPT valid)
  double gyro_noise_scale = 1.0;   ///< factor on the scheduled gyro noise
  double accel_noise_scale = 1.0;  ///< factor on the scheduled accelerometer noise
};

struct TruthSample {
  double t_s = 0.0;
  double latitude_rad = 0.0;
  double longitude_rad = 0.0;
  double height_m = 0.0;
  Eigen::Vector3d v_n = Eigen::Vector3d::Zero();       ///< m/s, ENU
  Eigen::Matrix3d C_nb = Eigen::Matrix3d::Identity();  ///< body to ENU
  double measured_depth_m = 0.0;  ///< true measured depth of the tool along the well (m)
  double rop_mps = 0.0;           ///< true rate of penetration (m/s), vibration excluded
  bool stationary = false;        ///< as the phase at t_s
};

class TrueMotion {
 public:
  virtual ~TrueMotion();
  TrueMotion() = default;
  TrueMotion(const TrueMotion&) = delete;
  TrueMotion& operator=(const TrueMotion&) = delete;

  /// The true state at time t_s in [0, duration_s()].
  virtual TruthSample truth(double t_s) = 0;

  /// Exact integrals of omega_ib_b (rad) and f_b (m/s) over [t0_s, t1_s], t0_s < t1_s.
  virtual void integrate(double t0_s, double t1_s, Eigen::Vector3d& delta_theta_b,
                         Eigen::Vector3d& delta_v_b) = 0;

  /// Phases in time order, covering [0, duration_s()].
  virtual const std::vector<ScenarioPhase>& phases() const = 0;
  virtual double duration_s() const = 0;

  /// Derived truth parameters for scenario.json (vibration components, stand schedule, ...).
  virtual nlohmann::json describe() const = 0;
};

/// The motion model of a validated configuration; `seed` fixes the random vibration.
std::unique_ptr<TrueMotion> make_true_motion(const ScenarioConfig& config, std::uint64_t seed);

}  // namespace stochnav
