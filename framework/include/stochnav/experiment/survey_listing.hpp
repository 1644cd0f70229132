#pragma once
// The columns of a field survey listing derived from the stations (survey.csv after the QC
// columns, in this order; DESIGN.md keeps the earlier ones):
//
//   dls_deg_30m          dogleg severity (deg / 30 m MD): the minimum-curvature dogleg between
//                        the previous station (the tie-on for the first) and this one, over the
//                        MD step, times 30 m
//   build_deg_30m        (I - I_previous) / dMD * 30 m: inclination rate, positive building
//   turn_deg_30m         (A - A_previous, wrapped to (-180, 180]) / dMD * 30 m: azimuth rate,
//                        positive turning right (clockwise from above)
//                        The three rates are NaN on the first station when the tie-on's
//                        attitude is not known (SurveyTieOn::direction: a run sets it from the
//                        configured initial attitude, the aligned one after an alignment, or
//                        the truth's at a start from truth), and on any station
//                        less than kMinimumCourseLengthM (1 m) of MD past the previous one:
//                        over a shorter course the angles' own errors are the rate (a station
//                        at the tie-on's depth, 0.1 deg apart over 0.1 m, would list 30 deg /
//                        30 m); the turn rate
//                        also where either station is within 1 deg of vertical (the azimuth
//                        undefined there).
//   closure_m            horizontal distance from the well reference (the tie-on's north/east,
//                        the origin of north_m/east_m) to the station: hypot(north, east) (m)
//   closure_azimuth_deg  its direction from true north, clockwise, [0, 360) (deg); NaN at a
//                        closure of exactly 0
//   vertical_section_m   the horizontal displacement projected onto the vertical-section
//                        azimuth VSA: north cos(VSA) + east sin(VSA) (m), origin the tie-on
//   ne_m2, nv_m2, ev_m2  position covariances (m^2) in (north, east, vertical DOWN) from the
//                        filter's covariance (nn, ee, vv are the squared *_sigma_m columns)
//   ellipse_semi_major_m, ellipse_semi_minor_m
//                        the horizontal error ellipse holding the position with probability
//                        `ellipse_confidence` (default 0.95): sqrt(eigenvalues of the NE
//                        covariance) times k = sqrt(chi2_2(p)) = sqrt(-2 ln(1 - p))
//                        (2.4477 at 0.95; 1 is the 39.3 % 1-sigma ellipse) (m)
//   ellipse_azimuth_deg  the semi-major axis' direction from true north, clockwise, [0, 180)
//                        (deg); 0 for a circle
//   tvd_below_datum_m    TVD below the depth datum (e.g. RKB), POSITIVE DOWN (m):
//                        tie-on TVD below the datum + tvd_m
//   tvdss_m              TVD below mean sea level (subsea), POSITIVE DOWN (negative above
//                        MSL): tvd_below_datum_m - datum_elevation_m (m)
//                        Both NaN without a datum (SurveyListingOptions::datum_elevation_m).
//   azimuth_defined      1 where the azimuth means something, 0 within 1 deg of vertical (or
//                        where the azimuth is unknown: NaN, a tie-on without attitude), where
//                        a tiny tilt swings it through any angle (azimuth_deg is then the MWD
//                        convention's value, its sigma large or NaN, and no turn rate is given)
//   gyro_toolface        1 where toolface_deg is the gyro ("north") toolface, the angle from
//                        North: at sin(inclination) < kNearVerticalSin (ins/mwd_attitude.hpp),
//                        where the high-side toolface is undefined; 0 where it is the high-side
//                        toolface
//   mc_north_m, mc_east_m, mc_tvd_m
//                        the station's position by MINIMUM CURVATURE (survey.hpp,
//                        minimum_curvature_path) through the listed md_m, inclination_deg and
//                        azimuth_deg from the tie-on at (0, 0, 0), TVD positive down (m): what a
//                        client recomputing the listing gets. The first segment starts with the
//                        tie-on's attitude when known (SurveyTieOn::direction), else straight
//                        along the first station's. north_m/east_m/tvd_m are the INS filter's
//                        positions, a second, independent solution of the same stations: the
//                        two differ by the filter's position error plus minimum curvature's
//                        (its circular-arc assumption and the MD and angle errors), which the
//                        *_sigma_m columns bound on the simulated runs of
//                        tests/experiment/survey_adds_up_test.cpp.
//   station_type         (experiment/survey.hpp) tie_on | survey | projection_to_bit
//   grid_azimuth_deg     azimuth_deg - grid convergence, wrapped to [0, 360) (deg); NaN without
//                        a convergence (SurveyListingOptions::grid_convergence_deg)
//   highside_sigma_m, lateral_sigma_m, alonghole_sigma_m
//                        the position's 1-sigma (m) along the hole's high side h = (cos I cos A,
//                        cos I sin A, -sin I), its lateral (right) l = (-sin A, cos A, 0) and
//                        along the hole t = (sin I cos A, sin I sin A, cos I), all in (north,
//                        east, down): sqrt(x^T P x) with P the NEV covariance (I, A: the listed
//                        inclination and azimuth; near vertical h and l turn with the azimuth)
//   map_easting_m, map_northing_m
//                        the station's map (grid) coordinates: the well reference's
//                        (SurveyListingOptions::map_reference, the tie-on's) plus the
//                        north/east offsets from it turned into grid north by the grid
//                        convergence g and scaled by the grid scale factor k (map_coordinates):
//                          E = E0 + k (east cos g - north sin g)
//                          N = N0 + k (north cos g + east sin g)   (m)
//                        A local tangent-plane approximation: the offsets are metres in the
//                        tie-on's level frame, the projection's convergence and scale taken
//                        constant over the well (their change over a few km of departure,
//                        ~1e-5 relative, is below the survey's uncertainty). NaN without a map
//                        reference
//
// The vertical-section azimuth, when not given, is the tie-on's azimuth (the planned direction
// at the start) when the tie-on's attitude is known and more than 1 deg from vertical, else the
// closure azimuth of the last station (the plane through the well reference and the end of the
// well; 0 when that closure is 0).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "stochnav/experiment/survey.hpp"

