// Noise plugin "davar": the noise-model properties, the exact integral of a time-varying N(t)^2,
// params errors, and recovery of a simulated nonstationary angle random walk (offline and
// causal windows) through the windowed Allan-variance fit.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "noise_plugin_support.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/model/noise_model.hpp"
#include "stochnav/sim/noise_generator.hpp"

namespace stochnav::plugin {
namespace {

using testing::Case;
using testing::case_name;
using testing::kDegPerRootHour;
using testing::context_for;
using testing::make;
using testing::NoiseModelProperties;
using testing::registry;

const nlohmann::json kOffline = {
    {"mode", "offline"},
    {"t", {0.0, 2.0, 4.5, 6.0, 10.0}},
    {"N", {{0.05, 0.5, 0.1, 0.2, 0.05}, {0.1, 0.1, 0.3, 0.3, 0.0}, {1.0, 2.0, 3.0, 4.0, 5.0}}},
    {"K", 0.01}};
const nlohmann::json kCausal = {{"mode", "causal"},
                                {"t", {1.0, 5.5, 6.0}},
                                {"N", {{0.02, 0.2, 0.04}, {0.03, 0.01, 0.02}, {0.5, 0.05, 0.05}}}};

// Start times around every analysis time of both models, before the first and after the last:
// the composed steps (0.37 s, then 1.9 s) cross each change of slope or level.
const PropertyCheckOptions kAroundAnalysisTimes{.times_s = {-1.0, 0.8, 1.8, 4.2, 5.3, 5.9, 9.5}};

INSTANTIATE_TEST_SUITE_P(
    Davar, NoiseModelProperties,
    ::testing::Values(Case{"davar", kOffline, SensorGroup::kGyro, kAroundAnalysisTimes},
                      Case{"davar", kCausal, SensorGroup::kAccel, kAroundAnalysisTimes}),
    case_name);

/// int_a^b of N(t)^2 for the gyro model {"t": [0, 10], "N": [n0, n1]} by the closed form of a
/// linear (offline) or held (causal) N^2, in rad^2.
double expected_integral(bool causal, double n0, double n1, double a, double b) {
  const double p0 = std::pow(n0 * kDegPerRootHour, 2);
  const double p1 = std::pow(n1 * kDegPerRootHour, 2);
  const auto level = [&](double t) {
    if (t <= 0.0) return p0;
    if (t >= 10.0) return p1;
    return causal ? p0 : p0 + (p1 - p0) * t / 10.0;
  };
  // Piecewise: constant before 0 and after 10, linear or held in between.
  double sum = 0.0;
  const double cuts[] = {a, std::clamp(0.0, a, b), std::clamp(10.0, a, b), b};
  for (int i = 0; i < 3; ++i) {
    const double lo = cuts[i], hi = cuts[i + 1];
    if (hi <= lo) continue;
    const double mid = 0.5 * (lo + hi);
    sum += (hi - lo) * (causal && mid > 0.0 && mid < 10.0 ? p0 : 0.5 * (level(lo) + level(hi)));
  }
  return sum;
}

TEST(DavarNoise, WhiteCovarianceIsTheExactIntegralOfTheInterpolatedLevel) {
  for (const bool causal : {false, true}) {
    const auto model = make("davar", {{"mode", causal ? "causal" : "offline"},
                                      {"t", {0.0, 10.0}},
                                      {"N", {{0.1, 0.3}, {0.1, 0.3}, {0.2, 0.2}}}});
    Eigen::Matrix3d q;
    // In the middle, across the end, before the start; then backwards (cursor fallback).
    for (const auto& [a, b] :
         {std::pair{2.0, 7.0}, std::pair{8.0, 13.0}, std::pair{-4.0, 3.0}, std::pair{0.5, 0.51}}) {
      model->white_noise_covariance(a, b - a, q);
      const double expected = expected_integral(causal, 0.1, 0.3, a, b);
      EXPECT_NEAR(q(0, 0), expected, 1e-13 * expected) << causal << " " << a << " " << b;
      EXPECT_NEAR(q(1, 1), expected, 1e-13 * expected);
      EXPECT_NEAR(q(2, 2), std::pow(0.2 * kDegPerRootHour, 2) * (b - a),
                  1e-13 * expected);
      EXPECT_EQ(q(0, 1), 0.0);
    }
  }
}

TEST(DavarNoise, ManySmallStepsSumToTheWholeIntegral) {
  const auto model = make("davar", kOffline);
  Eigen::Matrix3d q, sum = Eigen::Matrix3d::Zero(), whole;
  for (int k = 0; k < 1500; ++k) {  // 100 Hz epochs over [-1, 14)
    model->white_noise_covariance(-1.0 + 0.01 * k, 0.01, q);
    sum += q;
  }
  model->white_noise_covariance(-1.0, 15.0, whole);
  EXPECT_LE((sum - whole).cwiseAbs().maxCoeff(), 1e-12 * whole.cwiseAbs().maxCoeff());
}

TEST(DavarNoise, BadParamsNameTheJsonPointer) {
  const auto message = [](const nlohmann::json& params) {
    try {
      make("davar", params);
    } catch (const ConfigError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{"t", {0.0, 1.0}}, {"N", {{0.1, 0.1}, {0.1}, {0.1, 0.1}}}})
                .find("/noise/gyro/params/N/1: found [0.1]; expected an array of 2 values"),
            std::string::npos);
  EXPECT_NE(message({{"t", {0.0, 0.0}}, {"N", {{0.1, 0.1}, {0.1, 0.1}, {0.1, 0.1}}}})
                .find("/noise/gyro/params/t/1: found 0.0; expected"),
            std::string::npos);
  EXPECT_NE(message({{"t", {0.0}}, {"N", {{-1.0}, {0.1}, {0.1}}}})
                .find("/noise/gyro/params/N/0/0: found -1.0; expected a number >= 0"),
            std::string::npos);
  EXPECT_NE(message({{"t", {0.0}}, {"N", {{1.0}, {0.1}, {0.1}}}, {"mode", "live"}})
                .find("/noise/gyro/params/mode"),
            std::string::npos);
}

TEST(DavarFit, BadFitParamsNameTheJsonPointer) {
  CalibrationRecord record;
  record.rate_hz = 100.0;
  record.source = "constant";
  for (auto& axis : record.axes) axis.assign(20000, 0.0);
  const auto fit = [&](const nlohmann::json& params) {
    try {
      registry().fit_noise_model("davar", record, params, context_for(SensorGroup::kGyro), "/p");
    } catch (const ConfigError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(fit({{"terms", {"B"}}}).find("/noise/gyro/params/terms: found [\"B\"]; expected"),
            std::string::npos);
  EXPECT_NE(fit({{"window_s", 0.1}}).find("/noise/gyro/params/window_s: found 0.1; expected"),
            std::string::npos);
}

// ---- recovery of a simulated nonstationary angle random walk ----

constexpr double kDuration = 1800.0, kRise = 600.0, kFall = 1200.0, kScale = 10.0;
constexpr double kN0 = 0.05;  // deg/sqrt(h)
constexpr double kWindow = 60.0, kStep = 5.0;

CalibrationRecord nonstationary_record(std::uint64_t seed) {
  const NoiseModel truth{Unit::kRadPerSecond,
                         100.0,
                         {AngleRandomWalkTerm{kN0 * kDegPerRootHour},
                          NonstationaryTerm{{NonstationarySegment{kRise, kFall, kScale}}}}};
  CalibrationRecord record;
  record.rate_hz = 100.0;
  record.source = "simulated";
  for (std::size_t axis = 0; axis < 3; ++axis) {
    record.axes[axis] = simulate_noise(truth, kDuration, 100.0, 100 * seed + axis);
  }
  return record;
}

double true_n(double t) { return t >= kRise && t < kFall ? kScale * kN0 : kN0; }

/// First time on a 0.1 s grid in [from, to) where the model's N^2 (from Qw over a 1 ms step,
/// deg^2/h) crosses the mid level (N0^2 + (10 N0)^2) / 2, upwards or downwards.
double crossing_time(const NoiseModelPlugin& model, int axis, double from, double to, bool upward) {
  const double mid = 0.5 * (1.0 + kScale * kScale) * kN0 * kN0;
  Eigen::Matrix3d q;
  for (double t = from; t < to; t += 0.1) {
    model.white_noise_covariance(t, 1e-3, q);
    const double level = q(axis, axis) / 1e-3 / std::pow(kDegPerRootHour, 2);
    if (upward ? level >= mid : level <= mid) return t;
  }
  return NAN;
}

TEST(DavarFit, RecoversANonstationaryAngleRandomWalkInBothModes) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const CalibrationRecord record = nonstationary_record(seed);
    for (const bool causal : {false, true}) {
      const nlohmann::json params = {
          {"mode", causal ? "causal" : "offline"}, {"window_s", kWindow}, {"step_s", kStep}};
      const auto model = registry().fit_noise_model("davar", record, params,
                                                    context_for(SensorGroup::kGyro), "/p");
      const nlohmann::json fitted = model->params();
      const auto& t = fitted["t"];
      // Away from the changes (a whole window), every window sees one level.
      double worst = 0.0;
      for (int axis = 0; axis < 3; ++axis) {
        for (std::size_t j = 0; j < t.size(); ++j) {
          const double time = t[j].get<double>();
          const double reach = causal ? kWindow : 0.5 * kWindow;  // data used before time
          const double ahead = causal ? 0.0 : 0.5 * kWindow;      // data used after time
          const bool mixed = [&] {
            for (double change : {kRise, kFall}) {
              if (time + ahead > change - 1e-9 && time - reach < change + 1e-9) return true;
            }
            return false;
          }();
          if (mixed) continue;
          const double n = fitted["N"][axis][j].get<double>();
          worst = std::max(worst, std::abs(n / true_n(time) - 1.0));
          EXPECT_NEAR(n, true_n(time), 0.1 * true_n(time))
              << "seed " << seed << " causal " << causal << " axis " << axis << " t " << time;
        }
      }
      // Offline: centred on the change. Causal: half a window after it (a held value changes
      // only at analysis times, every step: the first window at least half past the change
      // ends at change + window / 2 or one step later; 0.2 s for the 0.1 s search grid).
      const double lag = causal ? 0.5 * kWindow : 0.0;
      const double tolerance = kStep + 0.2;
      for (int axis = 0; axis < 3; ++axis) {
        const double rise = crossing_time(*model, axis, 300.0, 900.0, true);
        const double fall = crossing_time(*model, axis, 900.0, 1500.0, false);
        EXPECT_NEAR(rise, kRise + lag, tolerance) << "seed " << seed << " causal " << causal;
        EXPECT_NEAR(fall, kFall + lag, tolerance) << "seed " << seed << " causal " << causal;
        if (causal) {
          EXPECT_GT(rise, kRise);
          EXPECT_GT(fall, kFall);
        }
        if (axis == 0) {
          std::printf("seed %d %s: worst |N/N_true - 1| = %.3f, rise at %.1f s, fall at %.1f s\n",
                      static_cast<int>(seed), causal ? "causal " : "offline", worst, rise, fall);
        }
      }
    }
  }
}

}  // namespace
}  // namespace stochnav::plugin
