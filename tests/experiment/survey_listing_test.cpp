// The listing columns of survey.csv (experiment/survey_listing.hpp): rates, closure, vertical
// section, covariances, the horizontal error ellipse and the depth datum, against closed forms.

#include "stochnav/experiment/survey_listing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "stochnav/core/angles.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

SurveyStation station_at(double md_m, double inclination_deg, double azimuth_deg,
                         double north_m = 0.0, double east_m = 0.0, double tvd_m = 0.0) {
  SurveyStation station;
  station.md_m = md_m;
  station.inclination_deg = inclination_deg;
  station.azimuth_deg = azimuth_deg;
  station.north_m = north_m;
  station.east_m = east_m;
  station.tvd_m = tvd_m;
  return station;
}

SurveyTieOn tie_on_at(double md_m, std::optional<SurveyDirection> direction = std::nullopt) {
  SurveyTieOn tie_on{0.6, -1.7, -300.0, md_m};
  tie_on.direction = direction;
  return tie_on;
}

/// Stations on a straight hold at (I, A) from a tie-on at MD 1000 m (N/E/TVD from the tie-on).
// A tool `depth_m` straight below the tie-on, inclined 30 deg towards azimuth 60.
NavState below_tie_on(const SurveyTieOn& tie_on, double depth_m) {
  NavState state;
  state.latitude_rad = tie_on.latitude_rad;
  state.longitude_rad = tie_on.longitude_rad;
  state.height_m = tie_on.height_m - depth_m;
  state.q_nb = quaternion_from_mwd({30.0 * kRadPerDeg, 0.0, 60.0 * kRadPerDeg});
  return state;
}

std::vector<SurveyStation> straight_hold(double inclination_deg, double azimuth_deg) {
  std::vector<SurveyStation> stations;
  const double i = inclination_deg * kRadPerDeg;
  const double a = azimuth_deg * kRadPerDeg;
  for (double along_m : {30.0, 60.0, 95.0}) {
    stations.push_back(station_at(1000.0 + along_m, inclination_deg, azimuth_deg,
                                  along_m * std::sin(i) * std::cos(a),
                                  along_m * std::sin(i) * std::sin(a), along_m * std::cos(i)));
  }
  return stations;
}

// ---------------------------------------------------------------- rates, closure, VS

TEST(SurveyListing, StraightHoleHasNoDoglegAndClosesOnItsHorizontalDistance) {
  const auto stations = straight_hold(30.0, 60.0);
  const auto listing = survey_listing(stations, tie_on_at(1000.0, SurveyDirection{30.0, 60.0}),
                                      SurveyListingOptions{});
  ASSERT_EQ(listing.size(), stations.size());
  for (std::size_t k = 0; k < listing.size(); ++k) {
    const double along_m = stations[k].md_m - 1000.0;
    EXPECT_NEAR(listing[k].dls_deg_30m, 0.0, 1e-12) << k;
    EXPECT_NEAR(listing[k].build_deg_30m, 0.0, 1e-12) << k;
    EXPECT_NEAR(listing[k].turn_deg_30m, 0.0, 1e-12) << k;
    EXPECT_NEAR(listing[k].closure_m, along_m * 0.5, 1e-9) << k;
    EXPECT_NEAR(listing[k].closure_azimuth_deg, 60.0, 1e-9) << k;
    // The default vertical-section azimuth is the tie-on's (60 deg): VS = closure.
    EXPECT_NEAR(listing[k].vertical_section_m, listing[k].closure_m, 1e-9) << k;
  }
}

