#include "stochnav/experiment/survey_listing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/minimum_curvature.hpp"
#include "stochnav/ins/mwd_attitude.hpp"

namespace stochnav {
namespace {

constexpr double kRateLengthM = 30.0;  ///< the listing's rates are per 30 m of MD
/// Within this of vertical (deg) the azimuth is undefined: no turn rate, and the tie-on's does
/// not set the vertical section.
constexpr double kNearVerticalDeg = 1.0;
constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

/// Whether an inclination (deg) is within kNearVerticalDeg of vertical (up or down).
bool near_vertical(double inclination_deg) {
  return std::abs(std::sin(inclination_deg * kRadPerDeg)) < std::sin(kNearVerticalDeg * kRadPerDeg);
}

/// Azimuth (deg, [0, 360)) of a horizontal vector from true north, NaN for the zero vector.
double azimuth_deg_of(double north, double east) {
  if (north == 0.0 && east == 0.0) return kUndefined;
  double azimuth = std::atan2(east, north) * kDegPerRad;
  if (azimuth < 0.0) azimuth += 360.0;
  return azimuth >= 360.0 ? 0.0 : azimuth;
}

/// DLS, build and turn (deg / 30 m) from (inclination, azimuth) at the previous station to
/// the current one over md_step_m; NaN over a course shorter than kMinimumCourseLengthM.
void set_rates(StationListing& listing, double previous_inclination_deg,
               double previous_azimuth_deg, const SurveyStation& station, double md_step_m) {
  if (!(md_step_m >= kMinimumCourseLengthM)) {
    listing.dls_deg_30m = listing.build_deg_30m = listing.turn_deg_30m = kUndefined;
    return;
  }
  const double per_30m = kRateLengthM / md_step_m;
  const double dogleg_deg = dogleg_rad(hole_direction_nev(previous_inclination_deg * kRadPerDeg,
                                                          previous_azimuth_deg * kRadPerDeg),
                                       hole_direction_nev(station.inclination_deg * kRadPerDeg,
                                                          station.azimuth_deg * kRadPerDeg)) *
                            kDegPerRad;
  listing.dls_deg_30m = dogleg_deg * per_30m;
  listing.build_deg_30m = (station.inclination_deg - previous_inclination_deg) * per_30m;
  // Near vertical the azimuth is undefined (a tiny tilt swings it through any angle): no turn.
  listing.turn_deg_30m =
      near_vertical(previous_inclination_deg) || near_vertical(station.inclination_deg)
          ? kUndefined
          : std::remainder(station.azimuth_deg - previous_azimuth_deg, 360.0) * per_30m;
}

/// 1-sigmas (m) of the NEV covariance along the hole's high side, lateral and along-hole axes.
void set_hole_frame_sigmas(StationListing& row, const SurveyStation& s) {
  const double i = s.inclination_deg * kRadPerDeg;
  const double a = s.azimuth_deg * kRadPerDeg;
  const Eigen::Vector3d high_side(std::cos(i) * std::cos(a), std::cos(i) * std::sin(a),
                                  -std::sin(i));
  const Eigen::Vector3d lateral(-std::sin(a), std::cos(a), 0.0);
  const Eigen::Vector3d along_hole = hole_direction_nev(i, a);
  const Eigen::Matrix3d& p = s.position_covariance_nev_m2;
  const auto sigma_along = [&](const Eigen::Vector3d& x) {
    return std::sqrt(std::max(x.dot(p * x), 0.0));
  };
  row.highside_sigma_m = sigma_along(high_side);
  row.lateral_sigma_m = sigma_along(lateral);
  row.alonghole_sigma_m = sigma_along(along_hole);
}

/// The columns that follow from the station alone and the references: closure, vertical
/// section, covariances, ellipse, the azimuth and toolface flags and the datum depths.
void set_position_columns(StationListing& row, const SurveyStation& s, double vs_azimuth_rad,
                          const std::optional<double>& tie_on_tvd,
                          const SurveyListingOptions& options) {
  row.closure_m = std::hypot(s.north_m, s.east_m);
  row.closure_azimuth_deg = azimuth_deg_of(s.north_m, s.east_m);
  row.vertical_section_m =
      s.north_m * std::cos(vs_azimuth_rad) + s.east_m * std::sin(vs_azimuth_rad);
  const Eigen::Matrix3d& p = s.position_covariance_nev_m2;
  row.ne_m2 = p(0, 1);
  row.nv_m2 = p(0, 2);
  row.ev_m2 = p(1, 2);
  const HorizontalEllipse ellipse =
      horizontal_ellipse(p.topLeftCorner<2, 2>(), options.ellipse_confidence);
  row.ellipse_semi_major_m = ellipse.semi_major_m;
  row.ellipse_semi_minor_m = ellipse.semi_minor_m;
  row.ellipse_azimuth_deg = ellipse.azimuth_deg;
  row.azimuth_defined = std::isnan(s.azimuth_deg) || near_vertical(s.inclination_deg) ? 0.0 : 1.0;
  row.gyro_toolface =
      std::abs(std::sin(s.inclination_deg * kRadPerDeg)) < kNearVerticalSin ? 1.0 : 0.0;
  if (tie_on_tvd) {
    row.tvd_below_datum_m = *tie_on_tvd + s.tvd_m;
    row.tvdss_m = row.tvd_below_datum_m - *options.datum_elevation_m;
  } else {
    row.tvd_below_datum_m = row.tvdss_m = kUndefined;
  }
  if (options.grid_convergence_deg) {
    double grid = std::fmod(s.azimuth_deg - *options.grid_convergence_deg, 360.0);
    if (grid < 0.0) grid += 360.0;
    row.grid_azimuth_deg = grid >= 360.0 ? 0.0 : grid;
  } else {
    row.grid_azimuth_deg = kUndefined;
  }
  if (options.map_reference) {
    const MapCoordinates map = map_coordinates(
        *options.map_reference, options.grid_convergence_deg.value_or(0.0), s.north_m, s.east_m);
    row.map_easting_m = map.easting_m;
    row.map_northing_m = map.northing_m;
  } else {
    row.map_easting_m = row.map_northing_m = kUndefined;
  }
  set_hole_frame_sigmas(row, s);
}

}  // namespace

MapCoordinates map_coordinates(const MapReference& reference, double convergence_deg,
                               double north_m, double east_m) {
  // Grid north is turned clockwise from true north by the convergence: an offset at true
  // azimuth A lies at grid azimuth A - g.
  const double g = convergence_deg * kRadPerDeg;
  const double k = reference.scale_factor;
  return {reference.easting_m + k * (east_m * std::cos(g) - north_m * std::sin(g)),
          reference.northing_m + k * (north_m * std::cos(g) + east_m * std::sin(g))};
}

double ellipse_scale(double confidence) { return std::sqrt(-2.0 * std::log1p(-confidence)); }

HorizontalEllipse horizontal_ellipse(const Eigen::Matrix2d& covariance_ne_m2, double confidence) {
  // Eigenvalues of [[a, b], [b, c]] in closed form: mean +/- hypot((a - c) / 2, b); the major
  // axis at 1/2 atan2(2b, a - c) from the first axis (north) towards the second (east).
  const double a = covariance_ne_m2(0, 0);
  const double b = 0.5 * (covariance_ne_m2(0, 1) + covariance_ne_m2(1, 0));
  const double c = covariance_ne_m2(1, 1);
  const double mean = 0.5 * (a + c);
  const double radius = std::hypot(0.5 * (a - c), b);
  const double k = ellipse_scale(confidence);
  HorizontalEllipse ellipse;
  ellipse.semi_major_m = k * std::sqrt(std::max(mean + radius, 0.0));
  ellipse.semi_minor_m = k * std::sqrt(std::max(mean - radius, 0.0));
  double azimuth = radius > 0.0 ? 0.5 * std::atan2(2.0 * b, a - c) * kDegPerRad : 0.0;
  if (azimuth < 0.0) azimuth += 180.0;
  ellipse.azimuth_deg = azimuth >= 180.0 ? 0.0 : azimuth;
  return ellipse;
}

double vertical_section_azimuth_deg(const std::vector<SurveyStation>& stations,
                                    const SurveyTieOn& tie_on,
                                    const SurveyListingOptions& options) {
  if (options.vertical_section_azimuth_deg) return *options.vertical_section_azimuth_deg;
  // A vertical tie-on's azimuth is arbitrary (the MWD convention puts the heading in the
  // toolface there): it does not choose the plane.
  if (tie_on.direction && !near_vertical(tie_on.direction->inclination_deg)) {
    const double azimuth = std::fmod(tie_on.direction->azimuth_deg, 360.0);
    return azimuth < 0.0 ? azimuth + 360.0 : azimuth;
  }
  if (stations.empty()) return 0.0;
  const double closure = azimuth_deg_of(stations.back().north_m, stations.back().east_m);
  return std::isnan(closure) ? 0.0 : closure;
}

std::optional<double> tie_on_tvd_below_datum_m(const SurveyTieOn& tie_on,
                                               const SurveyListingOptions& options) {
  if (options.tie_on_tvd_m) return options.tie_on_tvd_m;
  if (options.datum_elevation_m) return *options.datum_elevation_m - tie_on.height_m;
  return std::nullopt;
}

std::vector<StationListing> survey_listing(const std::vector<SurveyStation>& stations,
                                           const SurveyTieOn& tie_on,
                                           const SurveyListingOptions& options) {
  const double vs_azimuth_rad =
      vertical_section_azimuth_deg(stations, tie_on, options) * kRadPerDeg;
  const std::optional<double> tie_on_tvd = tie_on_tvd_below_datum_m(tie_on, options);
  const std::vector<WellPathPoint> minimum_curvature =
      minimum_curvature_path(stations, tie_on.measured_depth_m, tie_on.direction);
  std::vector<StationListing> listing(stations.size());
  for (std::size_t i = 0; i < stations.size(); ++i) {
    const SurveyStation& s = stations[i];
    StationListing& row = listing[i];
    row.mc_north_m = minimum_curvature[i].north_m;
    row.mc_east_m = minimum_curvature[i].east_m;
    row.mc_tvd_m = minimum_curvature[i].tvd_m;
    if (i > 0) {
      set_rates(row, stations[i - 1].inclination_deg, stations[i - 1].azimuth_deg, s,
                s.md_m - stations[i - 1].md_m);
    } else if (tie_on.direction) {
      set_rates(row, tie_on.direction->inclination_deg, tie_on.direction->azimuth_deg, s,
                s.md_m - tie_on.measured_depth_m);
    } else {
      row.dls_deg_30m = row.build_deg_30m = row.turn_deg_30m = kUndefined;
    }
    set_position_columns(row, s, vs_azimuth_rad, tie_on_tvd, options);
  }
  return listing;
}

StationListing tie_on_listing(const SurveyStation& tie_on_row,
                              const std::vector<SurveyStation>& stations, const SurveyTieOn& tie_on,
                              const SurveyListingOptions& options) {
  StationListing row;
  row.dls_deg_30m = row.build_deg_30m = row.turn_deg_30m = kUndefined;
  set_position_columns(row, tie_on_row,
                       vertical_section_azimuth_deg(stations, tie_on, options) * kRadPerDeg,
                       tie_on_tvd_below_datum_m(tie_on, options), options);
  row.mc_north_m = row.mc_east_m = row.mc_tvd_m = 0.0;  // the origin of minimum curvature
  return row;
}

}  // namespace stochnav
