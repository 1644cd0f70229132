// The strapdown integrator follows noise-free simulated scenarios over an hour, within the
// bounds stated in ins/strapdown.hpp (measured values are printed; the bounds leave a factor
// of about 3).

#include "stochnav/ins/strapdown.hpp"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace stochnav
