#include "stochnav/experiment/survey.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "client_minimum_curvature.hpp"
#include "stochnav/core/angles.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "survey/survey_plot.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

SurveyStation station_at(double md_m, double inclination_deg, double azimuth_deg) {
  SurveyStation station;
  station.md_m = md_m;
  station.inclination_deg = inclination_deg;
  station.azimuth_deg = azimuth_deg;
  return station;
}

/// Unit direction of the hole in (north, east, down).
Eigen::Vector3d direction_ned(double inclination_deg, double azimuth_deg) {
  const double i = inclination_deg * kRadPerDeg;
  const double a = azimuth_deg * kRadPerDeg;
  return {std::sin(i) * std::cos(a), std::sin(i) * std::sin(a), std::cos(i)};
}

/// (inclination, azimuth) in degrees of a unit (north, east, down) direction.
std::pair<double, double> angles_deg(const Eigen::Vector3d& direction_ned) {
  const double inclination = std::acos(std::clamp(direction_ned.z(), -1.0, 1.0));
  double azimuth = std::atan2(direction_ned.y(), direction_ned.x());
  if (azimuth < 0.0) azimuth += 2.0 * std::numbers::pi;
  return {inclination * kDegPerRad, azimuth * kDegPerRad};
}

// ---------------------------------------------------------------- minimum curvature

TEST(MinimumCurvature, VerticalHoleDescendsByTheMeasuredDepth) {
  const std::vector<SurveyStation> stations = {
      station_at(150.0, 0.0, 0.0), station_at(250.0, 0.0, 0.0), station_at(400.0, 0.0, 0.0)};
  const auto path = minimum_curvature_path(stations, 50.0);
  ASSERT_EQ(path.size(), stations.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    EXPECT_DOUBLE_EQ(path[i].md_m, stations[i].md_m);
    EXPECT_NEAR(path[i].tvd_m, stations[i].md_m - 50.0, 1e-12);
    EXPECT_EQ(path[i].north_m, 0.0);
    EXPECT_EQ(path[i].east_m, 0.0);
  }
}

TEST(MinimumCurvature, StraightHoldFollowsTheClosedForm) {
  // The tie-on takes the first station's attitude, so the whole path is one straight line.
  const double inclination = 30.0 * kRadPerDeg;
  const double azimuth = 60.0 * kRadPerDeg;
  const double tie_on_md_m = 1200.0;
  std::vector<SurveyStation> stations;
  for (double md : {1230.0, 1275.5, 1301.0, 1500.0, 2017.25}) {
    stations.push_back(station_at(md, 30.0, 60.0));
  }
  const auto path = minimum_curvature_path(stations, tie_on_md_m);
  ASSERT_EQ(path.size(), stations.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    const double along_m = stations[i].md_m - tie_on_md_m;
    EXPECT_NEAR(path[i].north_m, along_m * std::sin(inclination) * std::cos(azimuth), 1e-9);
    EXPECT_NEAR(path[i].east_m, along_m * std::sin(inclination) * std::sin(azimuth), 1e-9);
    EXPECT_NEAR(path[i].tvd_m, along_m * std::cos(inclination), 1e-9);
  }
}

TEST(MinimumCurvature, CircularBuildIsExact) {
  // A build of 3 deg / 30 m from vertical to horizontal at azimuth 45 deg, below a vertical
  // section of 100 m: minimum curvature assumes circular arcs, so it is exact here.
  const double radius_m = 30.0 / (3.0 * kRadPerDeg);
  const double kickoff_md_m = 1000.0;
  std::vector<SurveyStation> stations;
  for (double inclination_deg = 0.0; inclination_deg <= 90.0; inclination_deg += 2.5) {
    stations.push_back(
        station_at(kickoff_md_m + radius_m * inclination_deg * kRadPerDeg, inclination_deg, 45.0));
  }
  const auto path = minimum_curvature_path(stations, kickoff_md_m - 100.0);
  ASSERT_EQ(path.size(), stations.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    const double inclination = stations[i].inclination_deg * kRadPerDeg;
    const double horizontal_m = radius_m * (1.0 - std::cos(inclination));
    const double tvd_m = 100.0 + radius_m * std::sin(inclination);
    const double tolerance_m = 1e-9 * (radius_m + 100.0);
    EXPECT_NEAR(path[i].north_m, horizontal_m * std::cos(45.0 * kRadPerDeg), tolerance_m) << i;
    EXPECT_NEAR(path[i].east_m, horizontal_m * std::sin(45.0 * kRadPerDeg), tolerance_m) << i;
    EXPECT_NEAR(path[i].tvd_m, tvd_m, tolerance_m) << i;
  }
  EXPECT_NEAR(path.back().tvd_m, 100.0 + radius_m, 1e-9 * radius_m);
}

TEST(MinimumCurvature, ThreeDimensionalArcMatchesIntegratedSlerp) {
  // A constant-curvature arc turning both inclination and azimuth: its direction is the slerp
  // of the end directions. Integrate the direction numerically (Simpson) and compare.
  const Eigen::Vector3d start = direction_ned(20.0, 30.0);
  const Eigen::Vector3d end = direction_ned(75.0, 140.0);
  const double dogleg = std::acos(start.dot(end));
  const double arc_length_m = 400.0;
  const auto direction_at = [&](double fraction) -> Eigen::Vector3d {
    return (std::sin((1.0 - fraction) * dogleg) * start + std::sin(fraction * dogleg) * end) /
           std::sin(dogleg);
  };
  const auto integrated_position = [&](double fraction) -> Eigen::Vector3d {
    constexpr int kIntervals = 2000;  // even, for Simpson's rule
    const double h = fraction / kIntervals;
    Eigen::Vector3d sum = direction_at(0.0) + direction_at(fraction);
    for (int k = 1; k < kIntervals; ++k) sum += (k % 2 == 1 ? 4.0 : 2.0) * direction_at(k * h);
    return sum * h / 3.0 * arc_length_m;
  };

  const double tie_on_md_m = 500.0;
  std::vector<SurveyStation> stations;
  std::vector<double> fractions;
  for (double fraction : {0.0, 0.1, 0.35, 0.5, 0.8, 1.0}) {
    const auto [inclination_deg, azimuth_deg] = angles_deg(direction_at(fraction));
    stations.push_back(
        station_at(tie_on_md_m + fraction * arc_length_m, inclination_deg, azimuth_deg));
    fractions.push_back(fraction);
  }
  const auto path = minimum_curvature_path(stations, tie_on_md_m);
  ASSERT_EQ(path.size(), stations.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Eigen::Vector3d expected = integrated_position(fractions[i]);
    EXPECT_NEAR(path[i].north_m, expected.x(), 1e-6) << i;
    EXPECT_NEAR(path[i].east_m, expected.y(), 1e-6) << i;
    EXPECT_NEAR(path[i].tvd_m, expected.z(), 1e-6) << i;
  }
}