TEST(SurveyListing, BuildTurnAndDoglegFollowTheClosedForm) {
  const std::vector<SurveyStation> stations = {station_at(1030.0, 10.0, 100.0),
                                               station_at(1045.0, 13.0, 106.0)};
  const auto listing = survey_listing(stations, tie_on_at(1000.0), SurveyListingOptions{});
  // Over 15 m: 3 deg of build and 6 deg of turn are 6 and 12 deg / 30 m.
  EXPECT_NEAR(listing[1].build_deg_30m, 6.0, 1e-9);
  EXPECT_NEAR(listing[1].turn_deg_30m, 12.0, 1e-9);
  const double i1 = 10.0 * kRadPerDeg, i2 = 13.0 * kRadPerDeg, da = 6.0 * kRadPerDeg;
  const double dogleg_deg =
      std::acos(std::cos(i2 - i1) - std::sin(i1) * std::sin(i2) * (1.0 - std::cos(da))) *
      kDegPerRad;
  EXPECT_NEAR(listing[1].dls_deg_30m, dogleg_deg * 2.0, 1e-7);
  // The tie-on's attitude is unknown: the first station has no rates.
  EXPECT_TRUE(std::isnan(listing[0].dls_deg_30m));
  EXPECT_TRUE(std::isnan(listing[0].build_deg_30m));
  EXPECT_TRUE(std::isnan(listing[0].turn_deg_30m));
}

TEST(SurveyListing, FirstStationRatesFromAKnownTieOn) {
  const std::vector<SurveyStation> stations = {station_at(1010.0, 2.0, 45.0)};
  const auto listing = survey_listing(stations, tie_on_at(1000.0, SurveyDirection{0.0, 45.0}), {});
  // A kick-off from vertical: DLS = build = 2 deg over 10 m = 6 deg / 30 m; no turn from a
  // vertical tie-on (its azimuth is undefined).
  EXPECT_NEAR(listing[0].dls_deg_30m, 6.0, 1e-9);
  EXPECT_NEAR(listing[0].build_deg_30m, 6.0, 1e-9);
  EXPECT_TRUE(std::isnan(listing[0].turn_deg_30m));
  const auto from_a_hold = survey_listing({station_at(1010.0, 32.0, 47.0)},
                                          tie_on_at(1000.0, SurveyDirection{30.0, 45.0}), {});
  EXPECT_NEAR(from_a_hold[0].build_deg_30m, 6.0, 1e-9);
  EXPECT_NEAR(from_a_hold[0].turn_deg_30m, 6.0, 1e-9);
}

// A station at the tie-on's depth (the alignment's, 0.1 m past it) differs from the tie-on's
// attitude by the two surveys' errors, not by a dogleg: no rates under kMinimumCourseLengthM,
// the rates from that course on.
TEST(SurveyListing, NoRatesOverACourseShorterThanAMetre) {
  const SurveyTieOn tie_on = tie_on_at(1000.0, SurveyDirection{30.0, 45.0});
  const auto at_tie_on = survey_listing({station_at(1000.1, 30.1, 45.2)}, tie_on, {});
  EXPECT_TRUE(std::isnan(at_tie_on[0].dls_deg_30m)) << at_tie_on[0].dls_deg_30m;
  EXPECT_TRUE(std::isnan(at_tie_on[0].build_deg_30m));
  EXPECT_TRUE(std::isnan(at_tie_on[0].turn_deg_30m));
  const auto one_metre =
      survey_listing({station_at(1000.0 + kMinimumCourseLengthM, 30.1, 45.0)}, tie_on, {});
  EXPECT_NEAR(one_metre[0].build_deg_30m, 3.0, 1e-9);
  EXPECT_NEAR(one_metre[0].dls_deg_30m, 3.0, 1e-6);
}

TEST(SurveyListing, TurnWrapsThroughNorthAndBackwardsDepthHasNoRates) {
  const std::vector<SurveyStation> stations = {
      station_at(1030.0, 60.0, 359.0), station_at(1060.0, 60.0, 1.0), station_at(1059.9, 60.0, 2.0),
      station_at(1059.9, 60.0, 2.0)};
  const auto listing = survey_listing(stations, tie_on_at(1000.0), {});
  EXPECT_NEAR(listing[1].turn_deg_30m, 2.0, 1e-9);
  EXPECT_GT(listing[1].dls_deg_30m, 0.0);
  for (std::size_t k : {2u, 3u}) {
    EXPECT_TRUE(std::isnan(listing[k].dls_deg_30m)) << k;
    EXPECT_TRUE(std::isnan(listing[k].build_deg_30m)) << k;
    EXPECT_TRUE(std::isnan(listing[k].turn_deg_30m)) << k;
  }
}

