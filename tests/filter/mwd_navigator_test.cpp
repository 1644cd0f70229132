// The MWD navigator on a stationary tool with known truth: it stays on the truth without noise,
// its covariance is consistent with its errors (NEES over Monte-Carlo seeds), and propagating P
// once per 0.1 s agrees with propagating it at every IMU epoch, also under a vibration whose
// period divides the interval.

#include "stochnav/filter/mwd_navigator.hpp"

#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <array>
#include <memory>
#include <numbers>

#include "static_truth.hpp"

namespace stochnav {
namespace {

using testing::core_error;
using testing::IntervalRecorder;
using testing::kDeg;
using testing::NoisyStaticAid;
using testing::StaticImu;
using testing::StaticImuErrors;
using testing::TestWhiteNoise;

using testing::kRateHz;

NavState perturbed(const NavState& truth, const Eigen::Matrix<double, 15, 1>& dx) {
  NavState estimate = truth;
  const EarthRadii radii = earth_radii(truth.latitude_rad);
  estimate.longitude_rad +=
      dx(0) / ((radii.transverse_m + truth.height_m) * std::cos(truth.latitude_rad));
  estimate.latitude_rad += dx(1) / (radii.meridian_m + truth.height_m);
  estimate.height_m += dx(2);
  estimate.v_n += dx.segment<3>(3);
  estimate.q_nb = quaternion_from_rotation_vector(-dx.segment<3>(6)) * truth.q_nb;
  return estimate;
}

TEST(MwdNavigator, NoiseFreeStationaryToolStaysOnTruthForAnHour) {
  const NavState truth = testing::static_truth_state();
  StaticImu imu(truth, {}, kRateHz, 1);
  TestWhiteNoise gyro(plugin::SensorGroup::kGyro, 1e-6);
  TestWhiteNoise accel(plugin::SensorGroup::kAccel, 1e-5);
  // The second-order attitude term's mean is the drift expected of an error drawn from P: a
  // noise-free truth is not such a draw (tests/filter/second_order_attitude_test.cpp).
  FilterOptions options;
  options.second_order_attitude_correlation_s = 0.0;
  MwdNavigator navigator(truth, gyro, accel, {}, options);
  for (int k = 0; k < 3600 * 100; ++k) navigator.step(imu.next());
  const auto dx =
      core_error(navigator.state(), truth, navigator.accel_bias_b(), navigator.gyro_bias_b(), {});
  EXPECT_LT(dx.head<3>().norm(), 1e-3) << "position error (m)";
  EXPECT_LT(dx.segment<3>(3).norm(), 1e-6) << "velocity error (m/s)";
  EXPECT_LT(dx.segment<3>(6).norm(), 1e-8) << "attitude error (rad)";
  EXPECT_TRUE(navigator.health().ok());
}

struct NeesRun {
  std::vector<double> nees;  // at each check time
};

NeesRun run_seed(std::uint64_t seed, const FilterOptions& options, int seconds) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal;
  Eigen::Matrix<double, 15, 1> sigma;
  sigma << options.position_sigma_m, options.velocity_sigma_mps, options.attitude_sigma_rad,
      options.accel_bias_sigma_mps2, options.gyro_bias_sigma_radps;
  Eigen::Matrix<double, 15, 1> initial_error;
  for (int i = 0; i < 15; ++i) initial_error(i) = sigma(i) * normal(engine);

  const NavState truth = testing::static_truth_state();
  StaticImuErrors errors{.gyro_arw = 0.2 * kDeg / 60.0, .accel_vrw = 0.05 / 60.0};
  // The filter starts from zero bias estimates: the true biases are minus the initial errors.
  errors.accel_bias = -initial_error.segment<3>(9);
  errors.gyro_bias = -initial_error.segment<3>(12);
  StaticImu imu(truth, errors, kRateHz, seed + 1000);
  TestWhiteNoise gyro(plugin::SensorGroup::kGyro, errors.gyro_arw);
  TestWhiteNoise accel(plugin::SensorGroup::kAccel, errors.accel_vrw);
  NoisyStaticAid aid(truth, 0.05, 0.002, seed + 2000);
  MwdNavigator navigator(perturbed(truth, initial_error), gyro, accel, {&aid}, options);

