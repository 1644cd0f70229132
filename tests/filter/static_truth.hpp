#pragma once
// A stationary tool with known truth for the filter tests (optionally turning about its own
// axis): exact IMU increments of the Earth rate and gravity, plus sensor errors drawn per seed,
// and test doubles of a white-noise model and a noisy position / zero-velocity aid (the real
// plugins are tested in tests/plugin).

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/ins/nav_state.hpp"
#include "stochnav/ins/strapdown.hpp"
#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav::testing {

inline constexpr double kDeg = 3.14159265358979323846 / 180.0;
inline constexpr double kRateHz = 100.0;  ///< the simulated IMU's rate (Hz)

inline NavState static_truth_state() {
  NavState truth;
  truth.latitude_rad = 39.9778 * kDeg;
  truth.longitude_rad = 116.3448 * kDeg;
  truth.height_m = 50.0;
  truth.q_nb = quaternion_from_mwd(
      {.inclination_rad = 60.0 * kDeg, .toolface_rad = 30.0 * kDeg, .azimuth_rad = 100.0 * kDeg});
  return truth;
}

/// Sensor errors of one simulated IMU (SI units, body axes).
struct StaticImuErrors {
  double gyro_arw = 0.0;                                 ///< rad/sqrt(s)
  double accel_vrw = 0.0;                                ///< m/s/sqrt(s)
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   ///< rad/s
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  ///< m/s^2
};

/// Exact increments of the stationary truth plus white noise and constant biases. With
/// `spin_radps` the tool turns about its own axis (body z) at that rate from the truth's
/// attitude at t = 0, C_nb(t) = C_nb(0) Rz(spin t), as a rotating drill string: the increments
/// are the integrals of the body rate and specific force over each epoch (the Earth rate's
/// coning, of order spin |w_ie| dt^2, left out).
class StaticImu {
 public:
  StaticImu(const NavState& truth, const StaticImuErrors& errors, double rate_hz,
            std::uint64_t seed, double spin_radps = 0.0)
      : errors_(errors), dt_(1.0 / rate_hz), spin_radps_(spin_radps), engine_(seed) {
    const Eigen::Matrix3d c_bn = truth.q_nb.toRotationMatrix().transpose();
    omega_ib_b_ = c_bn * earth_rate_n(truth.latitude_rad);
    f_ib_b_ = -(c_bn * gravity_n(truth.latitude_rad, truth.height_m));
  }

  ImuIncrement next() {
    ++epoch_;
    ImuIncrement increment;
    increment.t_s = static_cast<double>(epoch_) * dt_;
    increment.dt_s = dt_;
    const double sd_theta = errors_.gyro_arw * std::sqrt(dt_);
    const double sd_v = errors_.accel_vrw * std::sqrt(dt_);
    const Eigen::Vector3d delta_theta =
        integral_in_body(omega_ib_b_, errors_.gyro_bias, increment.t_s);
    const Eigen::Vector3d delta_v = integral_in_body(f_ib_b_, errors_.accel_bias, increment.t_s);
    for (int i = 0; i < 3; ++i) {
      increment.delta_theta_b(i) = delta_theta(i) + sd_theta * normal_(engine_);
      increment.delta_v_b(i) = delta_v(i) + sd_v * normal_(engine_);
    }
    increment.delta_theta_b.z() += spin_radps_ * dt_;  // exactly 0 for a still tool
    return increment;
  }

 private:
  // The integral over the epoch ending at t of a vector fixed in the navigation frame, read in
  // the turning body axes (`at_start_b`: its body components at t = 0, Rz(-spin t) at_start_b
  // at t), plus a constant body-axis `bias`.
  Eigen::Vector3d integral_in_body(const Eigen::Vector3d& at_start_b, const Eigen::Vector3d& bias,
                                   double t) const {
    if (spin_radps_ == 0.0) return (at_start_b + bias) * dt_;
    const double w = spin_radps_;
    const double t0 = t - dt_;
    const double cos_integral = (std::sin(w * t) - std::sin(w * t0)) / w;
    const double sin_integral = (std::cos(w * t0) - std::cos(w * t)) / w;
    const Eigen::Vector3d turning{cos_integral * at_start_b.x() + sin_integral * at_start_b.y(),
                                  -sin_integral * at_start_b.x() + cos_integral * at_start_b.y(),
                                  at_start_b.z() * dt_};
    return turning + bias * dt_;
  }