TEST(SurveyListing, NoTurnRateNearVertical) {
  const std::vector<SurveyStation> stations = {station_at(1030.0, 0.5, 10.0),
                                               station_at(1060.0, 0.9, 200.0),
                                               station_at(1090.0, 1.5, 210.0)};
  const auto listing = survey_listing(stations, tie_on_at(1000.0), {});
  EXPECT_TRUE(std::isnan(listing[1].turn_deg_30m));
  EXPECT_TRUE(std::isnan(listing[2].turn_deg_30m));  // from a near-vertical station
  EXPECT_NEAR(listing[1].build_deg_30m, 0.4, 1e-9);
  EXPECT_TRUE(std::isfinite(listing[1].dls_deg_30m));  // the dogleg is defined at any attitude
  EXPECT_GT(listing[1].dls_deg_30m, 0.5);
}

// The azimuth is marked undefined within 1 deg of vertical, and the toolface named gyro where
// the MWD convention switches to it (exactly vertical here), high-side elsewhere.
TEST(SurveyListing, NearVerticalAzimuthAndTheToolfaceKindAreMarked) {
  const std::vector<SurveyStation> stations = {
      station_at(1010.0, 0.0, 0.0), station_at(1020.0, 0.5, 10.0), station_at(1030.0, 1.5, 20.0),
      station_at(1040.0, 179.5, 30.0)};
  const auto listing = survey_listing(stations, tie_on_at(1000.0), {});
  const double defined[] = {0.0, 0.0, 1.0, 0.0};
  const double gyro[] = {1.0, 0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < stations.size(); ++i) {
    EXPECT_EQ(listing[i].azimuth_defined, defined[i]) << i;
    EXPECT_EQ(listing[i].gyro_toolface, gyro[i]) << i;
  }
}

TEST(SurveyListing, VerticalSectionProjectsOntoTheChosenAzimuth) {
  const std::vector<SurveyStation> stations = {station_at(1100.0, 40.0, 10.0, 30.0, 40.0),
                                               station_at(1200.0, 40.0, 10.0, -6.0, 8.0)};
  SurveyListingOptions options;
  options.vertical_section_azimuth_deg = 90.0;
  auto listing = survey_listing(stations, tie_on_at(1000.0), options);
  EXPECT_NEAR(listing[0].vertical_section_m, 40.0, 1e-9);  // east
  EXPECT_NEAR(listing[1].vertical_section_m, 8.0, 1e-9);
  EXPECT_NEAR(listing[0].closure_m, 50.0, 1e-12);
  EXPECT_NEAR(listing[0].closure_azimuth_deg, std::atan2(40.0, 30.0) * kDegPerRad, 1e-9);
  EXPECT_NEAR(listing[1].closure_azimuth_deg, 180.0 - std::atan2(8.0, 6.0) * kDegPerRad, 1e-9);
  // No azimuth given, no tie-on attitude: the last station's closure azimuth.
  options.vertical_section_azimuth_deg.reset();
  EXPECT_NEAR(vertical_section_azimuth_deg(stations, tie_on_at(1000.0), options),
              listing[1].closure_azimuth_deg, 1e-12);
  listing = survey_listing(stations, tie_on_at(1000.0), options);
  EXPECT_NEAR(listing[1].vertical_section_m, 10.0, 1e-9);
  // Projected onto the last closure: the first station's 50 m at 53.13 - 126.87 deg apart.
  EXPECT_NEAR(listing[0].vertical_section_m, (-6.0 * 30.0 + 8.0 * 40.0) / 10.0, 1e-9);
  // A tie-on attitude sets the default, unless it is vertical (its azimuth then arbitrary).
  EXPECT_NEAR(vertical_section_azimuth_deg(stations, tie_on_at(1000.0, SurveyDirection{5.0, -20.0}),
                                           options),
              340.0, 1e-12);
  EXPECT_NEAR(vertical_section_azimuth_deg(stations, tie_on_at(1000.0, SurveyDirection{0.5, 200.0}),
                                           options),
              listing[1].closure_azimuth_deg, 1e-12);
  // West of the reference: a closure azimuth in [0, 360).
  const auto west =
      survey_listing({station_at(1100.0, 40.0, 10.0, 0.0, -5.0)}, tie_on_at(1000.0), {});
  EXPECT_NEAR(west[0].closure_azimuth_deg, 270.0, 1e-9);
  const auto origin = survey_listing({station_at(1100.0, 0.0, 0.0)}, tie_on_at(1000.0), {});
  EXPECT_TRUE(std::isnan(origin[0].closure_azimuth_deg));
}

