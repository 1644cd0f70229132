#pragma once
// Noise-model plugins: the stochastic model of one sensor group's errors, as a Kalman filter
// needs it. Plugin API (plugin_api.hpp); one instance per sensor group per filter.
//
// Error model of one sensor group (3 axes, body frame b, SI units: gyro rad/s, accel m/s^2):
//   e(t) = w(t) + b(t) + M x_aug(t)
//   w      white noise (may be time-varying): what white_noise_covariance integrates;
//   b      the filter's core bias block of the group (3 states, b_g or b_a), a random walk
//          driven by bias_walk_covariance (zero when the model has no rate random walk);
//   x_aug  n_aug augmented states owned by the model, propagated exactly over a step by
//          x_aug(t + dt) = Phi x_aug(t) + u, u ~ N(0, Qd), started from N(0, P0);
//   M      the 3 x n_aug map from the augmented states to the sensor error (augmented_sensor_map).
// The filter integrates e into its navigation errors; the model only describes e.
//
// Call pattern of the filter (per propagation step [t, t + dt], dt >= 0, in s):
//   white_noise_covariance(t, dt, Qw)          3 x 3
//   bias_walk_covariance(t, dt, Qb)            3 x 3
//   augmented_transition(t, dt, Phi, Qd)       n_aug x n_aug each   (only when n_aug > 0)
// and once, at initialisation: augmented_initial_covariance(P0), augmented_sensor_map(M).
// Outputs are written into caller-owned matrices of exactly the stated size (the caller sizes
// them; the plugin never resizes) and every output entry is written. These calls are const, do
// not allocate and do not throw; dt == 0 gives Qw = Qb = Qd = 0 and Phi = I. Each Q returned is
// symmetric positive semi-definite, and over consecutive steps they compose:
//   Phi(t + dt1, dt2) Qd(t, dt1) Phi(t + dt1, dt2)^T + Qd(t + dt1, dt2) = Qd(t, dt1 + dt2),
//   Qw(t, dt1) + Qw(t + dt1, dt2) = Qw(t, dt1 + dt2)   (same for Qb).
//
// Threads: an instance belongs to one filter and is called from one thread at a time; build one
// instance per filter (compare builds one per variant and seed).
//
// Matrices cross the library boundary as dynamic-size Eigen types (Eigen::Ref<MatrixXd> binds
// fixed-size caller matrices such as Matrix3d too, without copies).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "stochnav/core/units.hpp"
#include "stochnav/model/reporting_units.hpp"
#include "stochnav/plugin/plugin_api.hpp"

