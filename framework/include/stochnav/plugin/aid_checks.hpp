#pragma once
// The properties every aid plugin must have (aid_plugin.hpp), as plain checks that return one
// line per failure: used by `stochnav plugins check LIB --params JSON` and by the GoogleTest
// suite stochnav/testing/aid_properties.hpp, so both check the same. Each line starts with the
// check's name and gives the numbers.
//
// An aid is checked at one epoch of an AidCheckCase: the true state, the time t_s at which the
// aid has a measurement, the IMU sample there, built from aid data that are what the tool at the
// true state measures (the residual at the truth is then zero). The plugin author writes those
// data: one or two rows of the aid's columns computed from the true state (a position fix at
// the true position, a depth increment equal to the true speed times the interval).
//
//   sizes         measurement_size() >= 1 and the same on every call; has_measurement(t_s) true
//                 and repeatable; measure() at the truth returns true, writes every entry of z
//                 (m), H (m x 15) and R (m x m) (outputs start as NaN) and nothing beside them,
//                 and gives the same outputs on a second call
//   covariance    R finite, symmetric (|R - R^T| <= symmetry_tolerance max|R|), positive
//                 definite (smallest eigenvalue > 0)
//   truth         |z_i| <= residual_tolerance sqrt(R_ii) at the truth (data consistent with it)
//   jacobian      H = dz/d(dx) by central differences, per core state j = 0..14: the estimate is
//                 the truth with the error dx = +-step e_j injected by the navigator's own
//                 feedback (filter/core_correction.hpp: apply_core_correction(-dx), so the
//                 position moves by dx ENU metres through latitude, longitude and height, and
//                 C_nb_est = (I - [phi x]) C_nb_true); the IMU sample seen through the estimated
//                 biases (f_ib_b - db_a, omega_ib_b - db_g) and the interval mean moved by its
//                 map (mean_v_n + mean_velocity_error_map dx, InsInterval); reference_v_n kept.
//                 Passes when |H_ij - N_ij| <= jacobian_absolute + jacobian_relative
//                 max(|H_ij|, |N_ij|) for every row i (as Ceres' GradientChecker)
//   round trip    the factory rebuilds from the same params an equal aid: same type,
//                 measurement size and describe(), same z, H, R at the case; describe() starts
//                 with type()

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stochnav/ins/nav_state.hpp"
#include "stochnav/plugin/aid_plugin.hpp"

namespace stochnav::plugin {

/// The epoch an aid is checked at.
struct AidCheckCase {
  NavState truth;    ///< the true state at t_s (its t_s is not used)
  double t_s = 1.0;  ///< a time (s) at which the aid has a measurement
  ImuSample imu;     ///< the IMU at t_s, true biases removed (steady_imu_sample())
};

/// The IMU sample of a tool moving steadily at truth.v_n with the attitude truth.q_nb: specific
/// force C_bn (-gravity_n) (m/s^2), angular rate C_bn omega_ie_n (rad/s), and the interval
/// [t_s - interval_s, t_s] of an interval aid (InsInterval): mean_v_n = truth.v_n, the map of a
/// constant specific force f_n, [0, I, -(T/2) [f_n x], (T/2) C_nb, 0], noise covariance
/// (1e-4 m/s)^2 I; reference_v_n = truth.v_n. interval_s = 0 gives no interval.
ImuSample steady_imu_sample(const NavState& truth, double t_s, double interval_s);

struct AidCheckOptions {
  double position_step_m = 1e-3;    ///< finite-difference step of the position states (m)
  double step = 1e-6;               ///< step of the other states (m/s, rad, m/s^2, rad/s)
  double jacobian_absolute = 1e-6;  ///< aid units per state unit
  double jacobian_relative = 1e-4;
  double residual_tolerance = 1e-6;   ///< at the truth, in 1-sigmas of R
  double symmetry_tolerance = 1e-12;  ///< relative to the largest |R_ij|

  /// Empty when usable, else why not ("step <= 0", ...).
  std::string invalid_reason() const;
};

/// Builds an aid of the same plugin from params (the plugin's factory, through a registry, with
/// the case's aid data and context).
using AidRebuild = std::function<std::shared_ptr<AidPlugin>(const nlohmann::json& params)>;

// Each check returns one line per failure, empty when the property holds. The checks after
// sizes say nothing (empty) when measure() gives no measurement at the case: sizes reports it.
std::vector<std::string> check_aid_sizes(const AidPlugin& aid, const AidCheckCase& at);
std::vector<std::string> check_aid_covariance(const AidPlugin& aid, const AidCheckCase& at,
                                              const AidCheckOptions& options);
std::vector<std::string> check_aid_residual_at_truth(const AidPlugin& aid, const AidCheckCase& at,
                                                     const AidCheckOptions& options);
std::vector<std::string> check_aid_jacobian(const AidPlugin& aid, const AidCheckCase& at,
                                            const AidCheckOptions& options);
/// Any exception of the rebuild is reported as a failure.
std::vector<std::string> check_aid_round_trip(const AidPlugin& aid, const AidRebuild& rebuild,
                                              const nlohmann::json& params, const AidCheckCase& at);

/// All of the above, in that order; the later checks only when measure() gives a measurement.
std::vector<std::string> check_aid(const AidPlugin& aid, const AidRebuild& rebuild,
                                   const nlohmann::json& params, const AidCheckCase& at,
                                   const AidCheckOptions& options = {});

}  // namespace stochnav::plugin