  StaticImuErrors errors_;
  double dt_;
  double spin_radps_;
  std::mt19937_64 engine_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  Eigen::Vector3d omega_ib_b_, f_ib_b_;
  std::uint64_t epoch_ = 0;
};

/// Constant white noise (angle / velocity random walk N per axis), no bias walk.
class TestWhiteNoise final : public plugin::NoiseModelPlugin {
 public:
  TestWhiteNoise(plugin::SensorGroup group, double n) : NoiseModelPlugin(group), n_(n) {}
  std::string_view type() const override { return "test_white"; }
  void white_noise_covariance(double, double dt_s, Eigen::Ref<Eigen::MatrixXd> q) const override {
    q.setZero();
    q.diagonal().setConstant(n_ * n_ * dt_s);
  }
  nlohmann::json params() const override { return {{"N", n_}}; }
  std::string describe() const override { return "test_white"; }
  bool equals(const NoiseModelPlugin& other, double) const override { return &other == this; }

 private:
  double n_;
};

/// The noise-free measurement of a tool at rest at `site`: z = (the ENU position offset of
/// `state` from the site (m), its velocity (m/s)), H on the core position and velocity states,
/// R = diag(sigma_position^2 x 3, sigma_velocity^2 x 3).
inline void static_measurement(const NavState& site, const NavState& state,
                               double sigma_position_m, double sigma_velocity_mps,
                               Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::MatrixXd> h,
                               Eigen::Ref<Eigen::MatrixXd> r) {
  const EarthRadii radii = earth_radii(site.latitude_rad);
  z(0) = (state.longitude_rad - site.longitude_rad) * (radii.transverse_m + site.height_m) *
         std::cos(site.latitude_rad);
  z(1) = (state.latitude_rad - site.latitude_rad) * (radii.meridian_m + site.height_m);
  z(2) = state.height_m - site.height_m;
  z.segment<3>(3) = state.v_n;
  h.setZero();
  h.block<3, 3>(0, plugin::core_state::kPosition).setIdentity();
  h.block<3, 3>(3, plugin::core_state::kVelocity).setIdentity();
  r.setZero();
  r.diagonal().head<3>().setConstant(sigma_position_m * sigma_position_m);
  r.diagonal().tail<3>().setConstant(sigma_velocity_mps * sigma_velocity_mps);
}

/// Position (ENU, against the site) and zero velocity at 1 Hz, with measurement noise drawn
/// from exactly the R it reports, so that a consistent filter sees what it assumes.
class NoisyStaticAid final : public plugin::AidPlugin {
 public:
  NoisyStaticAid(const NavState& site, double sigma_position_m, double sigma_velocity_mps,
                 std::uint64_t seed, plugin::NisGate gate = plugin::NisGate{.enabled = false})
      : AidPlugin(gate),
        site_(site),
        sigma_position_m_(sigma_position_m),
        sigma_velocity_mps_(sigma_velocity_mps),
        engine_(seed) {}
  std::string_view type() const override { return "noisy_static"; }
  int measurement_size() const override { return 6; }
  bool has_measurement(double t_s) const override {
    return std::abs(t_s - std::round(t_s)) < 1e-6 && t_s > 0.5;
  }
  bool measure(double, const NavState& state, const plugin::ImuSample&,
               Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    static_measurement(site_, state, sigma_position_m_, sigma_velocity_mps_, z, h, r);
    for (int i = 0; i < 6; ++i) {
      z(i) -= (i < 3 ? sigma_position_m_ : sigma_velocity_mps_) * normal_(engine_);
    }
    return true;
  }
  std::string describe() const override { return "noisy_static"; }

 private:
  NavState site_;
  double sigma_position_m_, sigma_velocity_mps_;
  mutable std::mt19937_64 engine_;
  mutable std::normal_distribution<double> normal_{0.0, 1.0};
};