  NeesRun run;
  const int steps_per_check = static_cast<int>(60 * kRateHz);
  for (int k = 1; k <= seconds * static_cast<int>(kRateHz); ++k) {
    navigator.step(imu.next());
    if (k % steps_per_check == 0) {
      const auto dx = core_error(navigator.state(), truth, navigator.accel_bias_b(),
                                 navigator.gyro_bias_b(), errors);
      const Eigen::MatrixXd p = navigator.covariance().topLeftCorner(15, 15);
      run.nees.push_back(dx.dot(p.ldlt().solve(dx)));
    }
  }
  EXPECT_TRUE(navigator.health().ok());
  return run;
}

TEST(MwdNavigator, AverageNeesIsInsideItsChiSquareBounds) {
  constexpr int kSeeds = 24;
  constexpr int kSeconds = 600;
  std::vector<double> sum;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const NeesRun run = run_seed(static_cast<std::uint64_t>(seed), FilterOptions{}, kSeconds);
    sum.resize(run.nees.size(), 0.0);
    for (std::size_t i = 0; i < run.nees.size(); ++i) sum[i] += run.nees[i];
  }
  // Average NEES over seeds at one time: chi2(15 kSeeds) / kSeeds; two-sided 99 % bounds each.
  const boost::math::chi_squared chi2(15.0 * kSeeds);
  const double lower = boost::math::quantile(chi2, 0.005) / kSeeds;
  const double upper = boost::math::quantile(chi2, 0.995) / kSeeds;
  int outside = 0;
  std::string trace;
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double average = sum[i] / kSeeds;
    if (average < lower || average > upper) ++outside;
    trace += " t=" + std::to_string(60 * (i + 1)) + "s: " + std::to_string(average);
  }
  // Ten check times at 99 % each: at most one outside by chance.
  EXPECT_LE(outside, 1) << "average NEES outside [" << lower << ", " << upper << "]:" << trace;
}

// A state far outside its covariance makes every NIS fail the gate; each rejection lets the
// error grow, so a strict gate never lets the aid back in. The lockout rule applies the aid
// ungated after FilterOptions::max_consecutive_rejections rejections in a row.
TEST(MwdNavigator, TheNisGateDoesNotLockTheAidOutForGood) {
  const NavState truth = testing::static_truth_state();
  Eigen::Matrix<double, 15, 1> initial_error = Eigen::Matrix<double, 15, 1>::Zero();
  initial_error(0) = 50.0;  // 50 m east, while P says 0.1 m
  const auto position_error_after_a_minute = [&](int max_rejections) {
    FilterOptions options;
    options.max_consecutive_rejections = max_rejections;
    StaticImu imu(truth, {}, kRateHz, 5);
    TestWhiteNoise gyro(plugin::SensorGroup::kGyro, 1e-6);
    TestWhiteNoise accel(plugin::SensorGroup::kAccel, 1e-5);
    NoisyStaticAid aid(
        truth, 0.05, 0.002, 6,
        plugin::NisGate{.enabled = true, .threshold = plugin::chi_square_quantile(0.999, 6)});
    MwdNavigator navigator(perturbed(truth, initial_error), gyro, accel, {&aid}, options);
    for (int k = 0; k < 60 * static_cast<int>(kRateHz); ++k) navigator.step(imu.next());
    return core_error(navigator.state(), truth, navigator.accel_bias_b(), navigator.gyro_bias_b(),
                      {})
        .head<3>()
        .norm();
  };
  EXPECT_GT(position_error_after_a_minute(0), 49.0) << "a strict gate keeps the aid out";
  EXPECT_LT(position_error_after_a_minute(10), 5.0) << "the lockout rule lets it back in";
}

TEST(MwdNavigator, IntervalPropagationMatchesEveryEpochPropagation) {
  FilterOptions every_epoch;
  every_epoch.covariance_interval_s = 0.0;
  const NavState truth = testing::static_truth_state();
  StaticImuErrors errors{.gyro_arw = 0.2 * kDeg / 60.0, .accel_vrw = 0.05 / 60.0};
  std::vector<Eigen::MatrixXd> covariances;
  for (const FilterOptions& options : {FilterOptions{}, every_epoch}) {
    StaticImu imu(truth, errors, kRateHz, 7);
    TestWhiteNoise gyro(plugin::SensorGroup::kGyro, errors.gyro_arw);
    TestWhiteNoise accel(plugin::SensorGroup::kAccel, errors.accel_vrw);
    NoisyStaticAid aid(truth, 0.05, 0.002, 8);
    MwdNavigator navigator(truth, gyro, accel, {&aid}, options);
    for (int k = 0; k < 300 * 100; ++k) navigator.step(imu.next());
    covariances.push_back(navigator.covariance());
  }
  const Eigen::VectorXd a = covariances[0].diagonal();
  const Eigen::VectorXd b = covariances[1].diagonal();
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(std::sqrt(a(i)) / std::sqrt(b(i)), 1.0, 0.01) << "state " << i;
  }
}