// ---------------------------------------------------------------- ellipse and covariance

TEST(SurveyListing, EllipseScaleIsTheChiSquareRadius) {
  EXPECT_NEAR(ellipse_scale(0.95), 2.4477468, 1e-6);             // sqrt(5.991465)
  EXPECT_NEAR(ellipse_scale(1.0 - std::exp(-0.5)), 1.0, 1e-12);  // the 1-sigma ellipse
  EXPECT_NEAR(ellipse_scale(0.99), std::sqrt(9.2103404), 1e-6);
}

TEST(SurveyListing, EllipseOfADiagonalCovarianceIsTheSigmasTimesTheScale) {
  const double k = ellipse_scale(0.95);
  Eigen::Matrix2d covariance;
  covariance << 9.0, 0.0, 0.0, 4.0;  // sigma N 3 m, E 2 m
  HorizontalEllipse e = horizontal_ellipse(covariance, 0.95);
  EXPECT_NEAR(e.semi_major_m, 3.0 * k, 1e-12);
  EXPECT_NEAR(e.semi_minor_m, 2.0 * k, 1e-12);
  EXPECT_NEAR(e.azimuth_deg, 0.0, 1e-12);
  covariance << 4.0, 0.0, 0.0, 9.0;  // the longer axis east
  e = horizontal_ellipse(covariance, 0.95);
  EXPECT_NEAR(e.semi_major_m, 3.0 * k, 1e-12);
  EXPECT_NEAR(e.semi_minor_m, 2.0 * k, 1e-12);
  EXPECT_NEAR(e.azimuth_deg, 90.0, 1e-12);
  covariance << 4.0, 0.0, 0.0, 4.0;  // a circle
  e = horizontal_ellipse(covariance, 0.95);
  EXPECT_NEAR(e.semi_major_m, 2.0 * k, 1e-12);
  EXPECT_NEAR(e.semi_minor_m, 2.0 * k, 1e-12);
  EXPECT_EQ(e.azimuth_deg, 0.0);
}

TEST(SurveyListing, RotatedCovarianceGivesTheRotatedAxes) {
  for (double azimuth_deg : {30.0, 75.0, 120.0, 150.0, -30.0, 210.0}) {
    const double a = azimuth_deg * kRadPerDeg;
    Eigen::Matrix2d rotation;  // (north, east) of the major, minor axes as columns
    rotation << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    const Eigen::Matrix2d covariance =
        rotation * Eigen::Vector2d(25.0, 1.0).asDiagonal() * rotation.transpose();
    const HorizontalEllipse e = horizontal_ellipse(covariance, 0.5);
    const double k = std::sqrt(-2.0 * std::log(0.5));
    EXPECT_NEAR(e.semi_major_m, 5.0 * k, 1e-9) << azimuth_deg;
    EXPECT_NEAR(e.semi_minor_m, 1.0 * k, 1e-9) << azimuth_deg;
    const double expected = std::fmod(azimuth_deg + 360.0, 180.0);
    EXPECT_NEAR(e.azimuth_deg, expected, 1e-9) << azimuth_deg;
  }
}

