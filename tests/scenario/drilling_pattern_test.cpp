// Drilling with a general well path and a per-stand slide / rotate pattern: exact kinematics
// (strapdown of the simulated increments follows truth), toolface held in slides and continuous
// across orientation, depth-tied vibration only while drilling.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "drilling_pattern_builders.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/ins/strapdown.hpp"
#include "stochnav/scenario/scenario_simulator.hpp"

namespace stochnav {
namespace {

using testing::kDeg;

double toolface(TrueMotion& motion, double t_s) {
  return mwd_from_dcm(motion.truth(t_s).C_nb).toolface_rad;
}

double angle_difference(double a, double b) {
  return std::remainder(a - b, 2.0 * std::numbers::pi);
}

TEST(DrillingPattern, StrapdownOfTheIncrementsFollowsTruth) {
  const ScenarioConfig config = testing::pattern_config(1500.0);
  ScenarioSimulator simulator(config, 1, /*sensor_errors=*/false);
  StrapdownIntegrator ins(testing::nav_state_of(simulator.initial_truth()));
  double attitude = 0.0;
  double velocity = 0.0;
  double horizontal = 0.0;
  double vertical = 0.0;
  ScenarioEpoch epoch;
  while (simulator.epochs_done() < simulator.epoch_count()) {
    simulator.next(epoch);
    ins.update(epoch.measured);
    if (simulator.epochs_done() % 100 != 0) continue;
    const NavState& s = ins.state();
    const TruthSample& t = epoch.truth;
    attitude = std::max(attitude, Eigen::Quaterniond(t.C_nb).angularDistance(s.q_nb));
    velocity = std::max(velocity, (s.v_n - t.v_n).norm());
    const EarthRadii r = earth_radii(t.latitude_rad);
    horizontal = std::max(
        horizontal, std::hypot((s.latitude_rad - t.latitude_rad) * (r.meridian_m + t.height_m),
                               (s.longitude_rad - t.longitude_rad) * (r.transverse_m + t.height_m) *
                                   std::cos(t.latitude_rad)));
    vertical = std::max(vertical, std::abs(s.height_m - t.height_m));
  }
  std::printf("pattern: attitude %.3g rad, velocity %.3g m/s, horizontal %.3g m, vertical %.3g m\n",
              attitude, velocity, horizontal, vertical);
  // The bounds of ins/strapdown_test.cpp's drilling path (an hour there, 25 min here).
  EXPECT_LT(attitude, 3e-7);
  EXPECT_LT(velocity, 2e-3);
  EXPECT_LT(horizontal, 2.5);
  EXPECT_LT(vertical, 0.5);
  // The tool went through the build-and-turn section.
  EXPECT_GT(epoch.truth.measured_depth_m, 60.0);
}

TEST(DrillingPattern, IncrementsAreExactToQuadratureAccuracyInEverySegmentKind) {
  const ScenarioConfig config = testing::pattern_config(1500.0);
  auto coarse = make_true_motion(config, 1);
  auto fine = make_true_motion(config, 1);
  std::vector<double> starts;
  // Kept: a range-for over a member of the temporary describe() would outlive it.
  const nlohmann::json description = coarse->describe();
  for (const auto& s : description["segments"]) {
    const double a = s["start_s"].get<double>();
    starts.push_back(a + 5.123);  // inside a ramp or an orientation
    starts.push_back(a + 15.5);   // slide or rotation at full rate
    starts.push_back(a - 0.004);  // across the boundary
  }
  int checked = 0;
  for (double t0 : starts) {
    if (t0 < 0.0 || t0 + 0.01 > 1500.0) continue;
    ++checked;
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
    // Relative to the increment, with a floor: at rest or slowly turning they are tiny.
    EXPECT_LT((theta - theta_sum).norm(), 1e-12 * theta.norm() + 1e-15) << t0;  // rad
    EXPECT_LT((v - v_sum).norm(), 1e-12 * v.norm() + 1e-12) << t0;              // m/s
  }
  EXPECT_GE(checked, 10);  // every segment kind, not an empty schedule
}

TEST(DrillingPattern, ToolfaceIsHeldInSlidesAndContinuousThroughOrientation) {
  const ScenarioConfig config = testing::pattern_config(1500.0);
  auto motion = make_true_motion(config, 1);
  const nlohmann::json segments = motion->describe()["segments"];
  int slides = 0;
  int orientations = 0;
  for (const auto& s : segments) {
    const double a = s["start_s"].get<double>();
    const double b = s["end_s"].get<double>();
    const std::string kind = s["kind"].get<std::string>();
    // Continuity at every segment start (toolface and its rate are continuous).
    if (a > 0.0) {
      EXPECT_LT(
          std::abs(angle_difference(toolface(*motion, a + 1e-7), toolface(*motion, a - 1e-7))),
          1e-5)
          << kind << " at " << a;
    }
    if (kind == "orienting") {
      ++orientations;
      // At its end the toolface is the slide's.
      EXPECT_LT(std::abs(angle_difference(toolface(*motion, b), testing::kSlideToolfaceRad)), 1e-9);
    }
    if (kind == "drilling" && s["pattern_index"] == 0) {
      ++slides;
      for (double t = a; t < b; t += 1.0) {
        EXPECT_LT(std::abs(angle_difference(toolface(*motion, t), testing::kSlideToolfaceRad)),
                  1e-9)
            << t;
      }
    }
  }
  EXPECT_GE(slides, 3);
  EXPECT_EQ(orientations, slides);
  // Between samples 10 ms apart the toolface moves by at most 90 rpm * 10 ms.
  double previous = toolface(*motion, 0.0);
  for (int k = 1; k <= 150000; ++k) {
    const double current = toolface(*motion, k * 0.01);
    EXPECT_LE(std::abs(angle_difference(current, previous)), 3.0 * std::numbers::pi * 0.01 + 1e-9)
        << k * 0.01;
    previous = current;
  }
}

TEST(DrillingPattern, DepthTiedVibrationOnlyWhileDrillingInItsRange) {
  const ScenarioConfig config = testing::pattern_config(1500.0);
  auto motion = make_true_motion(config, 1);
  const nlohmann::json description = motion->describe();
  const nlohmann::json& spans = description["md_vibration_spans"];
  ASSERT_GE(spans.size(), 2u);  // the episode crosses a connection and an orientation
  double drilled = 0.0;
  for (const auto& span : spans) {
    const double a = span["start_s"].get<double>();
    const double b = span["end_s"].get<double>();
    // The envelope is zero at the edges: truth depth is the drilled depth there.
    const double md_a = motion->truth(a).measured_depth_m;
    const double md_b = motion->truth(b).measured_depth_m;
    EXPECT_GE(md_a, 50.0 - 1e-9);
    EXPECT_LE(md_b, 62.0 + 1e-9);
    drilled += md_b - md_a;
    for (const auto& s : description["segments"]) {
      const bool overlaps = s["start_s"].get<double>() < b && s["end_s"].get<double>() > a;
      if (overlaps) {
        EXPECT_EQ(s["kind"], "drilling") << a << " " << b;
      }
    }
  }
  EXPECT_NEAR(drilled, 12.0, 1e-6);
  // In connections and orientations the depth stands still (no vibration); the phases say so.
  for (const auto& s : description["segments"]) {
    if (s["kind"] != "connection" && s["kind"] != "orienting") continue;
    for (double t = s["start_s"].get<double>(); t < s["end_s"].get<double>(); t += 0.013) {
      EXPECT_EQ(motion->truth(t).measured_depth_m, s["start_md_m"].get<double>()) << t;
    }
  }
  int vibration_phases = 0;
  for (const auto& phase : motion->phases()) {
    if (phase.name != "vibration") continue;
    ++vibration_phases;
    bool inside = false;
    for (const auto& span : spans) {
      inside = inside || (phase.start_s >= span["start_s"].get<double>() &&
                          phase.end_s <= span["end_s"].get<double>());
    }
    EXPECT_TRUE(inside) << phase.start_s;
  }
  EXPECT_GE(vibration_phases, 2);
  // And the tool does vibrate inside a span: depth oscillates around the drilled depth.
  const double mid = 0.5 * (spans[0]["start_s"].get<double>() + spans[0]["end_s"].get<double>());
  double low = 1e9;
  double high = -1e9;
  for (int k = 0; k < 100; ++k) {
    const double x = motion->truth(mid + k * 0.001).measured_depth_m;
    low = std::min(low, x);
    high = std::max(high, x);
  }
  const double amplitude = 2.0 * testing::kG / std::pow(2.0 * std::numbers::pi * 12.0, 2);
  EXPECT_GT(high - low, amplitude);
}

}  // namespace
}  // namespace stochnav
