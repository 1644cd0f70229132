// The strapdown integrator follows noise-free simulated scenarios over an hour, within the
// bounds stated in ins/strapdown.hpp (measured values are printed; the bounds leave a factor
// of about 3).

#include "stochnav/ins/strapdown.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scenario_builders.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/scenario/scenario_simulator.hpp"

namespace stochnav {
namespace {

using testing::kDeg;

struct Errors {
  double attitude_rad = 0.0;
  double velocity_mps = 0.0;
  double horizontal_m = 0.0;
  double vertical_m = 0.0;
};

// Runs the integrator over the whole scenario on ideal increments; largest errors seen.
Errors follow(const ScenarioConfig& config) {
  ScenarioSimulator simulator(config, 1, /*sensor_errors=*/false);
  StrapdownIntegrator ins(testing::nav_state_of(simulator.initial_truth()));
  Errors worst;
  ScenarioEpoch epoch;
  while (simulator.epochs_done() < simulator.epoch_count()) {
    simulator.next(epoch);
    ins.update(epoch.measured);
    if (simulator.epochs_done() % 100 != 0) continue;
    const NavState& s = ins.state();
    const TruthSample& t = epoch.truth;
    const Eigen::Quaterniond q_true(t.C_nb);
    worst.attitude_rad = std::max(worst.attitude_rad, q_true.angularDistance(s.q_nb));
    worst.velocity_mps = std::max(worst.velocity_mps, (s.v_n - t.v_n).norm());
    const EarthRadii r = earth_radii(t.latitude_rad);
    const double north = (s.latitude_rad - t.latitude_rad) * (r.meridian_m + t.height_m);
    const double east = (s.longitude_rad - t.longitude_rad) * (r.transverse_m + t.height_m) *
                        std::cos(t.latitude_rad);
    worst.horizontal_m = std::max(worst.horizontal_m, std::hypot(north, east));
    worst.vertical_m = std::max(worst.vertical_m, std::abs(s.height_m - t.height_m));
  }
  EXPECT_NEAR(ins.state().t_s, static_cast<double>(simulator.epoch_count()) / config.imu.rate_hz,
              1e-9);
  return worst;
}

void print(const char* name, const Errors& e) {
  std::printf("%s: attitude %.3g rad, velocity %.3g m/s, horizontal %.3g m, vertical %.3g m\n",
              name, e.attitude_rad, e.velocity_mps, e.horizontal_m, e.vertical_m);
}

TEST(Strapdown, StaticToolStaysPutForAnHour) {
  const auto config = testing::table_config({37.0 * kDeg, 200.0 * kDeg, 123.0 * kDeg},
                                            {testing::static_phase(3600.0)});
  const Errors e = follow(config);
  print("static", e);
  EXPECT_LT(e.attitude_rad, 1e-10);
  EXPECT_LT(e.velocity_mps, 1e-5);
  EXPECT_LT(e.horizontal_m, 1e-3);
  EXPECT_LT(e.vertical_m, 1e-2);
}

TEST(Strapdown, FollowsTheVibrationTableForAnHour) {
  const auto config = testing::table_config(
      {90.0 * kDeg, 30.0 * kDeg, 20.0 * kDeg},
      {testing::static_phase(300.0), testing::sine_phase(2700.0, 25.0, 5.0),
       testing::static_phase(300.0), testing::random_phase(300.0, 13.12, 64)});
  const Errors e = follow(config);
  print("vibration table", e);
  EXPECT_LT(e.attitude_rad, 1e-8);
  EXPECT_LT(e.velocity_mps, 1e-3);
  EXPECT_LT(e.horizontal_m, 0.05);
  EXPECT_LT(e.vertical_m, 0.5);
}

TEST(Strapdown, FollowsADrillingPathForAnHour) {
  const Errors e = follow(testing::drilling_config(3600.0));
  print("drilling", e);
  EXPECT_LT(e.attitude_rad, 3e-7);
  EXPECT_LT(e.velocity_mps, 2e-3);
  EXPECT_LT(e.horizontal_m, 2.5);
  EXPECT_LT(e.vertical_m, 0.5);
}

TEST(Strapdown, ZeroIntervalOnlyMovesTime) {
  NavState start;
  start.latitude_rad = 0.5;
  StrapdownIntegrator ins(start);
  ImuIncrement increment;
  increment.t_s = 2.0;
  increment.dt_s = 0.0;
  increment.delta_v_b = Eigen::Vector3d(1.0, 2.0, 3.0);
  ins.update(increment);
  EXPECT_EQ(ins.state().t_s, 2.0);
  EXPECT_EQ(ins.state().v_n, start.v_n);
  EXPECT_EQ(ins.state().latitude_rad, start.latitude_rad);
}

TEST(Strapdown, RotationVectorQuaternionIsExactForSmallAndLargeAngles) {
  for (double angle : {0.0, 1e-12, 1e-8, 1e-3, 0.5, 3.0}) {
    const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
    const Eigen::Quaterniond expected(Eigen::AngleAxisd(angle, axis));
    EXPECT_LT(quaternion_from_rotation_vector(angle * axis).angularDistance(expected), 1e-15);
  }
}

// The mean of C_nb over an epoch of constant body rate against a 2,000-point midpoint sum, on
// both sides of the series' range (0.1 rad) and at a spinning tool's 0.168 rad (160 rpm, 100 Hz);
// the chord of the ends is off by |a|^2 / 8 across the axis.
TEST(Strapdown, EpochMeanAttitudeIsTheMeanOverTheEpoch) {
  const Eigen::Matrix3d start =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, 1.0, -0.4).normalized()).toRotationMatrix();
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.1, 1.0).normalized();
  for (const double angle : {0.0, 1e-4, 0.05, 0.0999, 0.1001, 0.168, 0.6}) {
    const int steps = 2000;
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    for (int i = 0; i < steps; ++i) {
      const double s = (i + 0.5) / steps;
      sum += start * Eigen::AngleAxisd(s * angle, axis).toRotationMatrix();
    }
    const Eigen::Matrix3d mean = sum / steps;
    EXPECT_LT((epoch_mean_attitude(start, angle * axis) - mean).norm(), 1e-7 * angle * angle + 1e-12)
        << "angle " << angle;
    if (angle > 0.1) {
      const Eigen::Matrix3d chord =
          0.5 * (start + start * Eigen::AngleAxisd(angle, axis).toRotationMatrix());
      EXPECT_GT((chord - mean).norm(), 0.05 * angle * angle) << "angle " << angle;
    }
  }
}

