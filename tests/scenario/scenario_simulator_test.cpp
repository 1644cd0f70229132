#include "stochnav/scenario/scenario_simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scenario_builders.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/scenario/vibration.hpp"

namespace stochnav {
namespace {

using testing::kDeg;

constexpr double kDegPerHour = kDeg / 3600.0;

ScenarioConfig noisy_static_table(double duration_s) {
  ScenarioConfig config = testing::table_config({63.0 * kDeg, 141.0 * kDeg, 287.0 * kDeg},
                                                {testing::static_phase(duration_s)});
  for (auto& m : config.gyro.noise) {
    m.terms = {AngleRandomWalkTerm{0.01 * kDeg / 60.0}, BiasInstabilityTerm{0.05 * kDegPerHour}};
  }
  for (auto& m : config.accel.noise) m.terms = {AngleRandomWalkTerm{1e-4}};
  return config;
}

TEST(ScenarioSimulator, StationaryMeansAreEarthRateAndGravityInTheToolFrame) {
  const ScenarioConfig config = noisy_static_table(600.0);
  const Eigen::Matrix3d C_bn = dcm_from_mwd(config.vibration_table->attitude).transpose();
  const double lat = config.site.latitude_rad;
  const Eigen::Vector3d omega_expected = C_bn * earth_rate_n(lat);
  const Eigen::Vector3d f_expected = -(C_bn * gravity_n(lat, config.site.height_m));

  // Noise-free: every increment is exact.
  ScenarioSimulator ideal(config, 5, false);
  ScenarioEpoch epoch;
  for (int k = 0; k < 1000; ++k) {
    ideal.next(epoch);
    EXPECT_LT((epoch.ideal.delta_theta_b / 0.01 - omega_expected).norm(),
              1e-12 * omega_expected.norm());
    EXPECT_LT((epoch.ideal.delta_v_b / 0.01 - f_expected).norm(), 1e-12 * f_expected.norm());
  }

  // With noise: the record means agree within their standard errors.
  ScenarioSimulator noisy(config, 5, true);
  Eigen::Vector3d omega_sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d f_sum = Eigen::Vector3d::Zero();
  while (noisy.epochs_done() < noisy.epoch_count()) {
    noisy.next(epoch);
    omega_sum += epoch.measured.delta_theta_b;
    f_sum += epoch.measured.delta_v_b;
  }
  const double duration = 600.0;
  // ARW 0.01 deg/sqrt(h): mean-rate error N / sqrt(T); bias instability adds ~B.
  const double omega_tolerance =
      5.0 * (0.01 * kDeg / 60.0) / std::sqrt(duration) + 3.0 * 0.05 * kDegPerHour;
  const double f_tolerance = 5.0 * 1e-4 / std::sqrt(duration);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(omega_sum[i] / duration, omega_expected[i], omega_tolerance) << "gyro " << i;
    EXPECT_NEAR(f_sum[i] / duration, f_expected[i], f_tolerance) << "accel " << i;
  }
}

TEST(ScenarioSimulator, BiasesAndScaleFactorsEnterAsModelled) {
  ScenarioConfig config =
      testing::table_config({30.0 * kDeg, 10.0 * kDeg, 40.0 * kDeg}, {testing::static_phase(10.0)});
  config.gyro.constant_bias = {1e-5, -2e-5, 3e-5};
  config.gyro.scale_factor = {1e-3, 2e-3, -1e-3};
  config.accel.constant_bias = {1e-3, 0.0, -1e-3};
  config.accel.turn_on_bias_sigma = 1e-3;
  ScenarioSimulator simulator(config, 11, true);
  ScenarioEpoch epoch;
  simulator.next(epoch);
  for (int i = 0; i < 3; ++i) {
    const double dt = epoch.ideal.dt_s;
    EXPECT_NEAR(epoch.measured.delta_theta_b[i],
                (1.0 + config.gyro.scale_factor[i]) * epoch.ideal.delta_theta_b[i] +
                    config.gyro.constant_bias[i] * dt,
                1e-18);
    EXPECT_NEAR(epoch.measured.delta_v_b[i],
                epoch.ideal.delta_v_b[i] +
                    (config.accel.constant_bias[i] + simulator.accel_turn_on_bias()[i]) * dt,
                1e-15);
    EXPECT_NE(simulator.accel_turn_on_bias()[i], 0.0);
  }
}

TEST(ScenarioSimulator, SameSeedSameRecordOtherSeedOtherNoiseSameTruth) {
  ScenarioConfig config = noisy_static_table(5.0);
  config.vibration_table->phases.push_back(testing::random_phase(5.0, 10.0, 32));
  const auto run = [&](std::uint64_t seed) {
    ScenarioSimulator simulator(config, seed, true);
    std::vector<double> values;
    ScenarioEpoch epoch;
    while (simulator.epochs_done() < simulator.epoch_count()) {
      simulator.next(epoch);
      for (int i = 0; i < 3; ++i) {
        values.push_back(epoch.measured.delta_theta_b[i]);
        values.push_back(epoch.measured.delta_v_b[i]);
      }
    }
    return values;
  };
  const auto a = run(3);
  const auto b = run(3);
  const auto c = run(4);
  EXPECT_EQ(a, b);
  ASSERT_EQ(a.size(), c.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differ += a[i] != c[i];
  EXPECT_GT(differ, a.size() * 9 / 10);
}

TEST(ScenarioSimulator, DrillingIncrementsAreExactToQuadratureAccuracy) {
  const ScenarioConfig config = testing::drilling_config(700.0);
  auto coarse = make_true_motion(config, 1);
  auto fine = make_true_motion(config, 1);
  // Intervals inside a ramp, while rotating, in the vibration episode and across a breakpoint.
  for (double t0 : {121.0, 125.003, 300.0, 555.55, 131.0 - 0.004}) {
    const double dt = 0.01;
    Eigen::Vector3d theta, v;
    coarse->integrate(t0, t0 + dt, theta, v);
    Eigen::Vector3d theta_sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d v_sum = Eigen::Vector3d::Zero();
    for (int j = 0; j < 16; ++j) {
      Eigen::Vector3d piece_theta, piece_v;
      fine->integrate(t0 + j * dt / 16, t0 + (j + 1) * dt / 16, piece_theta, piece_v);
      theta_sum += piece_theta;
      v_sum += piece_v;
    }
    EXPECT_LT((theta - theta_sum).norm(), 1e-12 * theta.norm()) << t0;
    EXPECT_LT((v - v_sum).norm(), 1e-12 * v.norm()) << t0;
  }
}

TEST(ScenarioSimulator, TableVibrationIntegratesToZeroVelocityChangeOverPeriods) {
  // 25 Hz at 100 Hz: four intervals per period; the sine phase starts from rest.
  const auto config =
      testing::table_config({90.0 * kDeg, 0.0, 0.0}, {testing::sine_phase(1.0, 25.0, 5.0)});
  ScenarioSimulator simulator(config, 1, false);
  const Eigen::Matrix3d C_bn = dcm_from_mwd(config.vibration_table->attitude).transpose();
  const Eigen::Vector3d f_static =
      -(C_bn * gravity_n(config.site.latitude_rad, config.site.height_m));
  ScenarioEpoch epoch;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double peak = 0.0;
  for (int k = 0; k < 4; ++k) {
    simulator.next(epoch);
    sum += epoch.ideal.delta_v_b;
    peak = std::max(peak, epoch.truth.v_n.norm());
  }
  EXPECT_LT((sum - f_static * 0.04).norm(), 1e-9);
  EXPECT_NEAR(peak, 5.0 * testing::kG / (2.0 * std::numbers::pi * 25.0), 1e-9);
}

TEST(ScenarioSimulator, TableIncrementsMatchTheKinematicsIntegratedByBruteForce) {
  // One sine phase from t = 0: a(t) = A cos(w t) along u = C_nb e_x.
  const double amplitude = 5.0 * testing::kG;
  const double w = 2.0 * std::numbers::pi * 25.0;
  const auto config = testing::table_config({70.0 * kDeg, 40.0 * kDeg, 130.0 * kDeg},
                                            {testing::sine_phase(1.0, 25.0, 5.0)});
  auto motion = make_true_motion(config, 1);
  auto probe = make_true_motion(config, 1);
  const Eigen::Matrix3d C_nb = dcm_from_mwd(config.vibration_table->attitude);
  const Eigen::Vector3d u = C_nb.col(0);
  for (double t0 : {0.0, 0.37, 0.8123}) {
    const double dt = 0.01;
    Eigen::Vector3d theta, v;
    motion->integrate(t0, t0 + dt, theta, v);
    // Midpoint rule with 20000 steps on the definitions of true_motion.hpp.
    Eigen::Vector3d theta_ref = Eigen::Vector3d::Zero();
    Eigen::Vector3d v_ref = Eigen::Vector3d::Zero();
    const int steps = 20000;
    for (int j = 0; j < steps; ++j) {
      const double t = t0 + (j + 0.5) * dt / steps;
      const TruthSample truth = probe->truth(t);
      const Eigen::Vector3d omega_ie = earth_rate_n(truth.latitude_rad);
      const Eigen::Vector3d omega_en =
          transport_rate_n(truth.latitude_rad, truth.height_m, truth.v_n);
      const Eigen::Vector3d a_n = u * amplitude * std::cos(w * t);
      theta_ref += C_nb.transpose() * (omega_ie + omega_en) * (dt / steps);
      v_ref += C_nb.transpose() *
               (a_n + (2.0 * omega_ie + omega_en).cross(truth.v_n) -
                gravity_n(truth.latitude_rad, truth.height_m)) *
               (dt / steps);
    }
    // Angle increments to 1e-11 relative; velocity increments to 3e-9 relative, the stated
    // bound of the trapezoid used for the second-order transport term (v x omega_en).
    EXPECT_LT((theta - theta_ref).norm(), 1e-11 * theta.norm()) << t0;
    EXPECT_LT((v - v_ref).norm(), 3e-9 * v.norm()) << t0;
  }
}

TEST(ScenarioSimulator, ScheduledNoiseVarianceFollowsThePhaseScale) {
  ScenarioConfig config = testing::table_config(
      {90.0 * kDeg, 0.0, 0.0}, {testing::static_phase(200.0), testing::static_phase(200.0)});
  config.vibration_table->phases[1].gyro_noise_scale = 10.0;
  for (auto& m : config.gyro.scheduled_noise) m.terms = {AngleRandomWalkTerm{1e-6}};
  ScenarioSimulator simulator(config, 9, true);
  ScenarioEpoch epoch;
  double sum_squares[2] = {0.0, 0.0};
  int counts[2] = {0, 0};
  while (simulator.epochs_done() < simulator.epoch_count()) {
    simulator.next(epoch);
    const int phase = epoch.measured.t_s <= 200.0 ? 0 : 1;
    const double noise = epoch.measured.delta_theta_b.x() - epoch.ideal.delta_theta_b.x();
    sum_squares[phase] += noise * noise;
    ++counts[phase];
  }
  const double ratio = (sum_squares[1] / counts[1]) / (sum_squares[0] / counts[0]);
  EXPECT_NEAR(ratio, 100.0, 5.0);
  // The echoed schedule carries the scaled model.
  const auto schedule = simulator.noise_schedule_json();
  ASSERT_EQ(schedule["phases"].size(), 2u);
  const double n0 = schedule["phases"][0]["gyro"][0]["terms"][0]["N"].get<double>();
  const double n1 = schedule["phases"][1]["gyro"][0]["terms"][0]["N"].get<double>();
  EXPECT_NEAR(n1 / n0, 10.0, 1e-9);
}

TEST(Vibration, RandomVibrationMeetsItsRmsAndSteppingMatchesDirectEvaluation) {
  const double g = testing::kG;
  auto vibration =
      random_vibration({{20.0, 0.087 * g * g}, {2000.0, 0.087 * g * g}}, 13.12 * g, 256, 42);
  EXPECT_NEAR(vibration.rms_mps2(), 13.12 * g, 1e-9);
  for (const auto& c : vibration.components()) {
    EXPECT_GE(c.omega_radps, 2.0 * std::numbers::pi * 20.0 * (1.0 - 1e-12));
    EXPECT_LE(c.omega_radps, 2.0 * std::numbers::pi * 2000.0 * (1.0 + 1e-12));
  }
  // Sample RMS over a long stretch.
  double sum = 0.0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const auto value = vibration.evaluate_stepping(k * 1e-4, 1e-4);
    sum += value.acceleration_mps2 * value.acceleration_mps2;
    if (k % 9973 == 0) {
      const auto direct = vibration.evaluate(k * 1e-4);
      EXPECT_NEAR(value.velocity_mps, direct.velocity_mps, 1e-10);
      EXPECT_NEAR(value.displacement_m, direct.displacement_m, 1e-12);
      EXPECT_NEAR(value.displacement_integral_ms, direct.displacement_integral_ms, 1e-12);
    }
  }
  EXPECT_NEAR(std::sqrt(sum / n), 13.12 * g, 0.05 * 13.12 * g);
}

}  // namespace
}  // namespace stochnav