TEST(SurveyListing, CovarianceColumnsAreNorthEastDown) {
  // The recorder's covariance is ENU; the listing's NEV has V positive down.
  const SurveyTieOn tie_on = tie_on_at(1000.0);
  SurveyRecorder recorder(tie_on);
  NavState state = below_tie_on(tie_on, 50.0);
  Eigen::Matrix<double, 9, 9> p = Eigen::Matrix<double, 9, 9>::Identity() * 1e-6;
  p(0, 0) = 4.0;              // E
  p(1, 1) = 9.0;              // N
  p(2, 2) = 16.0;             // U
  p(0, 1) = p(1, 0) = 1.5;    // EN
  p(1, 2) = p(2, 1) = 0.5;    // NU
  p(0, 2) = p(2, 0) = -0.25;  // EU
  recorder.observe(state, p, true, 1050.0, nullptr);
  recorder.finish();
  ASSERT_EQ(recorder.stations().size(), 1u);
  const auto listing = survey_listing(recorder.stations(), tie_on, {});
  EXPECT_DOUBLE_EQ(listing[0].ne_m2, 1.5);
  EXPECT_DOUBLE_EQ(listing[0].nv_m2, -0.5);
  EXPECT_DOUBLE_EQ(listing[0].ev_m2, 0.25);
  const Eigen::Matrix3d& nev = recorder.stations()[0].position_covariance_nev_m2;
  EXPECT_DOUBLE_EQ(nev(0, 0), 9.0);
  EXPECT_DOUBLE_EQ(nev(1, 1), 4.0);
  EXPECT_DOUBLE_EQ(nev(2, 2), 16.0);
  const HorizontalEllipse e =
      horizontal_ellipse(recorder.stations()[0].horizontal_covariance_m2, 0.95);
  EXPECT_DOUBLE_EQ(listing[0].ellipse_semi_major_m, e.semi_major_m);
  EXPECT_DOUBLE_EQ(listing[0].ellipse_semi_minor_m, e.semi_minor_m);
  EXPECT_DOUBLE_EQ(listing[0].ellipse_azimuth_deg, e.azimuth_deg);
}

// ---------------------------------------------------------------- depth datum

TEST(SurveyListing, DatumColumnsArePositiveDownFromTheDatumAndMeanSeaLevel) {
  const std::vector<SurveyStation> stations = {station_at(1100.0, 0.0, 0.0, 0.0, 0.0, 100.0)};
  const SurveyTieOn tie_on = tie_on_at(1000.0);  // height -300 m
  EXPECT_TRUE(std::isnan(survey_listing(stations, tie_on, {})[0].tvd_below_datum_m));
  EXPECT_TRUE(std::isnan(survey_listing(stations, tie_on, {})[0].tvdss_m));
  SurveyListingOptions options;
  options.datum_elevation_m = 30.0;  // e.g. a kelly bushing 30 m above MSL
  // The tie-on 300 m below MSL is 330 m below the datum; the station 100 m deeper.
  auto listing = survey_listing(stations, tie_on, options);
  EXPECT_NEAR(listing[0].tvd_below_datum_m, 430.0, 1e-9);
  EXPECT_NEAR(listing[0].tvdss_m, 400.0, 1e-9);
  options.tie_on_tvd_m = 1000.0;  // stated in the config: the height is not used
  listing = survey_listing(stations, tie_on, options);
  EXPECT_NEAR(listing[0].tvd_below_datum_m, 1100.0, 1e-9);
  EXPECT_NEAR(listing[0].tvdss_m, 1070.0, 1e-9);
}

// On a straight hold from a tie-on with the same attitude, minimum curvature is the straight
// line, where straight_hold also put the INS positions: the two solutions coincide.
TEST(SurveyListing, MinimumCurvatureColumnsFollowTheListedStations) {
  const auto stations = straight_hold(30.0, 60.0);
  const auto listing = survey_listing(stations, tie_on_at(1000.0, SurveyDirection{30.0, 60.0}), {});
  ASSERT_EQ(listing.size(), stations.size());
  for (std::size_t i = 0; i < stations.size(); ++i) {
    EXPECT_NEAR(listing[i].mc_north_m, stations[i].north_m, 1e-9) << i;
    EXPECT_NEAR(listing[i].mc_east_m, stations[i].east_m, 1e-9) << i;
    EXPECT_NEAR(listing[i].mc_tvd_m, stations[i].tvd_m, 1e-9) << i;
  }
  // From a vertical tie-on the first segment bends: the columns follow minimum_curvature_path
  // with the tie-on's direction, not the INS positions.
  const SurveyTieOn vertical = tie_on_at(1000.0, SurveyDirection{0.0, 0.0});
  const auto bent = survey_listing(stations, vertical, {});
  const auto path = minimum_curvature_path(stations, 1000.0, vertical.direction);
  EXPECT_NEAR(bent[0].mc_tvd_m, path[0].tvd_m, 1e-12);
  EXPECT_NEAR(bent[2].mc_east_m, path[2].east_m, 1e-12);
  EXPECT_GT(bent[0].mc_tvd_m, stations[0].tvd_m + 0.1);
}