TEST(MinimumCurvature, TinyDoglegStaysFiniteAndStraight) {
  const std::vector<SurveyStation> stations = {station_at(10.0, 45.0, 90.0),
                                               station_at(110.0, 45.0 + 1e-11, 90.0)};
  const auto path = minimum_curvature_path(stations, 0.0);
  ASSERT_EQ(path.size(), 2u);
  EXPECT_NEAR(path[1].east_m, 110.0 * std::sin(45.0 * kRadPerDeg), 1e-9);
  EXPECT_NEAR(path[1].tvd_m, 110.0 * std::cos(45.0 * kRadPerDeg), 1e-9);
  EXPECT_NEAR(path[1].north_m, 0.0, 1e-9);
}

TEST(MinimumCurvature, TieOnDirectionStartsTheFirstSegment) {
  // From a vertical tie-on, a circular build to 30 deg over the first 300 m of MD (the arc of
  // radius R = 300 / (pi/6)): minimum curvature is exact on it. Without the tie-on's
  // direction the first segment is straight along the station's 30 deg instead.
  const double arc_m = 300.0;
  const double radius_m = arc_m / (30.0 * kRadPerDeg);
  const std::vector<SurveyStation> stations = {station_at(1000.0 + arc_m, 30.0, 90.0)};
  const auto arc = minimum_curvature_path(stations, 1000.0, SurveyDirection{0.0, 0.0});
  ASSERT_EQ(arc.size(), 1u);
  EXPECT_NEAR(arc[0].east_m, radius_m * (1.0 - std::cos(30.0 * kRadPerDeg)), 1e-9);
  EXPECT_NEAR(arc[0].north_m, 0.0, 1e-9);
  EXPECT_NEAR(arc[0].tvd_m, radius_m * std::sin(30.0 * kRadPerDeg), 1e-9);
  const auto straight = minimum_curvature_path(stations, 1000.0);
  EXPECT_NEAR(straight[0].east_m, arc_m * std::sin(30.0 * kRadPerDeg), 1e-9);
}

TEST(MinimumCurvature, NoStationsGiveNoPoints) {
  EXPECT_TRUE(minimum_curvature_path({}, 100.0).empty());
}

// ---------------------------------------------------------------- recorder

const SurveyTieOn kTieOn{0.6, -1.7, 350.0, 1000.0};

/// A state at (north, east, tvd) metres from kTieOn, in the tie-on frame's linearisation.
NavState state_at(double t_s, double north_m, double east_m, double tvd_m,
                  const MwdAttitude& attitude) {
  const EarthRadii radii = earth_radii(kTieOn.latitude_rad);
  NavState state;
  state.t_s = t_s;
  state.latitude_rad = kTieOn.latitude_rad + north_m / (radii.meridian_m + kTieOn.height_m);
  state.longitude_rad = kTieOn.longitude_rad + east_m / ((radii.transverse_m + kTieOn.height_m) *
                                                         std::cos(kTieOn.latitude_rad));
  state.height_m = kTieOn.height_m - tvd_m;
  state.q_nb = quaternion_from_mwd(attitude);
  return state;
}

MwdAttitude attitude_deg(double inclination, double toolface, double azimuth) {
  return {inclination * kRadPerDeg, toolface * kRadPerDeg, azimuth * kRadPerDeg};
}

/// Position variances E 4, N 9, U 16 m^2 with an E-N covariance of 1.5 m^2; attitude 1 mrad.
Eigen::Matrix<double, 9, 9> known_covariance() {
  Eigen::Matrix<double, 9, 9> p = Eigen::Matrix<double, 9, 9>::Identity() * 0.01;
  p(0, 0) = 4.0;
  p(1, 1) = 9.0;
  p(2, 2) = 16.0;
  p(0, 1) = p(1, 0) = 1.5;
  p.block<3, 3>(6, 6) = Eigen::Matrix3d::Identity() * 1e-6;
  return p;
}

/// One epoch of a synthetic run: where the tool is and whether it is stationary.
struct Epoch {
  double t_s;
  double tvd_m;
  bool stationary;
};

/// Connections at t = 0-2, 6-8 and 11-12 (the record ends stationary); between them the tool
/// moves straight down by 5 m per epoch.
std::vector<Epoch> three_connections() {
  std::vector<Epoch> epochs;
  double tvd_m = 0.0;
  for (int t = 0; t <= 12; ++t) {
    const bool stationary = t <= 2 || (t >= 6 && t <= 8) || t >= 11;
    if (!stationary) tvd_m += 5.0;
    epochs.push_back({static_cast<double>(t), tvd_m, stationary});
  }
  return epochs;
}

TEST(SurveyRecorder, StationsAtTheLastStationaryEpochWithGivenDepth) {
  SurveyRecorder recorder(kTieOn);
  const auto covariance = known_covariance();
  for (const Epoch& e : three_connections()) {
    recorder.observe(state_at(e.t_s, 0.0, 0.0, e.tvd_m, attitude_deg(2.0, 10.0, 50.0)), covariance,
                     e.stationary, 1000.0 + 10.0 * e.t_s, nullptr);
  }
  ASSERT_EQ(recorder.stations().size(), 2u);  // the last connection is still open
  recorder.finish();
  const auto& stations = recorder.stations();
  ASSERT_EQ(stations.size(), 3u);
  const double expected_t[] = {2.0, 8.0, 12.0};
  // The MD is the mean of the span's readings (t = 0-2, 6-8, 11-12): at its mean time here.
  const double mean_span_t[] = {1.0, 7.0, 11.5};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(stations[i].t_s, expected_t[i]);
    EXPECT_DOUBLE_EQ(stations[i].md_m, 1000.0 + 10.0 * mean_span_t[i]);
    EXPECT_TRUE(std::isnan(stations[i].md_sigma_m)) << "no stated depth sigma";
  }
  EXPECT_NEAR(stations[0].tvd_m, 0.0, 1e-6);
  EXPECT_NEAR(stations[1].tvd_m, 15.0, 1e-6);
  EXPECT_NEAR(stations[2].tvd_m, 25.0, 1e-6);
  EXPECT_NEAR(stations[1].inclination_deg, 2.0, 1e-9);
  EXPECT_NEAR(stations[1].azimuth_deg, 50.0, 1e-7);
  EXPECT_NEAR(stations[1].toolface_deg, 10.0, 1e-7);
  EXPECT_TRUE(recorder.station_errors().empty());
}

