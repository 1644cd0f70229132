#pragma once
// The properties every noise-model plugin must have (noise_model_plugin.hpp), as plain checks
// that return one line per failure: used by `stochnav plugins check LIB --params JSON` and by
// the GoogleTest suite stochnav/testing/noise_model_properties.hpp, so both check the same.
//
//   covariances   Qw, Qb, Qd symmetric positive semi-definite at every t in times_s and dt in
//                 psd_steps_s, not all zero; P0 symmetric positive semi-definite
//   zero step     dt = 0 gives Qw = Qb = Qd = 0 and Phi = I, at every t in times_s
//   composition   Phi2 Qd1 Phi2^T + Qd2 = Qd(dt1 + dt2), Phi2 Phi1 = Phi(dt1 + dt2),
//                 Qw1 + Qw2 = Qw(dt1 + dt2) (same for Qb), starting at every t in times_s: put
//                 a time-varying model's features (a change of level, a segment) among them
//   stationarity  P0 kept by stationary_steps steps of stationary_step_s from the first time
//                 (models with augmented states)
//   round trip    the factory rebuilds from params() a model equal to it both ways;
//                 describe() names the type; M not all zero when there are augmented states
//
// A model defined on a grid of propagation intervals (ar, arma) needs dt1, dt2 and
// stationary_step_s on that grid.

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stochnav/plugin/noise_model_plugin.hpp"

namespace stochnav::plugin {

struct PropertyCheckOptions {
  std::vector<double> times_s = {3.0, 5.0, 7.0};               ///< start times t (s)
  std::vector<double> psd_steps_s = {1e-4, 0.01, 1.0, 100.0};  ///< steps dt (s)
  double dt1_s = 0.37;                                         ///< first composed step (s)
  double dt2_s = 1.9;                                          ///< second composed step (s)
  double stationary_step_s = 0.01;                             ///< step of the stationarity run (s)
  int stationary_steps = 100000;
  double symmetry_tolerance = 1e-14;     ///< relative to the largest entry
  double composition_tolerance = 1e-12;  ///< relative to the largest entry
  double stationarity_tolerance = 1e-9;  ///< relative to the largest entry of P0
  double equals_tolerance = 1e-12;       ///< rel_tol of equals()

  /// Empty when usable, else why not ("times_s is empty", "dt1_s <= 0", ...).
  std::string invalid_reason() const;
};

/// Builds a model of the same plugin from params (the plugin's factory, through a registry).
using NoiseModelRebuild =
    std::function<std::shared_ptr<NoiseModelPlugin>(const nlohmann::json& params)>;

std::vector<std::string> check_covariances(const NoiseModelPlugin& model,
                                           const PropertyCheckOptions& options);
std::vector<std::string> check_zero_step(const NoiseModelPlugin& model,
                                         const PropertyCheckOptions& options);
std::vector<std::string> check_composition(const NoiseModelPlugin& model,
                                           const PropertyCheckOptions& options);
std::vector<std::string> check_stationarity(const NoiseModelPlugin& model,
                                            const PropertyCheckOptions& options);
/// Any exception of the rebuild is reported as a failure.
std::vector<std::string> check_params_round_trip(const NoiseModelPlugin& model,
                                                 const NoiseModelRebuild& rebuild,
                                                 const PropertyCheckOptions& options);

/// All of the above, in that order.
std::vector<std::string> check_noise_model(const NoiseModelPlugin& model,
                                           const NoiseModelRebuild& rebuild,
                                           const PropertyCheckOptions& options = {});

}  // namespace stochnav::plugin
