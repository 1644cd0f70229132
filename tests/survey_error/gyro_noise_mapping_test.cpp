// The mapping from a fitted gyro noise model to GXY-RN, GXY-GD and GXY-GRW against its closed
// forms (survey_error/gyro_noise_mapping.hpp), and the tool model names.

#include "stochnav/survey_error/gyro_noise_mapping.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/survey_error/tool_models.hpp"

namespace stochnav::survey_error {
namespace {

constexpr double kRadPerSecondPerDegPerHour = kRadPerDeg / 3600.0;
constexpr double kRadPerSqrtSecondPerDegPerSqrtHour = kRadPerDeg / 60.0;

NoiseModel gyro_model(const nlohmann::json& terms) {
  return noise_model_from_json({{"units", "deg/h"}, {"rate_hz", 100}, {"terms", terms}});
}

TEST(GyroNoiseMapping, AngleRandomWalkGivesTheWalkAndTheGyrocompassNoise) {
  // N = 0.01 deg/sqrt(h), T = 36 s = 0.01 h: RN = N / sqrt(T) = 0.1 deg/h, GRW = N.
  const MappedGyroTerms mapped =
      map_gyro_noise_model(gyro_model({{{"type", "angle_random_walk"}, {"N", 0.01}}}), 36.0, 1000.0,
                           owsg_gyro_ns_ct_terms());
  EXPECT_NEAR(mapped.terms.random_walk_rad_per_sqrt_s, 0.01 * kRadPerSqrtSecondPerDegPerSqrtHour,
              1e-15);
  EXPECT_NEAR(mapped.terms.noise_rad_s / kRadPerSecondPerDegPerHour, 0.1, 1e-12);
  EXPECT_EQ(mapped.terms.drift_rad_s, 0.0);
  EXPECT_TRUE(mapped.ignored_terms.empty());
  // The tool's constants stay.
  EXPECT_EQ(mapped.terms.noise_reduction_factor, owsg_gyro_ns_ct_terms().noise_reduction_factor);
  EXPECT_EQ(mapped.terms.running_speed_m_s, owsg_gyro_ns_ct_terms().running_speed_m_s);
}

TEST(GyroNoiseMapping, DriftAddsBiasInstabilityAndRateRandomWalkInQuadrature) {
  // B = 0.1 deg/h: 0.664 B; K = 0.3 deg/h/sqrt(h) over T_run = 3 h: K sqrt(T_run / 3) = 0.3.
  const double b = 0.1, k = 0.3, run_h = 3.0;
  const MappedGyroTerms mapped =
      map_gyro_noise_model(gyro_model({{{"type", "bias_instability"}, {"B", b}},
                                       {{"type", "rate_random_walk"}, {"K", k}}}),
                           60.0, run_h * 3600.0, owsg_gyro_ns_ct_terms());
  const double floor = std::sqrt(2.0 * std::log(2.0) / M_PI) * b;
  EXPECT_NEAR(floor, 0.0664, 1e-4);
  EXPECT_NEAR(mapped.terms.drift_rad_s / kRadPerSecondPerDegPerHour,
              std::hypot(floor, k * std::sqrt(run_h / 3.0)), 1e-12);
  EXPECT_EQ(mapped.terms.noise_rad_s, 0.0);
  EXPECT_EQ(mapped.terms.random_walk_rad_per_sqrt_s, 0.0);
}

// A constant drift d over T_run gives the azimuth variance d^2 T_run^2; the rate random walk's
// integral K^2 T_run^3 / 3: the two agree at the end of the run.
TEST(GyroNoiseMapping, RateRandomWalkDriftMatchesTheIntegratedWalkAtTheRunEnd) {
  const double k_si = 0.2 * kRadPerSecondPerDegPerHour / 60.0;  // 0.2 deg/h/sqrt(h)
  const double run_s = 7200.0;
  const MappedGyroTerms mapped =
      map_gyro_noise_model(gyro_model({{{"type", "rate_random_walk"}, {"K", 0.2}}}), 60.0, run_s,
                           owsg_gyro_ns_ct_terms());
  EXPECT_NEAR(std::pow(mapped.terms.drift_rad_s * run_s, 2), k_si * k_si * std::pow(run_s, 3) / 3.0,
              1e-12 * k_si * k_si * std::pow(run_s, 3));
  // No run, no drift from the walk.
  EXPECT_EQ(map_gyro_noise_model(gyro_model({{{"type", "rate_random_walk"}, {"K", 0.2}}}), 60.0,
                                 0.0, owsg_gyro_ns_ct_terms())
                .terms.drift_rad_s,
            0.0);
}

// A Gauss-Markov bias started at 0: a rate random walk while T_run << tau_c (2 sigma^2 / tau_c
// = K^2), an angle random walk of N^2 = 2 sigma^2 tau_c once T_run >> tau_c.
TEST(GyroNoiseMapping, GaussMarkovDriftHasTheWalkLimits) {
  const double sigma = 0.5, tau_c = 1.0e9;  // deg/h, s
  const double run_s = 100.0;
  const auto drift_deg_h = [&](double tau, double run) {
    return map_gyro_noise_model(
               gyro_model({{{"type", "gauss_markov"}, {"sigma", sigma}, {"tau_c", tau}}}), 60.0,
               run, owsg_gyro_ns_ct_terms())
               .terms.drift_rad_s /
           kRadPerSecondPerDegPerHour;
  };
  // K^2 = 2 sigma^2 / tau_c (deg/h)^2 / s: drift^2 = K^2 T_run / 3.
  EXPECT_NEAR(drift_deg_h(tau_c, run_s), std::sqrt(2.0 * sigma * sigma / tau_c * run_s / 3.0),
              1e-6 * drift_deg_h(tau_c, run_s));
  // tau_c = 1 s over 1e6 s: drift^2 T_run^2 = 2 sigma^2 tau_c (T_run - 3/2 tau_c).
  const double short_tau = 1.0, long_run = 1.0e6;
  EXPECT_NEAR(drift_deg_h(short_tau, long_run),
              std::sqrt(2.0 * sigma * sigma * short_tau * (long_run - 1.5 * short_tau)) / long_run,
              1e-9);
}

TEST(GyroNoiseMapping, QuantizationAddsToTheGyrocompassNoise) {
  // Q = 3600 arcsec = 1 deg: 2 Q^2 / T^2 with T = 36 s = 0.01 h gives sqrt(2) * 100 deg/h.
  const MappedGyroTerms mapped = map_gyro_noise_model(
      gyro_model({{{"type", "quantization"}, {"Q", 3600.0}}, {{"type", "rate_ramp"}, {"R", 0.01}}}),
      36.0, 0.0, owsg_gyro_ns_ct_terms());
  EXPECT_NEAR(mapped.terms.noise_rad_s / kRadPerSecondPerDegPerHour, std::sqrt(2.0) * 100.0, 1e-9);
  ASSERT_EQ(mapped.ignored_terms.size(), 1u);
  EXPECT_EQ(mapped.ignored_terms[0], "rate_ramp");
}

TEST(GyroNoiseMapping, UnitsAreConvertedFromTheModelsUnit) {
  const NoiseModel in_rad =
      noise_model_from_json({{"units", "rad/s"},
                             {"rate_hz", 100},
                             {"terms", {{{"type", "angle_random_walk"}, {"N", 0.01}}}}});
  const NoiseModel in_deg = gyro_model({{{"type", "angle_random_walk"}, {"N", 0.01}}});
  EXPECT_NEAR(map_gyro_noise_model(in_rad, 60, 0, owsg_gyro_ns_ct_terms()).terms.noise_rad_s,
              map_gyro_noise_model(in_deg, 60, 0, owsg_gyro_ns_ct_terms()).terms.noise_rad_s,
              1e-15);
}

TEST(GyroNoiseMapping, RejectsWhatItCannotMap) {
  const NoiseModel accel =
      noise_model_from_json({{"units", "m/s^2"},
                             {"rate_hz", 100},
                             {"terms", {{{"type", "angle_random_walk"}, {"N", 0.01}}}}});
  EXPECT_THROW(map_gyro_noise_model(accel, 60, 0, owsg_gyro_ns_ct_terms()), std::invalid_argument);
  const NoiseModel gyro = gyro_model({{{"type", "angle_random_walk"}, {"N", 0.01}}});
  EXPECT_THROW(map_gyro_noise_model(gyro, 0, 0, owsg_gyro_ns_ct_terms()), std::invalid_argument);
  EXPECT_THROW(map_gyro_noise_model(gyro, 60, -1, owsg_gyro_ns_ct_terms()), std::invalid_argument);
}

TEST(GyroNoiseMapping, RunTimeIsTheContinuousPartOverTheSpeed) {
  ContinuousGyroTerms terms = owsg_gyro_ns_ct_terms();
  terms.running_speed_m_s = 0.5;
  const std::vector<ListingStation> stations = {
      {0, 0, 0}, {100, 10 * kRadPerDeg, 0}, {200, 20 * kRadPerDeg, 0}, {400, 30 * kRadPerDeg, 0}};
  EXPECT_DOUBLE_EQ(continuous_run_time_s(stations, terms), 400.0);  // 200 m from 200 m MD
  const std::vector<ListingStation> vertical = {{0, 0, 0}, {100, 0, 0}};
  EXPECT_EQ(continuous_run_time_s(vertical, terms), 0.0);
}

TEST(ToolModels, GyroModelTotalIsTheSumOfItsSources) {
  WellParameters well;
  well.latitude_rad = 60.0 * kRadPerDeg;
  const std::vector<ListingStation> stations = {{0, 0, 0},
                                                {300, 10 * kRadPerDeg, 1.0},
                                                {600, 20 * kRadPerDeg, 1.0},
                                                {900, 30 * kRadPerDeg, 1.0}};
  const SurveyCovariance covariance =
      tool_model_covariance(kGyroNsCtModelName, stations, well, owsg_gyro_ns_ct_terms());
  ASSERT_EQ(covariance.sources.size(), 19u);
  EXPECT_EQ(covariance.sources[15].code, "GXY-RN");
  for (std::size_t k = 0; k < stations.size(); ++k) {
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    for (const SourceCovariance& source : covariance.sources) sum += source.nev_m2[k];
    EXPECT_TRUE(sum.isApprox(covariance.total_nev_m2[k]) || sum.isZero());
  }
  EXPECT_GT(covariance.total_nev_m2.back().trace(), 0.0);
  EXPECT_THROW(check_tool_model_name("gyro_free", "--model"), ConfigError);
  EXPECT_NO_THROW(check_tool_model_name("mwd_rev4", "--model"));
  EXPECT_NO_THROW(check_tool_model_name("gyro_ns", "--model"));
  EXPECT_NO_THROW(check_tool_model_name("gyro_mwd", "--model"));
}

}  // namespace
}  // namespace stochnav::survey_error