// A ZUPT rejected in the middle of a connection splits its stationary span in two: one station
// still, the later span's (after more ZUPTs), with its error, and MD strictly increasing from
// station to station although the tally read 5 cm less after the gap (it went backwards:
// 1429.989 -> 1429.916 m in the run).
TEST(SurveyRecorder, OneStationPerConnectionWhenAZuptIsRejectedInIt) {
  SurveyRecorder recorder(kTieOn);
  const auto covariance = known_covariance();
  struct Step {
    double t_s, tvd_m, md_m;
    bool stationary;
  };
  const Step steps[] = {{0, 0, 1000.00, true},  {1, 0, 1000.00, true}, {2, 0, 999.95, false},
                        {3, 0, 999.95, true},   {4, 0, 999.95, true},  {5, 10, 1010.0, false},
                        {6, 20, 1020.0, false}, {7, 20, 1020.0, true}};
  for (const Step& step : steps) {
    const NavState state = state_at(step.t_s, 0.0, 0.0, step.tvd_m, attitude_deg(2.0, 0.0, 50.0));
    recorder.observe(state, covariance, step.stationary, step.md_m, &state);
  }
  recorder.finish();
  const auto& stations = recorder.stations();
  ASSERT_EQ(stations.size(), 2u);
  EXPECT_EQ(stations[0].t_s, 4.0) << "the connection's last stationary epoch";
  EXPECT_DOUBLE_EQ(stations[0].md_m, 999.95);
  EXPECT_EQ(stations[1].t_s, 7.0);
  ASSERT_EQ(recorder.station_errors().size(), 2u);
  EXPECT_EQ(recorder.station_errors()[0].t_s, 4.0);
  for (std::size_t i = 1; i < stations.size(); ++i) {
    EXPECT_GT(stations[i].md_m, stations[i - 1].md_m + SurveyRecorder::kSameConnectionMd_m);
  }
}

// The tally smoother (experiment/tally_smoother.hpp): a station's MD is the mean of its
// connection's readings, its sigma sqrt(random^2 / n + (scale dMD)^2); readings of a span
// before the tool moved do not leak into the next one.
TEST(SurveyRecorder, StationDepthIsTheMeanOfItsSpanWithTheStatedSigma) {
  const DepthReadingSigma stated{0.05, 1e-3};
  SurveyRecorder recorder(kTieOn, std::nullopt, stated);
  const auto covariance = known_covariance();
  struct Step {
    double tvd_m, md_m;
    bool stationary;
  };
  const Step steps[] = {{0, 1000.02, true}, {0, 999.98, true},   {0, 1000.06, true},
                        {0, 999.94, true},  {15, 1015.0, false}, {30, 1030.0, false},
                        {30, 1030.1, true}, {30, 1029.9, true},  {30, std::nan(""), true}};
  double t_s = 0.0;
  for (const Step& step : steps) {
    const NavState state = state_at(t_s++, 0.0, 0.0, step.tvd_m, attitude_deg(0.0, 0.0, 0.0));
    recorder.observe(state, covariance, step.stationary,
                     std::isnan(step.md_m) ? std::nullopt : std::optional<double>(step.md_m),
                     nullptr);
  }
  recorder.finish();
  const auto& stations = recorder.stations();
  ASSERT_EQ(stations.size(), 2u);
  EXPECT_NEAR(stations[0].md_m, 1000.0, 1e-12);
  EXPECT_NEAR(stations[0].md_sigma_m, 0.05 / 2.0, 1e-12);  // 4 readings at the tie-on's MD
  EXPECT_EQ(stations[1].t_s, 8.0) << "the last stationary epoch, without a reading";
  EXPECT_NEAR(stations[1].md_m, 1030.0, 1e-12);
  EXPECT_NEAR(stations[1].md_sigma_m, std::hypot(0.05 / std::sqrt(2.0), 1e-3 * 30.0), 1e-12);
}