// A static tool: the specific-force increment is the accelerometers' in n, minus gravity.
TEST(Strapdown, SpecificForceIncrementIsTheAccelerometersInN) {
  const auto config = testing::table_config({37.0 * kDeg, 200.0 * kDeg, 123.0 * kDeg},
                                            {testing::static_phase(10.0)});
  ScenarioSimulator simulator(config, 1, /*sensor_errors=*/false);
  StrapdownIntegrator ins(testing::nav_state_of(simulator.initial_truth()));
  ScenarioEpoch epoch;
  for (int k = 0; k < 100; ++k) {
    simulator.next(epoch);
    ins.update(epoch.measured);
  }
  const Eigen::Vector3d expected =
      -gravity_n(ins.state().latitude_rad, ins.state().height_m) * epoch.measured.dt_s;
  EXPECT_LT((ins.specific_force_increment_n() - expected).norm(), 1e-9 * expected.norm());
}

// A filter's feedback of a zero correction every second leaves a spinning tool's integration as
// it was (to the quaternion's renormalisation): the sculling and coning history is kept. (Forgotten, as set_state does,
// the velocity at 160 rpm was off by (theta^2 / 12) |f_perp| dt a second, 23 micro-g.)
TEST(Strapdown, AFeedbackKeepsTheSpinningToolsSculling) {
  auto config = testing::drilling_config(400.0);
  config.drilling->rotation_radps = 2.0 * std::numbers::pi * 160.0 / 60.0;
  config.drilling->vibration_episodes.clear();
  config.drilling->start_md_m = 300.0;  // in the build, about 85 deg
  ScenarioSimulator simulator(config, 1, /*sensor_errors=*/false);
  StrapdownIntegrator plain(testing::nav_state_of(simulator.initial_truth()));
  StrapdownIntegrator fed_back = plain;
  StrapdownIntegrator restarted = plain;
  ScenarioEpoch epoch;
  while (simulator.epochs_done() < simulator.epoch_count()) {
    simulator.next(epoch);
    plain.update(epoch.measured);
    fed_back.update(epoch.measured);
    restarted.update(epoch.measured);
    if (simulator.epochs_done() % 100 == 0) {
      fed_back.correct_state(fed_back.state());
      restarted.set_state(restarted.state());
    }
  }
  EXPECT_LT((fed_back.state().v_n - plain.state().v_n).norm(), 1e-9);
  EXPECT_LT(fed_back.state().q_nb.angularDistance(plain.state().q_nb), 1e-12);
  const double velocity_error = (plain.state().v_n - epoch.truth.v_n).norm();
  const double restarted_error = (restarted.state().v_n - epoch.truth.v_n).norm();
  std::printf("160 rpm, 400 s: velocity error %.3g m/s, restarted every second %.3g m/s\n",
              velocity_error, restarted_error);
  EXPECT_GT(restarted_error, 3.0 * velocity_error);
}

}  // namespace
}  // namespace stochnav