namespace stochnav::plugin {

/// The sensor triads a noise model can describe.
enum class SensorGroup {
  kGyro,   ///< "gyro": angular rate omega_ib_b, rad/s
  kAccel,  ///< "accel": specific force f_ib_b, m/s^2
};

/// "gyro" or "accel".
std::string_view sensor_group_name(SensorGroup group);
/// Inverse of sensor_group_name; nullopt otherwise.
std::optional<SensorGroup> parse_sensor_group(std::string_view name);
/// kAngularRate (gyro) or kSpecificForce (accel): fixes the reporting units of params
/// (model/reporting_units.hpp), e.g. N in deg/sqrt(h) for gyros, m/s/sqrt(h) for accelerometers.
Quantity sensor_quantity(SensorGroup group);

/// A static calibration record of one sensor group: three axes sampled together, SI units.
struct CalibrationRecord {
  SensorGroup group = SensorGroup::kGyro;
  double rate_hz = 0.0;       ///< sampling rate (Hz), > 0
  double start_time_s = 0.0;  ///< time of the first sample (s)
  /// Rate samples per body axis x, y, z (rad/s or m/s^2), equal lengths.
  std::array<std::vector<double>, 3> axes;
  std::string source;  ///< file (and columns) the record came from, for messages
};

/// What a factory gets besides its params.
struct NoiseModelContext {
  SensorGroup group = SensorGroup::kGyro;
  double imu_rate_hz = 0.0;  ///< nominal IMU rate (Hz); 0 when unknown
  /// JSON pointer of the params object in its document (e.g. "/noise/gyro/params"): prefix of
  /// every error message about params.
  std::string params_pointer;
  std::filesystem::path config_dir;    ///< folder of the config file: relative paths start here
  std::filesystem::path scenario_dir;  ///< simulated scenario folder of the run; empty otherwise
};

/// Where the runtime put the model's blocks in the filter's error state (state_layout.hpp).
struct StatePlacement {
  int bias_offset = -1;       ///< first index of the group's core bias block (3 states)
  int augmented_offset = -1;  ///< first index of the augmented block; -1 when n_aug == 0
  int state_size = 0;         ///< size n of the whole error state
};

/// What the filter reports after each measurement update (for adaptive models, e.g. Sage-Husa).
/// Views into filter storage, valid during the call only. n = StatePlacement::state_size.
struct UpdateFeedback {
  double t_s;                                    ///< time of the update (s)
  std::string_view aid_type;                     ///< the aid plugin's type
  bool accepted;                                 ///< passed the NIS gate and was applied
  double nis;                                    ///< normalised innovation squared z^T S^-1 z
  Eigen::Ref<const Eigen::VectorXd> innovation;  ///< z, m (aid units)
  Eigen::Ref<const Eigen::MatrixXd> innovation_covariance;  ///< S = H P H^T + R, m x m
  Eigen::Ref<const Eigen::MatrixXd> gain;                   ///< K, n x m (zero if rejected)
  Eigen::Ref<const Eigen::MatrixXd> covariance_prior;       ///< P before the update, n x n
  Eigen::Ref<const Eigen::MatrixXd> covariance_posterior;   ///< P after the update, n x n
};

class NoiseModelPlugin {
 public:
  virtual ~NoiseModelPlugin();
  NoiseModelPlugin(const NoiseModelPlugin&) = delete;
  NoiseModelPlugin& operator=(const NoiseModelPlugin&) = delete;

  /// The plugin type (PluginInfo::type), e.g. "white".
  virtual std::string_view type() const = 0;
  SensorGroup group() const { return group_; }

  /// n_aug >= 0, constant over the model's life.
  virtual int augmented_size() const { return 0; }

  /// False when every output depends on dt only (not on t or update feedback): the filter may
  /// then compute them once per distinct dt.
  virtual bool time_varying() const { return false; }

  /// Covariance of the integrated white sensor error over [t, t + dt]: E[(int w)(int w)^T],
  /// 3 x 3, rad^2 (gyro) or (m/s)^2 (accel). For constant white noise of PSD N^2 (N the angle
  /// random walk, rad/sqrt(s)): N^2 dt per axis.
  virtual void white_noise_covariance(double t_s, double dt_s,
                                      Eigen::Ref<Eigen::MatrixXd> q_white) const = 0;

  /// Discrete random-walk covariance of the core bias block over [t, t + dt], 3 x 3,
  /// (rad/s)^2 or (m/s^2)^2: K^2 dt per axis for rate random walk K. Default: zero.
  virtual void bias_walk_covariance(double t_s, double dt_s,
                                    Eigen::Ref<Eigen::MatrixXd> q_bias) const;

  /// Exact discrete transition Phi and noise Qd of the augmented states over [t, t + dt],
  /// n_aug x n_aug each. Default (n_aug == 0): nothing to write.
  virtual void augmented_transition(double t_s, double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                                    Eigen::Ref<Eigen::MatrixXd> q_d) const;

  /// Initial covariance of the augmented states, n_aug x n_aug (their stationary covariance
  /// for stationary processes). Default: nothing to write.
  virtual void augmented_initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const;

  /// M, 3 x n_aug: sensor error (rad/s or m/s^2, body axes) = M x_aug. Default: nothing.
  virtual void augmented_sensor_map(Eigen::Ref<Eigen::MatrixXd> map) const;

  /// Feedback after each measurement update; adaptive models adjust their Q here. Called
  /// between propagation steps, never concurrently with them. Default: no-op.
  virtual void on_update(const UpdateFeedback& feedback);

  /// Params that rebuild an equal model through the plugin's factory (a fitted model written
  /// out for reuse), in the reporting units of the params.
  virtual nlohmann::json params() const = 0;

  /// A few lines in reporting units, e.g. "gauss_markov (gyro): x: sigma = 0.1 deg/h, ...".
  virtual std::string describe() const = 0;