TEST(StationaryDepthMean, MeanAboutTheFirstReadingAndItsSigma) {
  StationaryDepthMean mean;
  EXPECT_EQ(mean.count(), 0u);
  EXPECT_TRUE(std::isnan(mean.mean_m()));
  EXPECT_TRUE(std::isnan(mean.sigma_m({0.05, 1e-3}, 0.0)));
  // Depths of 5 km read to 0.1 mm: the mean keeps the tenths of a millimetre.
  for (double reading : {5000.0001, 5000.0003, std::nan(""), 5000.0002}) mean.add(reading);
  EXPECT_EQ(mean.count(), 3u) << "a non-finite reading is ignored";
  EXPECT_NEAR(mean.mean_m(), 5000.0002, 1e-10);
  EXPECT_NEAR(mean.sigma_m({0.03, 0.0}, 0.0), 0.03 / std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(mean.sigma_m({0.0, 2e-3}, 4000.0), 2e-3 * 1000.0002, 1e-12);
  mean.reset();
  EXPECT_EQ(mean.count(), 0u);
  mean.add(12.0);
  EXPECT_EQ(mean.mean_m(), 12.0);
}

TEST(SurveyRecorder, DepthFromTheInsPathWhenNotGiven) {
  SurveyRecorder recorder(kTieOn);
  const auto covariance = known_covariance();
  for (const Epoch& e : three_connections()) {
    // Moving epochs also step 2 m north: each step is sqrt(5^2 + 2^2) m of path.
    const double north_m = e.tvd_m * 0.4;
    recorder.observe(state_at(e.t_s, north_m, 0.0, e.tvd_m, attitude_deg(20.0, 0.0, 0.0)),
                     covariance, e.stationary, std::nullopt, nullptr);
  }
  recorder.finish();
  const auto& stations = recorder.stations();
  ASSERT_EQ(stations.size(), 3u);
  const double step_m = std::hypot(5.0, 2.0);
  EXPECT_NEAR(stations[0].md_m, kTieOn.measured_depth_m, 1e-6);
  EXPECT_NEAR(stations[1].md_m, kTieOn.measured_depth_m + 3.0 * step_m, 1e-6);
  EXPECT_NEAR(stations[2].md_m, kTieOn.measured_depth_m + 5.0 * step_m, 1e-6);
  ASSERT_FALSE(recorder.ins_path().empty());
  EXPECT_NEAR(recorder.ins_path().back().md_m, kTieOn.measured_depth_m + 5.0 * step_m, 1e-6);
}

TEST(SurveyRecorder, NoStationWithoutAConnection) {
  SurveyRecorder recorder(kTieOn);
  for (int t = 0; t < 5; ++t) {
    recorder.observe(state_at(t, 0.0, 0.0, t, attitude_deg(0.0, 0.0, 0.0)), known_covariance(),
                     false, std::nullopt, nullptr);
  }
  recorder.finish();
  EXPECT_TRUE(recorder.stations().empty());
  EXPECT_EQ(recorder.ins_path().size(), 5u);
}

TEST(SurveyRecorder, PositionSignsAndSigmas) {
  SurveyRecorder recorder(kTieOn);
  // 30 m north (higher latitude), 20 m west, 100 m below the tie-on.
  recorder.observe(state_at(7.0, 30.0, -20.0, 100.0, attitude_deg(30.0, 45.0, 60.0)),
                   known_covariance(), true, std::nullopt, nullptr);
  recorder.finish();
  ASSERT_EQ(recorder.stations().size(), 1u);
  const SurveyStation& s = recorder.stations().front();
  EXPECT_NEAR(s.north_m, 30.0, 1e-6);
  EXPECT_NEAR(s.east_m, -20.0, 1e-6);
  EXPECT_NEAR(s.tvd_m, 100.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.north_sigma_m, 3.0);
  EXPECT_DOUBLE_EQ(s.east_sigma_m, 2.0);
  EXPECT_DOUBLE_EQ(s.tvd_sigma_m, 4.0);
  Eigen::Matrix2d expected_ne;
  expected_ne << 9.0, 1.5, 1.5, 4.0;
  EXPECT_EQ(s.horizontal_covariance_m2, expected_ne);
  // Isotropic 1 mrad tilt: inclination moves 1:1 with a tilt across the hole; the azimuth
  // moves with the vertical component and cot(I) times the along-azimuth tilt, so
  // sigma_A = sigma / sin(I) = 2 mrad at I = 30 deg.
  EXPECT_NEAR(s.inclination_sigma_deg, 1e-3 * kDegPerRad, 1e-6);
  EXPECT_NEAR(s.azimuth_sigma_deg, 2e-3 * kDegPerRad, 1e-6);
}

TEST(SurveyRecorder, LongitudeDifferenceWrapsAcrossTheDateLine) {
  const SurveyTieOn tie_on{0.0, std::numbers::pi - 1e-6, 0.0, 0.0};
  SurveyRecorder recorder(tie_on);
  NavState state;
  state.latitude_rad = 0.0;
  state.longitude_rad = -std::numbers::pi + 1e-6;  // 2e-6 rad east of the tie-on
  recorder.observe(state, known_covariance(), true, 0.0, nullptr);
  recorder.finish();
  ASSERT_EQ(recorder.stations().size(), 1u);
  EXPECT_NEAR(recorder.stations()[0].east_m, 2e-6 * earth_radii(0.0).transverse_m, 1e-6);
}

TEST(SurveyRecorder, ErrorsOnlyForStationsWithTruth) {
  SurveyRecorder recorder(kTieOn);
  const auto covariance = known_covariance();
  for (const Epoch& e : three_connections()) {
    const NavState estimate = state_at(e.t_s, 1.0, 2.0, e.tvd_m, attitude_deg(40.0, 100.0, 80.0));
    // Truth: 0.5 m further north, 0.2 m shallower, 0.1 deg more inclined, 0.3 deg more azimuth.
    const NavState truth =
        state_at(e.t_s, 1.5, 2.0, e.tvd_m - 0.2, attitude_deg(40.1, 100.0, 80.3));
    // Truth is known only up to t = 9: the last connection has none.
    recorder.observe(estimate, covariance, e.stationary, std::nullopt,
                     e.t_s <= 9.0 ? &truth : nullptr);
  }
  recorder.finish();
  ASSERT_EQ(recorder.stations().size(), 3u);
  const auto& errors = recorder.station_errors();
  ASSERT_EQ(errors.size(), 2u);
  for (std::size_t i = 0; i < errors.size(); ++i) {
    const SurveyStation& station = recorder.stations()[i];
    EXPECT_EQ(errors[i].t_s, station.t_s);
    EXPECT_EQ(errors[i].md_m, station.md_m);
    EXPECT_EQ(errors[i].north_sigma_m, station.north_sigma_m);
    EXPECT_EQ(errors[i].azimuth_sigma_deg, station.azimuth_sigma_deg);
    EXPECT_NEAR(errors[i].north_m, -0.5, 1e-6);
    EXPECT_NEAR(errors[i].east_m, 0.0, 1e-6);
    EXPECT_NEAR(errors[i].tvd_m, 0.2, 1e-6);
    EXPECT_NEAR(errors[i].inclination_deg, -0.1, 1e-7);
    EXPECT_NEAR(errors[i].azimuth_deg, -0.3, 1e-7);
    EXPECT_FALSE(std::isnan(errors[i].toolface_deg));
  }
}

TEST(SurveyRecorder, AzimuthUndefinedNearVertical) {
  SurveyRecorder recorder(kTieOn);
  const NavState estimate = state_at(0.0, 0.0, 0.0, 50.0, attitude_deg(0.4, 20.0, 100.0));
  const NavState truth = state_at(0.0, 0.0, 0.0, 50.0, attitude_deg(0.5, 20.0, 110.0));
  recorder.observe(estimate, known_covariance(), true, 1050.0, &truth);
  recorder.finish();
  ASSERT_EQ(recorder.station_errors().size(), 1u);
  const SurveyStation& error = recorder.station_errors().front();
  EXPECT_TRUE(std::isnan(error.azimuth_deg));
  EXPECT_TRUE(std::isnan(error.toolface_deg));
  EXPECT_NEAR(error.inclination_deg, -0.1, 1e-7);
  EXPECT_TRUE(std::isnan(recorder.stations().front().azimuth_sigma_deg));
  EXPECT_FALSE(std::isnan(recorder.stations().front().inclination_sigma_deg));
}

TEST(SurveyRecorder, InsPathIsThinnedEvenlyAndKeepsTheLatestPoint) {
  SurveyRecorder recorder(kTieOn);
  constexpr int kEpochs = 10003;  // the last epoch falls between strides
  for (int k = 0; k < kEpochs; ++k) {
    recorder.observe(state_at(k, 0.0, 0.0, k, attitude_deg(0.0, 0.0, 0.0)), known_covariance(),
                     false, std::nullopt, nullptr);
    ASSERT_LE(recorder.ins_path().size(), 4000u);
    ASSERT_NEAR(recorder.ins_path().back().tvd_m, k, 1e-6);
  }
  const auto& path = recorder.ins_path();
  EXPECT_GE(path.size(), 1000u);
  EXPECT_NEAR(path.front().md_m, kTieOn.measured_depth_m, 1e-9);
  EXPECT_NEAR(path.front().tvd_m, 0.0, 1e-9);
  // Every point but the latest lies on one stride.
  const double stride_m = path[1].tvd_m - path[0].tvd_m;
  EXPECT_GT(stride_m, 1.0);
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    EXPECT_NEAR(path[i].tvd_m - path[i - 1].tvd_m, stride_m, 1e-6) << i;
  }
  EXPECT_LE(path.back().tvd_m - path[path.size() - 2].tvd_m, stride_m + 1e-6);
  EXPECT_NEAR(path.back().md_m, kTieOn.measured_depth_m + (kEpochs - 1), 1e-5);
}

// ---------------------------------------------------------------- files

std::vector<std::string> read_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::size_t files_in(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir),
                                                std::filesystem::directory_iterator()));
}