// A 2-g axial vibration at 10 Hz has whole periods in a 1-s covariance interval: the velocity
// error it causes through a heading error (phi x its oscillation velocity) is sampled at the
// same phase at every interval's end. Taken as constant over the next interval it would grow the
// position variance without bound; integrated over the interval (error_dynamics.hpp,
// position_shape_correction) it agrees with propagating P at every epoch.
TEST(MwdNavigator, IntervalPropagationMatchesEveryEpochPropagationUnderAPhaseLockedVibration) {
  const double amplitude_mps2 = 2.0 * 9.8;
  const double omega_radps = 2.0 * std::numbers::pi * 10.0;
  FilterOptions options;
  options.covariance_interval_s = 1.0;
  options.attitude_sigma_rad = {1e-4, 1e-4, 5.0 * kDeg};
  options.position_sigma_m.setConstant(1e-3);
  options.velocity_sigma_mps.setConstant(1e-4);
  options.accel_bias_sigma_mps2.setConstant(1e-6);
  options.gyro_bias_sigma_radps.setConstant(1e-9);
  options.second_order_attitude_correlation_s = 0.0;
  FilterOptions every_epoch = options;
  every_epoch.covariance_interval_s = 0.0;
  const NavState truth = testing::static_truth_state();
  std::vector<Eigen::MatrixXd> covariances;
  for (const FilterOptions& run : {options, every_epoch}) {
    StaticImu imu(truth, StaticImuErrors{}, kRateHz, 7);
    TestWhiteNoise gyro(plugin::SensorGroup::kGyro, 1e-9);
    TestWhiteNoise accel(plugin::SensorGroup::kAccel, 1e-9);
    MwdNavigator navigator(truth, gyro, accel, {}, run);
    for (int k = 0; k < 120 * 100; ++k) {
      ImuIncrement increment = imu.next();
      const double t0 = increment.t_s - increment.dt_s;
      increment.delta_v_b.z() +=
          amplitude_mps2 / omega_radps *
          (std::cos(omega_radps * t0) - std::cos(omega_radps * increment.t_s));
      navigator.step(increment);
    }
    covariances.push_back(navigator.covariance());
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::sqrt(covariances[0](i, i)) / std::sqrt(covariances[1](i, i)), 1.0, 0.01)
        << "position axis " << i;
  }
}

// Interval aids whose intervals start at the same epoch share one accumulator; when one of them
// measures alone, the next inherits the sums and the rest follow the heir
// (MwdNavigator::restart_aid_interval). Four aids: every 4 epochs, twice every 8 (the one every
// 4 measures alone with both as its followers), and every 7 from 3 (staggered against the
// others: alone, in pairs, all four together). Each must see the interval it sees as the
// navigator's only aid, to the last bit.
TEST(MwdNavigator, SharedIntervalSumsAreEachAidsOwnUnderStaggeredEpochs) {
  const NavState truth = testing::static_truth_state();
  const StaticImuErrors errors{.gyro_arw = 0.2 * kDeg / 60.0, .accel_vrw = 0.05 / 60.0};
  const std::array<std::pair<int, int>, 4> schedules{{{4, 0}, {8, 0}, {8, 0}, {7, 3}}};
  constexpr int kEpochs = 2000;
  // The covariance at every epoch and no second-order attitude feedback: otherwise the epochs
  // at which P is propagated, which follow the aids' epochs, move the state by the last bits.
  FilterOptions options;
  options.covariance_interval_s = 0.0;
  options.second_order_attitude_correlation_s = 0.0;
  const auto run = [&](std::vector<IntervalRecorder*> aids) {
    StaticImu imu(truth, errors, kRateHz, 11);
    TestWhiteNoise gyro(plugin::SensorGroup::kGyro, errors.gyro_arw);
    TestWhiteNoise accel(plugin::SensorGroup::kAccel, errors.accel_vrw);
    std::vector<plugin::AidPlugin*> plugins(aids.begin(), aids.end());
    MwdNavigator navigator(truth, gyro, accel, plugins, options);
    for (int k = 0; k < kEpochs; ++k) navigator.step(imu.next());
  };
  std::vector<std::unique_ptr<IntervalRecorder>> together, alone;
  for (const auto& [period, phase] : schedules) {
    together.push_back(std::make_unique<IntervalRecorder>(period, phase));
    alone.push_back(std::make_unique<IntervalRecorder>(period, phase));
  }
  run({together[0].get(), together[1].get(), together[2].get(), together[3].get()});
  for (const auto& aid : alone) run({aid.get()});
  for (std::size_t a = 0; a < schedules.size(); ++a) {
    const auto& shared = together[a]->intervals;
    const auto& own = alone[a]->intervals;
    ASSERT_EQ(shared.size(), own.size()) << "aid " << a;
    ASSERT_GT(shared.size(), 100u) << "aid " << a;
    for (std::size_t i = 0; i < shared.size(); ++i) {
      SCOPED_TRACE("aid " + std::to_string(a) + ", measurement " + std::to_string(i));
      EXPECT_GT(own[i].duration_s, 0.0);
      EXPECT_EQ(shared[i].duration_s, own[i].duration_s);
      EXPECT_EQ(shared[i].mean_v_n, own[i].mean_v_n);
      EXPECT_EQ(shared[i].mean_velocity_error_map, own[i].mean_velocity_error_map);
      EXPECT_EQ(shared[i].mean_velocity_noise_covariance, own[i].mean_velocity_noise_covariance);
    }
  }
}

}  // namespace
}  // namespace stochnav
