#include "stochnav/plugin/noise_model_checks.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>

namespace stochnav::plugin {
namespace {

struct Step {
  Eigen::MatrixXd q_white = Eigen::MatrixXd::Zero(3, 3);
  Eigen::MatrixXd q_bias = Eigen::MatrixXd::Zero(3, 3);
  Eigen::MatrixXd phi, q_d;
};

Step step(const NoiseModelPlugin& model, double t_s, double dt_s) {
  const int n = model.augmented_size();
  Step s;
  s.phi = Eigen::MatrixXd::Zero(n, n);
  s.q_d = Eigen::MatrixXd::Zero(n, n);
  model.white_noise_covariance(t_s, dt_s, s.q_white);
  model.bias_walk_covariance(t_s, dt_s, s.q_bias);
  model.augmented_transition(t_s, dt_s, s.phi, s.q_d);
  return s;
}

double largest(const Eigen::MatrixXd& a) { return a.size() == 0 ? 0.0 : a.cwiseAbs().maxCoeff(); }

/// Appends a failure when q is not symmetric positive semi-definite.
void require_symmetric_psd(const Eigen::MatrixXd& q, double tolerance, const std::string& what,
                           std::vector<std::string>& failures) {
  if (q.size() == 0) return;
  if (!q.allFinite()) {
    failures.push_back(what + ": not finite");
    return;
  }
  const double scale = std::max(largest(q), 1e-300);
  const double asymmetry = largest(q - q.transpose());
  if (asymmetry > tolerance * scale) {
    failures.push_back(fmt::format("{}: not symmetric (max |Q - Q^T| = {:.3g}, max |Q| = {:.3g})",
                                   what, asymmetry, scale));
    return;
  }
  const double lowest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(q).eigenvalues().minCoeff();
  if (lowest < -tolerance * scale) {
    failures.push_back(
        fmt::format("{}: not positive semi-definite (smallest eigenvalue {:.3g}, max |Q| = {:.3g})",
                    what, lowest, scale));
  }
}

/// Appends a failure when a and b differ by more than tolerance times their largest entry.
void require_close(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double tolerance,
                   const std::string& what, std::vector<std::string>& failures) {
  if (a.size() == 0) return;
  const double scale = std::max({largest(a), largest(b), 1e-300});
  const double difference = (a - b).allFinite() ? largest(a - b) : HUGE_VAL;
  if (!(difference <= tolerance * scale)) {
    failures.push_back(fmt::format("{}: differ by {:.3g} relative (tolerance {:.3g})", what,
                                   difference / scale, tolerance));
  }
}

}  // namespace

std::string PropertyCheckOptions::invalid_reason() const {
  if (times_s.empty()) return "times_s is empty";
  if (psd_steps_s.empty()) return "psd_steps_s is empty";
  if (!(dt1_s > 0.0) || !(dt2_s > 0.0)) return "dt1_s and dt2_s must be > 0";
  if (!(stationary_step_s > 0.0) || stationary_steps < 1) {
    return "stationary_step_s must be > 0 and stationary_steps >= 1";
  }
  return {};
}

std::vector<std::string> check_covariances(const NoiseModelPlugin& model,
                                           const PropertyCheckOptions& options) {
  std::vector<std::string> failures;
  for (double t : options.times_s) {
    for (double dt : options.psd_steps_s) {
      const Step s = step(model, t, dt);
      const std::string at = fmt::format("covariances at t = {} s, dt = {} s", t, dt);
      require_symmetric_psd(s.q_white, options.symmetry_tolerance, at + ": Qw", failures);
      require_symmetric_psd(s.q_bias, options.symmetry_tolerance, at + ": Qb", failures);
      require_symmetric_psd(s.q_d, options.symmetry_tolerance, at + ": Qd", failures);
      if (!(s.q_white.trace() + s.q_bias.trace() + s.q_d.trace() > 0.0)) {
        failures.push_back(at + ": Qw, Qb and Qd are all zero (a model must add noise)");
      }
    }
  }
  const int n = model.augmented_size();
  Eigen::MatrixXd p0 = Eigen::MatrixXd::Zero(n, n);
  model.augmented_initial_covariance(p0);
  require_symmetric_psd(p0, options.symmetry_tolerance, "initial covariance P0", failures);
  return failures;
}

std::vector<std::string> check_zero_step(const NoiseModelPlugin& model,
                                         const PropertyCheckOptions& options) {
  std::vector<std::string> failures;
  for (double t : options.times_s) {
    const Step s = step(model, t, 0.0);
    const std::string at = fmt::format("zero step at t = {} s", t);
    if (largest(s.q_white) != 0.0) failures.push_back(at + ": Qw is not zero");
    if (largest(s.q_bias) != 0.0) failures.push_back(at + ": Qb is not zero");
    if (s.q_d.size() > 0 && largest(s.q_d) != 0.0) failures.push_back(at + ": Qd is not zero");
    if (s.phi.size() > 0 && !s.phi.isIdentity(0.0)) {
      failures.push_back(at + ": Phi is not the identity");
    }
  }
  return failures;
}

std::vector<std::string> check_composition(const NoiseModelPlugin& model,
                                           const PropertyCheckOptions& options) {
  std::vector<std::string> failures;
  const double dt1 = options.dt1_s, dt2 = options.dt2_s, tolerance = options.composition_tolerance;
  for (double t : options.times_s) {
    const Step first = step(model, t, dt1), second = step(model, t + dt1, dt2),
               whole = step(model, t, dt1 + dt2);
    const std::string at = fmt::format("composition at t = {} s of {} s and {} s", t, dt1, dt2);
    require_close(first.q_white + second.q_white, whole.q_white, tolerance, at + ": Qw", failures);
    require_close(first.q_bias + second.q_bias, whole.q_bias, tolerance, at + ": Qb", failures);
    require_close(second.phi * first.phi, whole.phi, tolerance, at + ": Phi", failures);
    require_close(second.phi * first.q_d * second.phi.transpose() + second.q_d, whole.q_d,
                  tolerance, at + ": Qd", failures);
  }
  return failures;
}

std::vector<std::string> check_stationarity(const NoiseModelPlugin& model,
                                            const PropertyCheckOptions& options) {
  const int n = model.augmented_size();
  if (n == 0) return {};
  Eigen::MatrixXd p0 = Eigen::MatrixXd::Zero(n, n), phi(n, n), q_d(n, n);
  model.augmented_initial_covariance(p0);
  Eigen::MatrixXd p = p0;
  const double t0 = options.times_s.front(), dt = options.stationary_step_s;
  for (int k = 0; k < options.stationary_steps; ++k) {
    model.augmented_transition(t0 + k * dt, dt, phi, q_d);
    p = phi * p * phi.transpose() + q_d;
  }
  std::vector<std::string> failures;
  require_close(p, p0, options.stationarity_tolerance,
                fmt::format("stationarity: P after {} steps of {} s from t = {} s and P0",
                            options.stationary_steps, dt, t0),
                failures);
  return failures;
}

std::vector<std::string> check_params_round_trip(const NoiseModelPlugin& model,
                                                 const NoiseModelRebuild& rebuild,
                                                 const PropertyCheckOptions& options) {
  std::vector<std::string> failures;
  const nlohmann::json params = model.params();
  std::shared_ptr<NoiseModelPlugin> rebuilt;
  try {
    rebuilt = rebuild(params);
  } catch (const std::exception& error) {
    failures.push_back("round trip: the factory refuses params() " + params.dump() + ": " +
                       error.what());
    return failures;
  }
  if (rebuilt == nullptr) {
    failures.push_back("round trip: the factory returned no model for params()");
    return failures;
  }
  if (!model.equals(*rebuilt, options.equals_tolerance)) {
    failures.push_back("round trip: the model rebuilt from params() is not equal to it: " +
                       rebuilt->describe());
  }
  if (!rebuilt->equals(model, options.equals_tolerance)) {
    failures.push_back("round trip: equals() is not symmetric");
  }
  if (model.describe().find(model.type()) == std::string::npos) {
    failures.push_back("describe() does not name the type '" + std::string(model.type()) + "'");
  }
  const int n = model.augmented_size();
  if (n > 0) {
    Eigen::MatrixXd map = Eigen::MatrixXd::Zero(3, n);
    model.augmented_sensor_map(map);
    if (!(largest(map) > 0.0)) failures.push_back("sensor map M is zero: the states do nothing");
  }
  return failures;
}

std::vector<std::string> check_noise_model(const NoiseModelPlugin& model,
                                           const NoiseModelRebuild& rebuild,
                                           const PropertyCheckOptions& options) {
  if (const std::string reason = options.invalid_reason(); !reason.empty()) {
    throw std::invalid_argument("check_noise_model: " + reason);
  }
  std::vector<std::string> failures;
  for (auto&& found : {check_covariances(model, options), check_zero_step(model, options),
                       check_composition(model, options), check_stationarity(model, options),
                       check_params_round_trip(model, rebuild, options)}) {
    failures.insert(failures.end(), found.begin(), found.end());
  }
  return failures;
}

}  // namespace stochnav::plugin