/// Three stations, the first near vertical, with truth at all of them when `with_truth`.
SurveyRecorder recorded_run(bool with_truth) {
  SurveyRecorder recorder(kTieOn);
  for (const Epoch& e : three_connections()) {
    const double inclination = e.t_s < 3.0 ? 0.3 : 3.0 * e.t_s;
    const NavState estimate = state_at(e.t_s, 0.1 * e.tvd_m, 0.05 * e.tvd_m, e.tvd_m,
                                       attitude_deg(inclination, 0.0, 30.0));
    recorder.observe(estimate, known_covariance(), e.stationary, std::nullopt,
                     with_truth ? &estimate : nullptr);
  }
  recorder.finish();
  return recorder;
}

// DESIGN.md's columns, then the station QC's (experiment/station_qc.hpp).
constexpr const char* kSurveyHeader =
    "t_s,md_m,inclination_deg,azimuth_deg,toolface_deg,tvd_m,north_m,east_m,"
    "inclination_sigma_deg,azimuth_sigma_deg,north_sigma_m,east_sigma_m,tvd_sigma_m,"
    "qc_static_s,qc_inclination_deg,qc_inclination_sigma_deg,qc_azimuth_deg,"
    "qc_azimuth_sigma_deg,qc_gravity_total_m_s2,qc_gravity_model_m_s2,qc_gravity_sigma_m_s2,"
    "qc_earth_rate_total_deg_h,qc_earth_rate_sigma_deg_h,qc_inclination_sigmas,"
    "qc_azimuth_sigmas,qc_flag";
// survey.csv only: the listing's (experiment/survey_listing.hpp), after the QC's.
constexpr const char* kListingColumns =
    ",dls_deg_30m,build_deg_30m,turn_deg_30m,closure_m,closure_azimuth_deg,vertical_section_m,"
    "ne_m2,nv_m2,ev_m2,ellipse_semi_major_m,ellipse_semi_minor_m,ellipse_azimuth_deg,"
    "tvd_below_datum_m,tvdss_m,azimuth_defined,gyro_toolface,mc_north_m,mc_east_m,mc_tvd_m,"
    "md_sigma_m,station_type,grid_azimuth_deg,highside_sigma_m,lateral_sigma_m,alonghole_sigma_m,"
    "map_easting_m,map_northing_m";

// The first `count` cells of a CSV row.
std::string first_cells(const std::string& row, int count) {
  std::size_t end = 0;
  for (int i = 0; i < count && end != std::string::npos; ++i) end = row.find(',', end + (i > 0));
  return row.substr(0, end);
}

TEST(SurveyFiles, AppearOnlyOnCommit) {
  const testing::TempDir dir;
  const SurveyRecorder recorder = recorded_run(true);
  auto files = write_survey_files(recorder, kTieOn, dir.path(), false);
  ASSERT_EQ(files.size(), 4u);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "survey.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "trajectory.xml"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "survey_errors.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "well_path.csv"));
  EXPECT_EQ(files_in(dir.path()), 4u);  // the temporaries
  for (auto& file : files) file->commit();
  files.clear();
  EXPECT_EQ(files_in(dir.path()), 4u);

  const auto survey = read_lines(dir.path() / "survey.csv");
  ASSERT_EQ(survey.size(), 5u);  // the tie-on row and three stations
  EXPECT_EQ(survey[0], std::string(kSurveyHeader) + kListingColumns);
  // The tie-on without a recorded start: its MD at (0, 0, 0), attitude and sigmas unknown.
  EXPECT_EQ(first_cells(survey[1], 13), "nan,1000,nan,nan,nan,0,0,0,nan,nan,nan,nan,nan")
      << survey[1];
  EXPECT_NE(survey[1].find(",0,0,0.000000,0.000000,0.000000,0,tie_on,nan,nan,nan,nan"),
            std::string::npos)
      << survey[1];
  for (std::size_t i = 2; i < survey.size(); ++i) {
    EXPECT_NE(survey[i].find(",survey,nan,"), std::string::npos) << survey[i];
  }
  // The near-vertical first station has no azimuth sigma.
  EXPECT_NE(first_cells(survey[2], 13).find(",nan,"), std::string::npos) << survey[2];
  EXPECT_EQ(first_cells(survey[3], 13).find("nan"), std::string::npos) << survey[3];
  // 9 significant digits: the time and depth read back to 1e-8 relative.
  std::istringstream row(survey[3]);
  std::string t, md;
  std::getline(row, t, ',');
  std::getline(row, md, ',');
  EXPECT_EQ(std::stod(t), recorder.stations()[1].t_s);
  EXPECT_NEAR(std::stod(md), recorder.stations()[1].md_m, 1e-8 * recorder.stations()[1].md_m);

  const auto errors = read_lines(dir.path() / "survey_errors.csv");
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_EQ(errors[0], kSurveyHeader);

  const auto well_path = read_lines(dir.path() / "well_path.csv");
  EXPECT_EQ(well_path[0], "source,md_m,north_m,east_m,tvd_m");
  std::size_t minimum_curvature_rows = 0, ins_rows = 0, truth_rows = 0;
  for (std::size_t i = 1; i < well_path.size(); ++i) {
    if (well_path[i].starts_with("minimum_curvature,")) ++minimum_curvature_rows;
    if (well_path[i].starts_with("ins,")) ++ins_rows;
    if (well_path[i].starts_with("truth,")) ++truth_rows;
  }
  EXPECT_EQ(minimum_curvature_rows, 1u + recorder.stations().size());  // tie-on + stations
  EXPECT_EQ(ins_rows, recorder.ins_path().size());
  EXPECT_EQ(truth_rows, ins_rows) << "truth at every epoch: the true path beside the INS's";
  EXPECT_EQ(well_path.size(), 1u + minimum_curvature_rows + ins_rows + truth_rows);
  EXPECT_EQ(well_path[1], "minimum_curvature,1000,0,0,0");
}

/// survey.csv's columns by name (numbers; "nan" and text as NaN).
std::map<std::string, std::vector<double>> survey_columns(const std::filesystem::path& path) {
  const auto lines = read_lines(path);
  std::map<std::string, std::vector<double>> columns;
  std::vector<std::string> names;
  std::istringstream header(lines.at(0));
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  for (std::size_t row = 1; row < lines.size(); ++row) {
    std::istringstream cells(lines[row]);
    std::string cell;
    for (std::size_t i = 0; i < names.size() && std::getline(cells, cell, ','); ++i) {
      const bool number =
          cell != "nan" && cell.find_first_of("_abcdefghijklmopqrsuvwxyz") == std::string::npos;
      columns[names[i]].push_back(number ? std::stod(cell) : std::nan(""));
    }
  }
  return columns;
}