/// Position and velocity fixes of a static tool (as NoisyStaticAid, sigmas 0.05 m and 0.002 m/s)
/// whose noise is a function of the epoch's whole second alone: two aids, or one aid asked
/// twice, give the same measurement at the same epoch.
inline void time_seeded_static_measurement(const NavState& site, const NavState& state,
                                           double t_s, Eigen::Ref<Eigen::VectorXd> z,
                                           Eigen::Ref<Eigen::MatrixXd> h,
                                           Eigen::Ref<Eigen::MatrixXd> r) {
  constexpr double kPositionSigma = 0.05;   // m
  constexpr double kVelocitySigma = 0.002;  // m/s
  static_measurement(site, state, kPositionSigma, kVelocitySigma, z, h, r);
  std::mt19937_64 engine(static_cast<std::uint64_t>(std::llround(t_s)));
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int i = 0; i < 6; ++i) z(i) -= (i < 3 ? kPositionSigma : kVelocitySigma) * normal(engine);
}

/// An aid of time_seeded_static_measurement at every whole second after 0.5 s (gate: `gate`).
class TimeSeededStaticAid final : public plugin::AidPlugin {
 public:
  explicit TimeSeededStaticAid(const NavState& site,
                               plugin::NisGate gate = plugin::NisGate{.enabled = false})
      : AidPlugin(gate), site_(site) {}
  std::string_view type() const override { return "time_seeded_static"; }
  int measurement_size() const override { return 6; }
  bool has_measurement(double t_s) const override {
    return std::abs(t_s - std::round(t_s)) < 1e-6 && t_s > 0.5;
  }
  bool measure(double t_s, const NavState& state, const plugin::ImuSample&,
               Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    time_seeded_static_measurement(site_, state, t_s, z, h, r);
    return true;
  }
  std::string describe() const override { return "time_seeded_static"; }

 private:
  NavState site_;
};

/// Estimate - truth as the filter's 15 core error states (see filter/error_dynamics.hpp).
inline Eigen::Matrix<double, 15, 1> core_error(const NavState& estimate, const NavState& truth,
                                               const Eigen::Vector3d& accel_bias_estimate,
                                               const Eigen::Vector3d& gyro_bias_estimate,
                                               const StaticImuErrors& errors) {
  Eigen::Matrix<double, 15, 1> dx;
  const EarthRadii radii = earth_radii(truth.latitude_rad);
  dx(0) = (estimate.longitude_rad - truth.longitude_rad) * (radii.transverse_m + truth.height_m) *
          std::cos(truth.latitude_rad);
  dx(1) = (estimate.latitude_rad - truth.latitude_rad) * (radii.meridian_m + truth.height_m);
  dx(2) = estimate.height_m - truth.height_m;
  dx.segment<3>(3) = estimate.v_n - truth.v_n;
  // C_est = (I - [phi x]) C_true: C_true C_est^T = Rot(phi).
  const Eigen::AngleAxisd rotation(truth.q_nb * estimate.q_nb.conjugate());
  dx.segment<3>(6) = rotation.angle() * rotation.axis();
  dx.segment<3>(9) = accel_bias_estimate - errors.accel_bias;
  dx.segment<3>(12) = gyro_bias_estimate - errors.gyro_bias;
  return dx;
}

/// An interval aid (plugin::InsInterval) that measures every `period` epochs (at kRateHz) from
/// `phase`, records the interval it is given and makes no update, so that the navigator's
/// state, and with it every interval, is a function of the IMU record alone.
class IntervalRecorder final : public plugin::AidPlugin {
 public:
  IntervalRecorder(int period, int phase)
      : AidPlugin(plugin::NisGate{.enabled = false}), period_(period), phase_(phase) {}
  std::string_view type() const override { return "interval_recorder"; }
  int measurement_size() const override { return 1; }
  bool has_measurement(double t_s) const override {
    const auto epoch = static_cast<long>(std::lround(t_s * kRateHz));
    return epoch >= phase_ && (epoch - phase_) % period_ == 0;
  }
  bool measure(double, const NavState&, const plugin::ImuSample& imu, Eigen::Ref<Eigen::VectorXd>,
               Eigen::Ref<Eigen::MatrixXd>, Eigen::Ref<Eigen::MatrixXd>) const override {
    intervals.push_back(imu.interval);
    return false;
  }
  bool measures_interval_mean() const override { return true; }
  std::string describe() const override { return "interval_recorder"; }

  mutable std::vector<plugin::InsInterval> intervals;

 private:
  int period_, phase_;
};

}  // namespace stochnav::testing