// Grid azimuth: true azimuth minus the convergence, wrapped; the position sigmas in the hole's
// frame: on a hole inclined 90 deg towards east, high side is up (the TVD sigma), lateral is
// south (the north sigma) and along-hole is east (the east sigma).
TEST(SurveyListing, GridAzimuthAndTheEllipseInTheHolesFrame) {
  std::vector<SurveyStation> stations = {station_at(1030.0, 90.0, 90.0),
                                         station_at(1060.0, 45.0, 0.5)};
  for (SurveyStation& s : stations) {
    s.position_covariance_nev_m2 << 4.0, 1.0, 0.5, 1.0, 9.0, 0.3, 0.5, 0.3, 16.0;
  }
  SurveyListingOptions options;
  options.grid_convergence_deg = 1.5;
  const auto listing = survey_listing(stations, tie_on_at(1000.0), options);
  EXPECT_NEAR(listing[0].grid_azimuth_deg, 88.5, 1e-12);
  EXPECT_NEAR(listing[1].grid_azimuth_deg, 359.0, 1e-12);
  EXPECT_NEAR(listing[0].highside_sigma_m, 4.0, 1e-12);
  EXPECT_NEAR(listing[0].lateral_sigma_m, 2.0, 1e-12);
  EXPECT_NEAR(listing[0].alonghole_sigma_m, 3.0, 1e-12);
  // The rotation keeps the trace: the three variances sum to NN + EE + VV.
  const StationListing& r = listing[1];
  EXPECT_NEAR(r.highside_sigma_m * r.highside_sigma_m + r.lateral_sigma_m * r.lateral_sigma_m +
                  r.alonghole_sigma_m * r.alonghole_sigma_m,
              29.0, 1e-9);
  EXPECT_TRUE(std::isnan(survey_listing(stations, tie_on_at(1000.0), {})[0].grid_azimuth_deg));
}

// Map coordinates: the well reference's plus the offsets turned into grid north and scaled.
// A station 1 km due east with grid north 2 deg east of true lies at grid azimuth 88 deg: its
// easting grows by k cos 2 deg km and its northing by k sin 2 deg km; 1 km due north goes
// k cos 2 deg km up and k sin 2 deg km west. The grid distance is k times the ground's, and
// the grid azimuth of the offset is the listed grid azimuth of a hole pointing at it.
TEST(SurveyListing, MapCoordinatesFromTheWellReference) {
  const MapReference reference{500000.0, 6200000.0, 0.9996};
  const double g = 2.0 * kRadPerDeg;
  const MapCoordinates east = map_coordinates(reference, 2.0, 0.0, 1000.0);
  EXPECT_NEAR(east.easting_m, 500000.0 + 0.9996 * 1000.0 * std::cos(g), 1e-9);
  EXPECT_NEAR(east.northing_m, 6200000.0 + 0.9996 * 1000.0 * std::sin(g), 1e-9);
  const MapCoordinates north = map_coordinates(reference, 2.0, 1000.0, 0.0);
  EXPECT_NEAR(north.easting_m, 500000.0 - 0.9996 * 1000.0 * std::sin(g), 1e-9);
  EXPECT_NEAR(north.northing_m, 6200000.0 + 0.9996 * 1000.0 * std::cos(g), 1e-9);
  const MapCoordinates origin = map_coordinates(reference, 2.0, 0.0, 0.0);
  EXPECT_EQ(origin.easting_m, 500000.0);
  EXPECT_EQ(origin.northing_m, 6200000.0);

  // In the listing: a hole at true azimuth 30 deg, 600 m out; its grid offset's azimuth is the
  // listed grid azimuth and its length k x the closure.
  std::vector<SurveyStation> stations = {station_at(1700.0, 60.0, 30.0, 600.0 * std::cos(0.5236),
                                                    600.0 * std::sin(0.5236), 400.0)};
  SurveyListingOptions options;
  options.grid_convergence_deg = 2.0;
  options.map_reference = reference;
  const auto listing = survey_listing(stations, tie_on_at(1000.0), options);
  const double de = listing[0].map_easting_m - reference.easting_m;
  const double dn = listing[0].map_northing_m - reference.northing_m;
  EXPECT_NEAR(std::hypot(de, dn), 0.9996 * listing[0].closure_m, 1e-6);
  EXPECT_NEAR(std::atan2(de, dn) * kDegPerRad, listing[0].closure_azimuth_deg - 2.0, 1e-9);
  EXPECT_NEAR(listing[0].grid_azimuth_deg, 28.0, 1e-12);
  // Without a map reference: NaN.
  options.map_reference.reset();
  EXPECT_TRUE(std::isnan(survey_listing(stations, tie_on_at(1000.0), options)[0].map_easting_m));
}