// Issue #27, "a listing that adds up": a client recomputing minimum curvature from survey.csv's
// md_m, inclination_deg and azimuth_deg (and the tie-on's MD and attitude) gets its mc_*
// columns to 1e-6 m, on a 3-km well of 120 stations turning through every quadrant below a
// tie-on at MD 2500 m: the columns are computed from the numbers as printed.
TEST(SurveyFiles, ClientMinimumCurvatureFromTheListingReproducesItsColumns) {
  SurveyTieOn tie_on = kTieOn;
  tie_on.measured_depth_m = 2500.123456789;
  tie_on.direction = SurveyDirection{12.3456789123, 201.987654321};
  SurveyRecorder recorder(tie_on);
  const auto covariance = known_covariance();
  constexpr int kStations = 120;
  for (int k = 1; k <= kStations; ++k) {
    const double md_m = tie_on.measured_depth_m + 25.0 * k + 0.123456789 * std::sin(k);
    const double inclination_deg = 45.0 + 44.0 * std::sin(0.05 * k) + 1e-7 / 3.0;
    const double azimuth_deg = std::fmod(3.1234567891 * k + 10.0, 360.0);
    const MwdAttitude attitude = attitude_deg(inclination_deg, 0.0, azimuth_deg);
    // A moving epoch then a stationary one: one station per k, at an arbitrary INS position.
    recorder.observe(state_at(2.0 * k, 0.0, 0.0, md_m - 2500.0, attitude), covariance, false,
                     md_m - 10.0, nullptr);
    recorder.observe(state_at(2.0 * k + 1.0, 0.0, 0.0, md_m - 2500.0, attitude), covariance, true,
                     md_m, nullptr);
  }
  recorder.finish();
  ASSERT_EQ(recorder.stations().size(), static_cast<std::size_t>(kStations));
  const testing::TempDir dir;
  auto files = write_survey_files(recorder, tie_on, dir.path(), false);
  for (auto& file : files) file->commit();
  const auto listing = survey_columns(dir.path() / "survey.csv");
  // The tie-on row first (MD and attitude to 9 digits), then the stations.
  const testing::ListedStation listed_tie_on{
      listing.at("md_m")[0], listing.at("inclination_deg")[0], listing.at("azimuth_deg")[0]};
  EXPECT_EQ(listed_tie_on.md_m, 2500.12346);
  EXPECT_EQ(listed_tie_on.inclination_deg, 12.3456789);
  EXPECT_EQ(listed_tie_on.azimuth_deg, 201.987654);
  std::vector<testing::ListedStation> listed;
  for (std::size_t i = 1; i < listing.at("md_m").size(); ++i) {
    listed.push_back(
        {listing.at("md_m")[i], listing.at("inclination_deg")[i], listing.at("azimuth_deg")[i]});
  }
  const auto client = testing::client_minimum_curvature(listed_tie_on, listed);
  ASSERT_EQ(client.size(), static_cast<std::size_t>(kStations));
  double worst_m = 0.0;
  for (std::size_t i = 0; i < client.size(); ++i) {
    worst_m = std::max({worst_m, std::abs(client[i].north_m - listing.at("mc_north_m")[i + 1]),
                        std::abs(client[i].east_m - listing.at("mc_east_m")[i + 1]),
                        std::abs(client[i].tvd_m - listing.at("mc_tvd_m")[i + 1])});
  }
  std::printf("worst client-recomputation difference %.3g m over %d stations, %.0f m of hole\n",
              worst_m, kStations, listed.back().md_m - listed_tie_on.md_m);
  EXPECT_LT(worst_m, 1e-6);
  EXPECT_GT(std::abs(listing.at("mc_east_m").back()) + std::abs(listing.at("mc_north_m").back()),
            100.0)
      << "a well that goes somewhere";
}

// The tie-on row from the navigation's start: the tie-on's MD and direction, the start's
// toolface, (0, 0, 0), the initial covariance's sigmas; and, with a sensor-to-bit offset, the
// projection to the bit after the last station: straight along its attitude, MD + offset.
TEST(SurveyFiles, TieOnRowFirstAndProjectionToTheBitLast) {
  SurveyTieOn tie_on = kTieOn;
  tie_on.direction = SurveyDirection{0.5, 30.0};
  SurveyRecorder recorder(tie_on);
  recorder.record_tie_on(state_at(-5.0, 3.0, 4.0, 5.0, attitude_deg(0.7, 15.0, 31.0)),
                         known_covariance());
  for (const Epoch& e : three_connections()) {
    recorder.observe(
        state_at(e.t_s, 0.0, 0.0, e.tvd_m, attitude_deg(e.t_s < 3.0 ? 0.5 : 40.0, 20.0, 60.0)),
        known_covariance(), e.stationary, 1000.0 + e.tvd_m, nullptr);
  }
  recorder.finish();
  const SurveyStation row = recorder.tie_on_station();
  EXPECT_EQ(row.type, SurveyStationType::kTieOn);
  EXPECT_EQ(row.t_s, -5.0);
  EXPECT_EQ(row.md_m, 1000.0);
  EXPECT_EQ(row.inclination_deg, 0.5) << "the tie-on's direction, not the state's 0.7";
  EXPECT_EQ(row.azimuth_deg, 30.0);
  EXPECT_EQ(row.north_m, 0.0);
  EXPECT_EQ(row.tvd_m, 0.0);
  EXPECT_DOUBLE_EQ(row.north_sigma_m, 3.0);  // known_covariance: N 9, E 4, U 16 m^2
  EXPECT_DOUBLE_EQ(row.tvd_sigma_m, 4.0);
  EXPECT_EQ(row.md_sigma_m, 0.0);

  const testing::TempDir dir;
  SurveyListingOptions options;
  options.sensor_to_bit_m = 12.5;
  auto files = write_survey_files(recorder, tie_on, dir.path(), false, options);
  for (auto& file : files) file->commit();
  const auto listing = survey_columns(dir.path() / "survey.csv");
  const auto lines = read_lines(dir.path() / "survey.csv");
  ASSERT_EQ(lines.size(), 1u + 1u + 3u + 1u);
  EXPECT_NE(lines[1].find(",tie_on,"), std::string::npos);
  EXPECT_NE(lines[4].find(",survey,"), std::string::npos);
  EXPECT_NE(lines[5].find(",projection_to_bit,"), std::string::npos);
  const std::size_t last = 3, bit = 4;  // data rows: the tie-on, three stations, the bit
  EXPECT_NEAR(listing.at("md_m")[bit], listing.at("md_m")[last] + 12.5, 1e-6);
  const double along = 12.5;
  const double inclination = 40.0 * kRadPerDeg, azimuth = 60.0 * kRadPerDeg;
  for (const auto& [column, component] :
       {std::pair{"north_m", std::sin(inclination) * std::cos(azimuth)},
        std::pair{"east_m", std::sin(inclination) * std::sin(azimuth)},
        std::pair{"tvd_m", std::cos(inclination)}}) {
    EXPECT_NEAR(listing.at(column)[bit] - listing.at(column)[last], along * component, 1e-6)
        << column;
    const std::string mc = std::string("mc_") + column;
    EXPECT_NEAR(listing.at(mc)[bit] - listing.at(mc)[last], along * component, 2e-6) << mc;
  }
  EXPECT_NEAR(listing.at("dls_deg_30m")[bit], 0.0, 1e-9) << "straight: no dogleg";
  EXPECT_EQ(listing.at("inclination_sigma_deg")[bit], listing.at("inclination_sigma_deg")[last]);
  EXPECT_TRUE(std::isnan(listing.at("qc_flag")[bit]));
  // The tie-on row: no rates, the origin of closure, vertical section and minimum curvature.
  EXPECT_TRUE(std::isnan(listing.at("dls_deg_30m")[0]));
  EXPECT_EQ(listing.at("closure_m")[0], 0.0);
  EXPECT_EQ(listing.at("mc_tvd_m")[0], 0.0);
  // known_covariance's [[9, 1.5], [1.5, 4]] m^2: major eigenvalue 6.5 + hypot(2.5, 1.5).
  EXPECT_NEAR(listing.at("ellipse_semi_major_m")[0],
              std::sqrt(-2.0 * std::log(0.05)) * std::sqrt(6.5 + std::hypot(2.5, 1.5)), 1e-6);
  // survey_errors.csv and trajectory.xml have the survey stations only (the tie-in point is
  // trajectory.xml's own).
  EXPECT_EQ(read_lines(dir.path() / "well_path.csv")[1], "minimum_curvature,1000,0,0,0");
}

