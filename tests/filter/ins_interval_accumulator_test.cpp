// The mean-velocity error map of an aid interval (filter/ins_interval_accumulator.hpp) against
// two strapdown INS runs over the same 1-s interval of a tool spinning at 60 rpm about a
// horizontal axis: one with exact sensors, one with a sensor error. The difference of their
// mean velocities must equal the map applied to the error state at the interval's end.
#include "stochnav/filter/ins_interval_accumulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "stochnav/filter/velocity_oscillation.hpp"
#include "stochnav/ins/strapdown.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav {
namespace {

namespace cs = plugin::core_state;

constexpr double kSpinRate_radps = 2.0 * std::numbers::pi;  // 60 rpm about body z
constexpr double kRate_hz = 100.0;
constexpr int kGyroScale = 15;  // the layout of the scale-factor states in this test
constexpr int kAccelScale = 18;

// Body axes in ENU: x north, y up, z east (the tool axis horizontal), then the spin.
Eigen::Matrix3d attitude_at(double t_s) {
  Eigen::Matrix3d c0;
  c0 << 0, 0, 1,  //
      1, 0, 0,    //
      0, 1, 0;
  return c0 * Eigen::AngleAxisd(kSpinRate_radps * t_s, Eigen::Vector3d::UnitZ()).matrix();
}

// Exact increments of the spinning tool at rest (specific force g up), by fine quadrature.
ImuIncrement ideal_increment(int epoch) {
  const double dt = 1.0 / kRate_hz;
  ImuIncrement increment{.t_s = (epoch + 1) * dt, .dt_s = dt};
  increment.delta_theta_b = Eigen::Vector3d(0.0, 0.0, kSpinRate_radps * dt);
  constexpr int kSubsteps = 64;
  const Eigen::Vector3d f_n(0.0, 0.0, 9.80);
  for (int i = 0; i < kSubsteps; ++i) {
    const double t = epoch * dt + (i + 0.5) * dt / kSubsteps;
    increment.delta_v_b += attitude_at(t).transpose() * f_n * (dt / kSubsteps);
  }
  return increment;
}

struct SensorError {
  Eigen::Vector3d gyro_scale = Eigen::Vector3d::Zero();  // the sensor reads (1 + s) truth
  Eigen::Vector3d accel_scale = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias_mps2 = Eigen::Vector3d::Zero();
  double gyro_white_radps_per_sqrt_hz = 0.0;  // angle random walk (rad/sqrt(s))
  double accel_white_mps2_per_sqrt_hz = 0.0;  // velocity random walk (m/s/sqrt(s))
  std::mt19937_64* random = nullptr;          // for the white noise
};

Eigen::Vector3d vee_of_skew(const Eigen::Matrix3d& m) {
  return 0.5 * Eigen::Vector3d(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
}

struct Comparison {
  Eigen::Vector3d actual;            // mean velocity (erring INS) - mean velocity (exact INS), m/s
  Eigen::Vector3d predicted;         // the map times the error state at the interval's end
  Eigen::Matrix3d noise_covariance;  // of actual - predicted, from the in-interval noise
  Eigen::Vector3d predicted_core_only;
};

Comparison compare_over_one_second(const SensorError& error) {
  NavState start;
  start.latitude_rad = 0.8;
  start.height_m = 100.0;
  start.q_nb = Eigen::Quaterniond(attitude_at(0.0));
  StrapdownIntegrator exact(start);
  StrapdownIntegrator erring(start);
  InsIntervalAccumulator interval;
  Eigen::Vector3d exact_sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d erring_sum = Eigen::Vector3d::Zero();
  const double dt = 1.0 / kRate_hz;
  std::normal_distribution<double> normal;
  const auto white = [&](double density) -> Eigen::Vector3d {
    if (!(density > 0.0)) return Eigen::Vector3d::Zero();
    const double x = normal(*error.random);
    const double y = normal(*error.random);
    const double z = normal(*error.random);
    return (density * std::sqrt(dt)) * Eigen::Vector3d(x, y, z);
  };
  const Eigen::Matrix3d attitude_noise =
      Eigen::Matrix3d::Identity() *
      (error.gyro_white_radps_per_sqrt_hz * error.gyro_white_radps_per_sqrt_hz * dt);
  const Eigen::Matrix3d velocity_noise =
      Eigen::Matrix3d::Identity() *
      (error.accel_white_mps2_per_sqrt_hz * error.accel_white_mps2_per_sqrt_hz * dt);
  for (int epoch = 0; epoch < static_cast<int>(kRate_hz); ++epoch) {
    const ImuIncrement ideal = ideal_increment(epoch);
    ImuIncrement read = ideal;
    read.delta_theta_b = ((1.0 + error.gyro_scale.array()) * ideal.delta_theta_b.array()).matrix() +
                         error.gyro_bias_radps * dt + white(error.gyro_white_radps_per_sqrt_hz);
    read.delta_v_b = ((1.0 + error.accel_scale.array()) * ideal.delta_v_b.array()).matrix() +
                     error.accel_bias_mps2 * dt + white(error.accel_white_mps2_per_sqrt_hz);
    const Eigen::Vector3d exact_v0 = exact.state().v_n;
    const Eigen::Vector3d erring_v0 = erring.state().v_n;
    const Eigen::Matrix3d c_start = exact.state().q_nb.toRotationMatrix();
    exact.update(ideal);
    erring.update(read);
    interval.add_epoch({.v_start_n = exact_v0,
                        .v_end_n = exact.state().v_n,
                        .c_nb_mean = epoch_mean_attitude(c_start, ideal.delta_theta_b),
                        .delta_v_n = exact.specific_force_increment_n(),
                        .scale_factor_delta_v_b = ideal.delta_v_b,
                        .delta_theta_b = ideal.delta_theta_b,
                        .velocity_noise = velocity_noise,
                        .attitude_noise = attitude_noise,
                        .dt_s = dt});
    exact_sum += 0.5 * dt * (exact_v0 + exact.state().v_n);
    erring_sum += 0.5 * dt * (erring_v0 + erring.state().v_n);
  }
  // The error state (estimate - truth) of the erring INS, which compensates nothing: its
  // estimates of the sensor errors are zero, so their errors are minus the true ones.
  Eigen::VectorXd dx = Eigen::VectorXd::Zero(21);
  dx.segment<3>(cs::kVelocity) = erring.state().v_n - exact.state().v_n;
  // C_est = (I - [phi x]) C_true.
  const Eigen::Matrix3d c_true = exact.state().q_nb.toRotationMatrix();
  const Eigen::Matrix3d c_est = erring.state().q_nb.toRotationMatrix();
  dx.segment<3>(cs::kAttitude) = -vee_of_skew(c_est * c_true.transpose());
  dx.segment<3>(cs::kAccelBias) = -error.accel_bias_mps2;
  dx.segment<3>(cs::kGyroBias) = -error.gyro_bias_radps;
  dx.segment<3>(kGyroScale) = -error.gyro_scale;
  dx.segment<3>(kAccelScale) = -error.accel_scale;

  IntervalMapLayout layout{
      .width = 21, .gyro_scale_offset = kGyroScale, .accel_scale_offset = kAccelScale};
  Eigen::MatrixXd map(3, 21);
  interval.mean_error_map(layout, map);
  Comparison comparison;
  comparison.actual = erring_sum - exact_sum;
  comparison.predicted = map * dx;
  comparison.predicted_core_only = map.leftCols<15>() * dx.head<15>();
  comparison.noise_covariance = interval.interval().mean_velocity_noise_covariance;
  return comparison;
}

void expect_map_explains(const Comparison& c, double relative_tolerance) {
  SCOPED_TRACE(::testing::Message()
               << "actual " << c.actual.transpose() << " predicted " << c.predicted.transpose());
  EXPECT_LT((c.predicted - c.actual).norm(), relative_tolerance * c.actual.norm());
}

TEST(InsIntervalMap, GyroScaleFactorOfASpinningHorizontalTool) {
  SensorError error;
  error.gyro_scale.z() = 1e-4;  // 100 ppm on the spin axis
  const Comparison c = compare_over_one_second(error);
  // About g T^2 / 6 * 2 pi 1e-4 = 1e-3 m/s: as large as a lateral velocity constraint.
  EXPECT_GT(c.actual.norm(), 5e-4);
  expect_map_explains(c, 0.02);
  // The 15-state map alone (what aids had before) misses most of it.
  EXPECT_GT((c.predicted_core_only - c.actual).norm(), 0.5 * c.actual.norm());
}

// The term that made the 36-h drilling run inconsistent in position: across a horizontal spin
// axis the cross-axis scale factors rectify gravity into a steady specific-force error whose
// mean over the interval the 15 core columns cannot express.
TEST(InsIntervalMap, AccelerometerScaleFactors) {
  SensorError error;
  error.accel_scale = Eigen::Vector3d(2e-4, -1e-4, 3e-4);
  const Comparison c = compare_over_one_second(error);
  expect_map_explains(c, 0.02);
  EXPECT_GT((c.predicted_core_only - c.actual).norm(), 0.3 * c.actual.norm());
}

TEST(InsIntervalMap, GyroBiasAcrossTheSpinAxis) {
  SensorError error;
  error.gyro_bias_radps = Eigen::Vector3d(2e-4, -1e-4, 0.0);  // about 40 deg/h
  expect_map_explains(compare_over_one_second(error), 0.02);
}

TEST(InsIntervalMap, AccelerometerBias) {
  SensorError error;
  error.accel_bias_mps2 = Eigen::Vector3d(1e-3, 2e-3, -1e-3);
  expect_map_explains(compare_over_one_second(error), 0.02);
}

// The white noise inside the interval: the sample covariance of what the map does not explain,
// over 400 realisations, against the accumulated covariance. Gyro noise of 1e-3 rad/sqrt(s)
// (what a model reading the drill string's rotation as noise may use) moves the mean by
// g / sqrt(3) 1e-3 = 5.7e-3 m/s across the tool: more than the accelerometer noise here.
TEST(InsIntervalMap, InIntervalWhiteNoiseCovariance) {
  std::mt19937_64 random(20261124);
  SensorError error;
  error.gyro_white_radps_per_sqrt_hz = 1e-3;
  error.accel_white_mps2_per_sqrt_hz = 2e-3;
  error.random = &random;
  constexpr int kRealisations = 400;
  Eigen::Matrix3d sample = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d predicted = Eigen::Matrix3d::Zero();
  for (int i = 0; i < kRealisations; ++i) {
    const Comparison c = compare_over_one_second(error);
    const Eigen::Vector3d unexplained = c.actual - c.predicted;
    sample += unexplained * unexplained.transpose() / kRealisations;
    predicted = c.noise_covariance;
  }
  // A variance estimated from 400 samples has a relative sigma of sqrt(2 / 400) = 7 %.
  for (int axis = 0; axis < 3; ++axis) {
    SCOPED_TRACE(axis);
    EXPECT_NEAR(sample(axis, axis) / predicted(axis, axis), 1.0, 0.22);
  }
}

// Under vibration (filter/velocity_oscillation.hpp) the velocities given are the INS's less the
// counted share of its high-pass, which takes that share of the velocity noise's high-pass out
// of the mean: the mean's noise covariance adds share^2 q high_passed_noise_variance(T), q the
// accelerometer noise's rate over the interval; without a share nothing changes.
TEST(InsIntervalMap, VibrationAddsTheHighPassedNoiseItTakesOut) {
  const double rate = 1e-6;  // (m/s)^2 per s
  const double dt = 0.01;
  InsIntervalAccumulator still, vibrating, half;
  for (int k = 0; k < 100; ++k) {
    InsIntervalAccumulator::Epoch epoch{.v_start_n = Eigen::Vector3d::Zero(),
                                        .v_end_n = Eigen::Vector3d::Zero(),
                                        .c_nb_mean = Eigen::Matrix3d::Identity(),
                                        .delta_v_n = Eigen::Vector3d(0.0, 0.0, 9.8 * dt),
                                        .scale_factor_delta_v_b = Eigen::Vector3d::Zero(),
                                        .delta_theta_b = Eigen::Vector3d::Zero(),
                                        .velocity_noise = rate * dt * Eigen::Matrix3d::Identity(),
                                        .attitude_noise = Eigen::Matrix3d::Zero(),
                                        .dt_s = dt};
    still.add_epoch(epoch);
    epoch.oscillation_share = 1.0;
    vibrating.add_epoch(epoch);
    epoch.oscillation_share = 0.5;
    half.add_epoch(epoch);
  }
  const Eigen::Matrix3d base = still.interval().mean_velocity_noise_covariance;
  const double added = rate * VelocityOscillation::high_passed_noise_variance(1.0);
  EXPECT_TRUE((vibrating.interval().mean_velocity_noise_covariance - base)
                  .isApprox(added * Eigen::Matrix3d::Identity(), 1e-9));
  EXPECT_TRUE((half.interval().mean_velocity_noise_covariance - base)
                  .isApprox(0.25 * added * Eigen::Matrix3d::Identity(), 1e-9));
  EXPECT_GT(added, 0.3 * base(0, 0)) << "comparable to the in-interval noise (0.43 of it)";
}

}  // namespace
}  // namespace stochnav