  /// Same type and group and parameters within rel_tol (|a - b| <= rel_tol max(|a|, |b|)).
  virtual bool equals(const NoiseModelPlugin& other, double rel_tol = 1e-9) const = 0;

  /// How well a fitter's model fits its calibration record, set by the fitter (null for a model
  /// built from params, and for fitters that cannot say). Fitters using fit_calibration_axes
  /// set calibration_fit_quality(fits) (plugin/calibration_fit.hpp): per axis
  /// {"chi_square", "dof", "chi_square_per_dof", "p_value", "at_bound": ["term.param", ...]}.
  const nlohmann::json& fit_quality() const { return fit_quality_; }
  void set_fit_quality(nlohmann::json quality) { fit_quality_ = std::move(quality); }

  /// Set by the runtime (state_layout.hpp) before the first propagation step.
  const StatePlacement& placement() const { return placement_; }
  void set_placement(const StatePlacement& placement) { placement_ = placement; }

 protected:
  explicit NoiseModelPlugin(SensorGroup group) : group_(group) {}

  /// A parameter in natural SI units converted to this group's reporting units (params(),
  /// describe()), e.g. rad/sqrt(s) -> deg/sqrt(h) for a gyro's angle random walk.
  double reported(ParameterDimension dimension, double natural) const;
  /// The name of this group's reporting unit of `dimension`, e.g. "deg/sqrt(h)".
  std::string reported_unit(ParameterDimension dimension) const;

 private:
  SensorGroup group_;
  StatePlacement placement_;
  nlohmann::json fit_quality_;  ///< null unless a fitter set it
};

/// The tolerance rule of NoiseModelPlugin::equals for one parameter:
/// |a - b| <= rel_tol max(|a|, |b|).
inline bool parameters_close(double a, double b, double rel_tol) {
  return std::abs(a - b) <= rel_tol * std::max(std::abs(a), std::abs(b));
}

/// Builds a model from its params. Throws ConfigError naming context.params_pointer (+ the key)
/// when params are invalid. Exported by STOCHNAV_NOISE_PLUGIN as stochnav_noise_factory.
using NoiseModelFactory = std::unique_ptr<NoiseModelPlugin>(const nlohmann::json& params,
                                                            const NoiseModelContext& context);

/// Fits a model to a calibration record; params hold fit options (and fixed parameters) as the
/// plugin documents them. Throws ConfigError (bad params) or InputError (record unusable).
using NoiseModelFitter = std::unique_ptr<NoiseModelPlugin>(const CalibrationRecord& record,
                                                           const nlohmann::json& params,
                                                           const NoiseModelContext& context);

/// The FITTER of plugins that cannot fit their model from data: throws ConfigError.
std::unique_ptr<NoiseModelPlugin> fit_not_supported(const CalibrationRecord& record,
                                                    const nlohmann::json& params,
                                                    const NoiseModelContext& context);

}  // namespace stochnav::plugin

/// Registers a noise-model plugin; use once, at global scope, in the plugin library. TYPE and
/// DESCRIPTION are string literals; FACTORY a NoiseModelFactory, FITTER a NoiseModelFitter or
/// ::stochnav::plugin::fit_not_supported.
#define STOCHNAV_NOISE_PLUGIN(TYPE, DESCRIPTION, FACTORY, FITTER)                           \
  static_assert(std::is_same_v<decltype(&FACTORY), ::stochnav::plugin::NoiseModelFactory*>, \
                "STOCHNAV_NOISE_PLUGIN: FACTORY must be a NoiseModelFactory");              \
  static_assert(std::is_same_v<decltype(&FITTER), ::stochnav::plugin::NoiseModelFitter*>,   \
                "STOCHNAV_NOISE_PLUGIN: FITTER must be a NoiseModelFitter");                \
  STOCHNAV_PLUGIN_INFO_(::stochnav::plugin::PluginKind::kNoiseModel, TYPE, DESCRIPTION)     \
  BOOST_DLL_ALIAS(FACTORY, stochnav_noise_factory)                                          \
  BOOST_DLL_ALIAS(FITTER, stochnav_noise_fitter)