TEST(SurveyFiles, UncommittedFilesLeaveNothing) {
  const testing::TempDir dir;
  {
    auto files = write_survey_files(recorded_run(true), kTieOn, dir.path(), true);
    EXPECT_GE(files.size(), 3u);
    EXPECT_GT(files_in(dir.path()), 0u);
  }
  EXPECT_EQ(files_in(dir.path()), 0u);
}

TEST(SurveyFiles, NoErrorFileWithoutTruth) {
  const testing::TempDir dir;
  auto files = write_survey_files(recorded_run(false), kTieOn, dir.path(), false);
  ASSERT_EQ(files.size(), 3u);
  for (auto& file : files) file->commit();
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "survey.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "well_path.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "trajectory.xml"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "survey_errors.csv"));
}

TEST(SurveyPlot, EllipseMagnificationIsOneTwoOrFiveTimesAPowerOfTen) {
  // A 4 m ellipse on a 2 km plan: 3 % is 60 m, 15x wanted, 10x drawn.
  EXPECT_EQ(ellipse_magnification(4.0, 2000.0), 10.0);
  EXPECT_EQ(ellipse_magnification(1.0, 2000.0), 50.0);     // 60x wanted
  EXPECT_EQ(ellipse_magnification(0.02, 2000.0), 2000.0);  // 3000x wanted
  EXPECT_EQ(ellipse_magnification(0.2, 10.0), 1.0);        // 1.5x wanted: not worth it
  EXPECT_EQ(ellipse_magnification(100.0, 1000.0), 1.0);    // never shrunk
  EXPECT_EQ(ellipse_magnification(0.0, 1000.0), 1.0);      // no uncertainty
  EXPECT_EQ(ellipse_magnification(1.0, 0.0), 1.0);         // no extent
  for (double axis_m : {0.013, 0.5, 3.7, 11.0}) {
    const double factor = ellipse_magnification(axis_m, 5000.0);
    EXPECT_LE(factor * axis_m, 0.03 * 5000.0 * (1 + 1e-12)) << axis_m;
    EXPECT_GT(factor * axis_m, 0.03 * 5000.0 / 2.5) << axis_m;
  }
}

// Issue #27, feet: survey_ft.csv holds survey.csv's rows in international feet with DLS per
// 100 ft, while survey.csv keeps its names and metres.
TEST(SurveyFiles, FeetListingBesideTheMetreOne) {
  SurveyTieOn tie_on = kTieOn;
  tie_on.direction = SurveyDirection{0.5, 30.0};
  SurveyRecorder recorder(tie_on);
  for (const Epoch& e : three_connections()) {
    recorder.observe(
        state_at(e.t_s, 0.0, 0.0, e.tvd_m, attitude_deg(e.t_s < 3.0 ? 0.5 : 40.0 + e.t_s, 20.0,
                                                        60.0)),
        known_covariance(), e.stationary, 1000.0 + e.tvd_m, nullptr);
  }
  recorder.finish();
  const testing::TempDir dir;
  SurveyListingOptions options;
  options.sensor_to_bit_m = 12.5;
  options.datum_elevation_m = 30.0;
  options.length_unit = SurveyLengthUnit::kFoot;
  auto files = write_survey_files(recorder, tie_on, dir.path(), false, options);
  for (auto& file : files) file->commit();
  const auto metres = survey_columns(dir.path() / "survey.csv");
  EXPECT_EQ(read_lines(dir.path() / "survey.csv")[0],
            std::string(kSurveyHeader) + kListingColumns)
      << "survey.csv keeps its columns and units";
  const auto feet_lines = read_lines(dir.path() / "survey_ft.csv");
  ASSERT_EQ(feet_lines.size(), read_lines(dir.path() / "survey.csv").size()) << "row for row";
  EXPECT_TRUE(feet_lines[0].starts_with("station_type,md_ft,inclination_deg,azimuth_deg,"))
      << feet_lines[0];
  EXPECT_TRUE(feet_lines[1].starts_with("tie_on,")) << feet_lines[1];
  EXPECT_TRUE(feet_lines.back().starts_with("projection_to_bit,")) << feet_lines.back();
  const auto feet = survey_columns(dir.path() / "survey_ft.csv");
  constexpr double kFoot_m = 0.3048;
  for (std::size_t row = 0; row < metres.at("md_m").size(); ++row) {
    SCOPED_TRACE(row);
    for (const auto& [in_feet, in_metres] :
         {std::pair{"md_ft", "md_m"}, std::pair{"tvd_ft", "tvd_m"},
          std::pair{"tvd_below_datum_ft", "tvd_below_datum_m"},
          std::pair{"mc_north_ft", "mc_north_m"}, std::pair{"north_sigma_ft", "north_sigma_m"}}) {
      const double expected = metres.at(in_metres)[row] / kFoot_m;
      const double listed = feet.at(in_feet)[row];
      if (std::isnan(expected)) {
        EXPECT_TRUE(std::isnan(listed)) << in_feet;  // e.g. the tie-on's unrecorded sigmas
      } else {
        EXPECT_NEAR(listed, expected, 1e-5) << in_feet;
      }
    }
    EXPECT_EQ(feet.at("inclination_deg")[row], metres.at("inclination_deg")[row]);
    const double dls_30m = metres.at("dls_deg_30m")[row];
    if (std::isnan(dls_30m)) {
      EXPECT_TRUE(std::isnan(feet.at("dls_deg_100ft")[row]));
    } else {
      // deg/30 m x (100 ft / 30 m) = deg/30 m x 1.016.
      EXPECT_NEAR(feet.at("dls_deg_100ft")[row], dls_30m * 1.016, 1e-6 * (1.0 + dls_30m));
    }
  }
  EXPECT_GT(feet.at("dls_deg_100ft")[2], 0.0) << "a station that builds";
}