namespace stochnav {

/// The shortest MD course (m) over which the listing gives DLS, build and turn rates.
inline constexpr double kMinimumCourseLengthM = 1.0;

/// The derived columns of one station (see above for each).
struct StationListing {
  double dls_deg_30m = 0.0;
  double build_deg_30m = 0.0;
  double turn_deg_30m = 0.0;
  double closure_m = 0.0;
  double closure_azimuth_deg = 0.0;
  double vertical_section_m = 0.0;
  double ne_m2 = 0.0;
  double nv_m2 = 0.0;
  double ev_m2 = 0.0;
  double ellipse_semi_major_m = 0.0;
  double ellipse_semi_minor_m = 0.0;
  double ellipse_azimuth_deg = 0.0;
  double tvd_below_datum_m = 0.0;
  double tvdss_m = 0.0;
  double azimuth_defined = 1.0;  ///< 1 or 0 (a CSV number)
  double gyro_toolface = 0.0;    ///< 1 or 0
  double mc_north_m = 0.0;       ///< minimum curvature through the listed stations (m)
  double mc_east_m = 0.0;
  double mc_tvd_m = 0.0;           ///< positive down (m)
  double grid_azimuth_deg = 0.0;   ///< deg from grid north, [0, 360); NaN without convergence
  double highside_sigma_m = 0.0;   ///< 1-sigma along the high side (m)
  double lateral_sigma_m = 0.0;    ///< 1-sigma across the hole, to the right (m)
  double alonghole_sigma_m = 0.0;  ///< 1-sigma along the hole (m)
  double map_easting_m = 0.0;      ///< map easting (m); NaN without a map reference
  double map_northing_m = 0.0;     ///< map northing (m); NaN without a map reference
};

/// A point's map coordinates (m).
struct MapCoordinates {
  double easting_m = 0.0;
  double northing_m = 0.0;
};

/// The map coordinates of the point north_m, east_m (m, true north and east in the tie-on's
/// level frame) from the well reference, with grid convergence `convergence_deg` (grid north's
/// angle from true north, clockwise positive): see map_easting_m above.
MapCoordinates map_coordinates(const MapReference& reference, double convergence_deg,
                               double north_m, double east_m);

/// A horizontal error ellipse: semi-axes (m) and the major axis' azimuth, [0, 180) deg.
struct HorizontalEllipse {
  double semi_major_m = 0.0;
  double semi_minor_m = 0.0;
  double azimuth_deg = 0.0;
};

/// k = sqrt(-2 ln(1 - confidence)): the 2-D Gaussian's radius (in sigmas) holding the
/// probability `confidence`, in (0, 1). 2.4477 at 0.95.
double ellipse_scale(double confidence);

/// The ellipse of a (north, east) covariance [[NN, NE], [NE, EE]] (m^2, symmetric positive
/// semi-definite; a rounding-negative eigenvalue counts as 0) at `confidence`.
HorizontalEllipse horizontal_ellipse(const Eigen::Matrix2d& covariance_ne_m2, double confidence);

/// The vertical-section azimuth used for these stations (deg): the option, else the tie-on's
/// azimuth (more than 1 deg from vertical), else the last station's closure azimuth (0 without
/// stations or closure).
double vertical_section_azimuth_deg(const std::vector<SurveyStation>& stations,
                                    const SurveyTieOn& tie_on, const SurveyListingOptions& options);

/// The tie-on's TVD below the depth datum (m): options.tie_on_tvd_m, else
/// datum_elevation_m - tie_on.height_m; nullopt without a datum.
std::optional<double> tie_on_tvd_below_datum_m(const SurveyTieOn& tie_on,
                                               const SurveyListingOptions& options);

/// The derived columns of every station, in order (one per station).
std::vector<StationListing> survey_listing(const std::vector<SurveyStation>& stations,
                                           const SurveyTieOn& tie_on,
                                           const SurveyListingOptions& options);

/// The derived columns of the tie-on row (SurveyRecorder::tie_on_station) listed before
/// `stations`: no rates (NaN), closure and vertical section 0 at (0, 0, 0), the covariances and
/// ellipse of its covariance, the datum depths of the tie-on, minimum curvature's origin.
StationListing tie_on_listing(const SurveyStation& tie_on_row,
                              const std::vector<SurveyStation>& stations, const SurveyTieOn& tie_on,
                              const SurveyListingOptions& options);

}  // namespace stochnav