// ---------------------------------------------------------------- file

std::vector<std::string> read_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> split(const std::string& row) {
  std::vector<std::string> cells;
  std::stringstream in(row);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

TEST(SurveyListing, SurveyCsvCarriesTheColumnsAfterTheQc) {
  const SurveyTieOn tie_on = tie_on_at(1000.0, SurveyDirection{30.0, 60.0});
  SurveyRecorder recorder(tie_on);
  NavState state = below_tie_on(tie_on, 20.0);
  Eigen::Matrix<double, 9, 9> p = Eigen::Matrix<double, 9, 9>::Identity() * 1e-6;
  p(0, 0) = 4.0;
  p(1, 1) = 9.0;
  recorder.observe(state, p, true, 1040.0, &state);
  recorder.finish();
  const testing::TempDir dir;
  SurveyListingOptions options;
  options.datum_elevation_m = 10.0;
  auto files = write_survey_files(recorder, tie_on, dir.path(), false, options);
  for (auto& file : files) file->commit();
  const auto survey = read_lines(dir.path() / "survey.csv");
  ASSERT_EQ(survey.size(), 3u);  // the tie-on row, the station
  const std::string listing_columns =
      ",qc_flag,dls_deg_30m,build_deg_30m,turn_deg_30m,closure_m,closure_azimuth_deg,"
      "vertical_section_m,ne_m2,nv_m2,ev_m2,ellipse_semi_major_m,ellipse_semi_minor_m,"
      "ellipse_azimuth_deg,tvd_below_datum_m,tvdss_m,azimuth_defined,gyro_toolface,mc_north_m,"
      "mc_east_m,mc_tvd_m,md_sigma_m,station_type,grid_azimuth_deg,highside_sigma_m,"
      "lateral_sigma_m,alonghole_sigma_m,map_easting_m,map_northing_m";
  ASSERT_TRUE(survey[0].ends_with(listing_columns)) << survey[0];
  const auto header = split(survey[0]);
  EXPECT_NE(survey[1].find(",tie_on,"), std::string::npos) << survey[1];
  const auto row = split(survey[2]);
  ASSERT_EQ(row.size(), header.size());
  const auto cell = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return std::stod(row[i]);
    }
    ADD_FAILURE() << "no column " << name;
    return std::nan("");
  };
  EXPECT_NEAR(cell("dls_deg_30m"), 0.0, 1e-6);
  EXPECT_NEAR(cell("ellipse_semi_major_m"), 3.0 * ellipse_scale(0.95), 1e-6);
  EXPECT_NEAR(cell("ellipse_semi_minor_m"), 2.0 * ellipse_scale(0.95), 1e-6);
  EXPECT_NEAR(cell("ellipse_azimuth_deg"), 0.0, 1e-9);
  EXPECT_NEAR(cell("tvd_below_datum_m"), 310.0 + 20.0, 1e-6);
  EXPECT_NEAR(cell("tvdss_m"), 320.0, 1e-6);
  // survey_errors.csv keeps the columns up to the QC's.
  const auto errors = read_lines(dir.path() / "survey_errors.csv");
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_TRUE(errors[0].ends_with(",qc_flag")) << errors[0];
}

}  // namespace
}  // namespace stochnav