TEST(SurveyRecorder, TruthPathBesideTheInsPathWhenThereIsTruth) {
  const SurveyRecorder with_truth = recorded_run(true);
  const std::vector<WellPathPoint> truth = with_truth.truth_path();
  ASSERT_EQ(truth.size(), with_truth.ins_path().size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    // recorded_run's truth is the estimate itself.
    EXPECT_NEAR(truth[i].north_m, with_truth.ins_path()[i].north_m, 1e-9);
    EXPECT_NEAR(truth[i].tvd_m, with_truth.ins_path()[i].tvd_m, 1e-9);
  }
  EXPECT_TRUE(recorded_run(false).truth_path().empty());
}

/// A plan of `points` points from (0, 0) to (north_m, east_m), TVD = MD, with stations.
SurveyPlotData straight_plan(double north_m, double east_m, bool with_truth) {
  SurveyPlotData data;
  constexpr int kPoints = 50;
  for (int k = 0; k <= kPoints; ++k) {
    const double f = static_cast<double>(k) / kPoints;
    const double md = 1000.0 * f;
    data.ins_path.push_back({md, north_m * f, east_m * f, md});
    if (with_truth) data.truth_path.push_back({md, north_m * f + 0.5, east_m * f - 0.3, md + 1.0});
    if (k % 10 == 0 && k > 0) {
      SurveyStation station;
      station.md_m = md;
      station.horizontal_covariance_m2 << 0.04, 0.0, 0.0, 0.01;
      station.tvd_sigma_m = 0.2;
      data.stations.push_back(station);
      data.minimum_curvature_stations.push_back({md, north_m * f, east_m * f, md});
    }
  }
  data.vertical_section_azimuth_deg = 45.0;
  return data;
}

// Issue #27: the plan view of a long straight hole is not squashed to a few pixels: each axis
// spans its own data (at least 1 m), said in the title; the ellipses are then true size.
TEST(SurveyPlot, LongStraightHoleGetsIndependentAxes) {
  const SurveyPlotData data = straight_plan(2000.0, 3.0, false);
  const PlanViewAxes axes = plan_view_axes(data);
  EXPECT_FALSE(axes.equal_scales);
  EXPECT_LE(axes.north_min_m, 0.0);
  EXPECT_GE(axes.north_max_m, 2000.0);
  EXPECT_LE(axes.east_min_m, 0.0);
  EXPECT_GE(axes.east_max_m, 3.0);
  EXPECT_LT(axes.east_max_m - axes.east_min_m, 10.0) << "the east axis spans the hole's drift";
  const std::string script = survey_plot_script(data);
  EXPECT_NE(script.find("set size noratio\nset xrange ["), std::string::npos) << script;
  EXPECT_EQ(script.find("set size ratio -1"), std::string::npos);
  EXPECT_NE(script.find("axes scaled independently"), std::string::npos);
  EXPECT_NE(script.find("2-sigma ellipses x1"), std::string::npos) << "true size";
  EXPECT_NE(script.find(fmt::format("set xrange [{:.9g}:{:.9g}]", axes.east_min_m,
                                    axes.east_max_m)),
            std::string::npos);
  EXPECT_NE(script.find(fmt::format("set yrange [{:.9g}:{:.9g}]", axes.north_min_m,
                                    axes.north_max_m)),
            std::string::npos);
  // A perfectly straight hole still has a readable (1 m) east axis.
  const PlanViewAxes straight = plan_view_axes(straight_plan(2000.0, 0.0, false));
  EXPECT_GE(straight.east_max_m - straight.east_min_m, 1.0);
}

TEST(SurveyPlot, SpreadWellKeepsOneScale) {
  const SurveyPlotData data = straight_plan(600.0, 400.0, false);
  const PlanViewAxes axes = plan_view_axes(data);
  EXPECT_TRUE(axes.equal_scales);
  EXPECT_NEAR(axes.east_max_m - axes.east_min_m, axes.north_max_m - axes.north_min_m, 1e-9);
  const std::string script = survey_plot_script(data);
  EXPECT_NE(script.find("set size ratio -1"), std::string::npos) << script;
  EXPECT_EQ(script.find("axes scaled independently"), std::string::npos);
}

// The truth path in both views when there is truth; the vertical section along the listing's
// azimuth (45 deg: a point at north 1, east 1 is sqrt(2) along it).
TEST(SurveyPlot, TruthPathAndTheListingsSectionAzimuth) {
  const std::string with_truth = survey_plot_script(straight_plan(100.0, 100.0, true));
  // east north tvd section of the first truth point (0.5 N, -0.3 E, TVD 1).
  EXPECT_NE(with_truth.find("$truth << EOD\n-0.3 0.5 1 "), std::string::npos) << with_truth;
  EXPECT_NE(with_truth.find("$truth using 1:2"), std::string::npos) << "plan view";
  EXPECT_NE(with_truth.find("$truth using 4:3"), std::string::npos) << "vertical section";
  EXPECT_NE(with_truth.find("vertical section along azimuth 45.0 deg"), std::string::npos);
  // The second INS point: north 2, east 2, section 2 sqrt(2).
  EXPECT_NE(with_truth.find(fmt::format("\n2 2 20 {:.9g}\n", 2.0 * std::numbers::sqrt2)),
            std::string::npos)
      << with_truth.substr(0, 200);
  const std::string without_truth = survey_plot_script(straight_plan(100.0, 100.0, false));
  EXPECT_EQ(without_truth.find("$truth"), std::string::npos);
}

TEST(SurveyFiles, PlotIsAPngAndLeavesNoTemporaries) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "no gnuplot";
  const testing::TempDir dir;
  auto files = write_survey_files(recorded_run(true), kTieOn, dir.path(), true);
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(files_in(dir.path()), 5u);  // only the five pending files, no script or data
  for (auto& file : files) file->commit();
  files.clear();
  EXPECT_EQ(files_in(dir.path()), 5u);
  std::ifstream png(dir.path() / "survey.png", std::ios::binary);
  char magic[4] = {};
  png.read(magic, 4);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

}  // namespace
}  // namespace stochnav
