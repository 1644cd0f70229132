#pragma once
// Survey stations of a drilling run: at every connection (the tool stationary, ZUPT applied)
// the filter's attitude and position become one station, as an MWD survey reports it.
//
// Conventions (DESIGN.md, `survey.csv`):
//   md_m          measured depth of the survey SENSOR along the hole (m): with depth readings
//                 (the aid data's "measured_depth_m", a pipe tally of the BIT's depth, minus the
//                 run config's "survey/sensor_to_bit_m"), the mean of the readings of the
//                 station's stationary span (experiment/tally_smoother.hpp); else the tie-on
//                 depth plus the INS path length
//   inclination   angle of the tool axis from vertical down (deg), [0, 180]
//   azimuth       direction of the tool axis' horizontal projection from TRUE north, clockwise
//                 towards east (deg), [0, 360)
//   toolface      high-side toolface (deg), [0, 360) (gyro toolface near vertical)
//   north_m, east_m, tvd_m
//                 position relative to the tie-on point in its local level frame: north and east
//                 along the tie-on's meridian and parallel (m), TVD = true vertical depth below the
//                 tie-on, POSITIVE DOWN (m)
//   *_sigma_*     1-sigma from the filter covariance (attitude sigmas by linearising the MWD
//                 angles about the estimate; position sigmas from the ENU position block)
// A station is taken at the LAST stationary aid epoch of each connection (the filter has then
// used every ZUPT of it); a record that ends while stationary yields a final station.
//
// Rows of survey.csv (column station_type, the last): first the TIE-ON ("tie_on": its MD, the
// attitude known there (SurveyTieOn::direction; toolface from the start state), position
// (0, 0, 0), the sigmas of the filter's initial covariance, md_sigma_m 0: the reference of the
// others; QC and rates NaN), then one row per connection ("survey"), then, with a sensor-to-bit
// offset X > 0, the PROJECTION TO THE BIT ("projection_to_bit": X m beyond the last station,
// straight along its attitude (minimum curvature with no dogleg), its sigmas the last
// station's: the projection's own error, the unknown curvature over X, is not in them).
// metrics.json's station count counts the "survey" rows only; survey_errors.csv has those only.
//
// Without measured depth in the data, md_m is the tie-on MD plus the length of the INS path
// (the sum of the 3-D distances between the positions of successive observe() calls, starting
// at the first one, which is taken to be at the tie-on); position jitter while stationary
// lengthens it slightly.
//
// survey_errors.csv has the columns of survey.csv up to the QC's (not the listing's), read
// differently: the angle and position
// columns are estimate - truth (angles wrapped to (-180, 180] deg; azimuth and toolface NaN,
// written `nan`, where the true hole is within 1 deg of vertical, as navigation_errors), while
// t_s and md_m are the station's (the key of the row, not errors) and the *_sigma_* columns are
// the station's sigmas, so each error can be compared with its own sigma on the same row.
//
// Minimum curvature (the industry's standard well-path method): between consecutive stations
// with (I1, A1) and (I2, A2) and a measured-depth step dMD, the dogleg angle
//   beta = acos(cos(I2 - I1) - sin I1 sin I2 (1 - cos(A2 - A1)))
// and ratio factor RF = (2 / beta) tan(beta / 2) (1 when beta = 0) give
//   dN = dMD / 2 (sin I1 cos A1 + sin I2 cos A2) RF
//   dE = dMD / 2 (sin I1 sin A1 + sin I2 sin A2) RF
//   dTVD = dMD / 2 (cos I1 + cos I2) RF,
// starting at the tie-on (0, 0, 0) with the first station's attitude (core/minimum_curvature.hpp,
// shared with the ISCWSA error model).

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "stochnav/experiment/station_qc.hpp"
#include "stochnav/experiment/tally_smoother.hpp"
#include "stochnav/ins/nav_state.hpp"
#include "stochnav/io/atomic_file.hpp"

namespace stochnav {

struct SurveyErrorModelRequest;  // experiment/survey_error_files.hpp

/// The hole's direction at a point (deg; inclination from vertical down, azimuth from true
/// north).
struct SurveyDirection {
  double inclination_deg = 0.0;
  double azimuth_deg = 0.0;
};

/// Where the well's local frame starts: the tie-on point (a known position on the well path).
struct SurveyTieOn {
  double latitude_rad = 0.0;      ///< geodetic latitude (rad)
  double longitude_rad = 0.0;     ///< longitude (rad)
  double height_m = 0.0;          ///< ellipsoidal height (m)
  double measured_depth_m = 0.0;  ///< MD of the tie-on point (m)
  /// The hole's direction at the tie-on when known (a configured initial attitude): the
  /// listing's first DLS/build/turn and default vertical-section azimuth
  /// (experiment/survey_listing.hpp). Not used by minimum_curvature_path.
  std::optional<SurveyDirection> direction;
};

/// The map (projected CRS) coordinates of the well reference, the origin of north_m/east_m.
struct MapReference {
  double easting_m = 0.0;   ///< map easting of the tie-on (m, the CRS's false-origin frame)
  double northing_m = 0.0;  ///< map northing of the tie-on (m)
  /// Grid scale factor at the well (combined point scale and elevation factor): map distance
  /// = k x ground distance, in [0.99, 1.01]; 1 by default.
  double scale_factor = 1.0;
};

/// The unit of the extra listing a run writes: kMetre (survey.csv only, the default) or
/// kFoot (survey_ft.csv too: the international foot, 0.3048 m exactly).
enum class SurveyLengthUnit { kMetre, kFoot };

/// The references of the listing columns of survey.csv (experiment/survey_listing.hpp; the run
/// config's "survey" section, plugin/run_config.hpp).
struct SurveyListingOptions {
  std::optional<double> vertical_section_azimuth_deg;  ///< deg from true north, [0, 360)
  double ellipse_confidence = 0.95;                    ///< probability inside the ellipse, (0, 1)
  std::optional<double> datum_elevation_m;             ///< depth datum's elevation above MSL (m)
  /// The tie-on's TVD below the datum (m); absent: datum_elevation_m - tie_on.height_m.
  std::optional<double> tie_on_tvd_m;
  /// The survey sensor's distance behind the bit (m), >= 0: > 0 adds the projection-to-bit row.
  double sensor_to_bit_m = 0.0;
  /// Grid convergence (deg): grid north's angle from true north, clockwise positive (grid
  /// azimuth = true azimuth - convergence); absent: no grid azimuth (NaN).
  std::optional<double> grid_convergence_deg;
  /// The well reference's (the tie-on's) map coordinates: with them (and grid_convergence_deg)
  /// the listing gives every station's map easting and northing
  /// (experiment/survey_listing.hpp, map_coordinates); absent: those columns NaN.
  std::optional<MapReference> map_reference;
  /// kFoot: write survey_ft.csv beside survey.csv (write_survey_files).
  SurveyLengthUnit length_unit = SurveyLengthUnit::kMetre;
};

/// What a row of survey.csv is (its column station_type).
enum class SurveyStationType { kTieOn, kSurvey, kProjectionToBit };

/// The station_type text: "tie_on", "survey", "projection_to_bit".
std::string_view station_type_name(SurveyStationType type);

/// One survey station: exactly the columns of survey.csv, in that order.
struct SurveyStation {
  double t_s = 0.0;
  double md_m = 0.0;
  double inclination_deg = 0.0;
  double azimuth_deg = 0.0;
  double toolface_deg = 0.0;
  double tvd_m = 0.0;
  double north_m = 0.0;
  double east_m = 0.0;
  double inclination_sigma_deg = 0.0;
  double azimuth_sigma_deg = 0.0;
  double north_sigma_m = 0.0;
  double east_sigma_m = 0.0;
  double tvd_sigma_m = 0.0;
  /// Horizontal position covariance [[NN, NE], [NE, EE]] (m^2): the 2-sigma ellipse of the plot.
  Eigen::Matrix2d horizontal_covariance_m2 = Eigen::Matrix2d::Zero();
  /// Position covariance in (north, east, vertical down) (m^2), 3 x 3, from the filter's.
  Eigen::Matrix3d position_covariance_nev_m2 = Eigen::Matrix3d::Zero();
  /// The QC of the station from its connection's static data alone (experiment/station_qc.hpp):
  /// the survey.csv columns after the DESIGN.md ones.
  StationQc qc;
  /// 1-sigma of md_m relative to the tie-on (m), experiment/tally_smoother.hpp; NaN without
  /// depth readings or without the depth aid's stated sigma.
  double md_sigma_m = std::numeric_limits<double>::quiet_NaN();
  SurveyStationType type = SurveyStationType::kSurvey;
};

/// The point of the minimum-curvature well path at a station.
struct WellPathPoint {
  double md_m = 0.0;
  double north_m = 0.0;
  double east_m = 0.0;
  double tvd_m = 0.0;
};

/// The projection of `last` (a survey station) `distance_m` ahead along its attitude: MD,
/// north/east/TVD moved straight along its direction, everything else (attitude, sigmas,
/// covariance, time) the station's; type kProjectionToBit, QC undefined.
SurveyStation projected_to_bit(const SurveyStation& last, double distance_m);

/// Minimum-curvature positions of the stations (inclination and azimuth in deg), from the
/// tie-on at (0, 0, 0) and its measured depth; the first segment starts with the tie-on's
/// direction when given, else with the first station's (a straight first segment). One point
/// per station.
std::vector<WellPathPoint> minimum_curvature_path(
    const std::vector<SurveyStation>& stations, double tie_on_md_m,
    const std::optional<SurveyDirection>& tie_on_direction = std::nullopt);

/// Collects stations while a run goes, and an INS path (thinned) for the plot.
class SurveyRecorder final {
 public:
  /// With a budget, every station gets its static QC (StationQc) from the span observe() is
  /// given; without, the QC columns are NaN. With the depth aid's stated sigma, stations with
  /// depth readings get md_sigma_m; without, it is NaN.
  explicit SurveyRecorder(const SurveyTieOn& tie_on,
                          std::optional<StationQcBudget> qc_budget = std::nullopt,
                          std::optional<DepthReadingSigma> depth_sigma = std::nullopt);

  /// Call at every epoch at which any aid measured (and may be called at others).
  ///   state:        the navigator's state after the epoch's updates
  ///   covariance:   the 9 x 9 top-left block of P (dr ENU m, dv ENU m/s, phi rad)
  ///   stationary:   a zero-velocity update was accepted at this epoch
  ///   measured_depth_m: the SENSOR's measured depth read at this epoch (the tally minus the
  ///                 sensor-to-bit offset), if the run has one; a station's md_m is the mean
  ///                 of its stationary span's readings
  ///   truth:        the true state at this epoch, when there is truth (for survey_errors.csv)
  ///   static_span:  the raw increments of the connection's stationary span so far (its first
  ///                 stationary aid epoch to this one), for the station's QC; may be null
  void observe(const NavState& state, const Eigen::Matrix<double, 9, 9>& covariance,
               bool stationary, std::optional<double> measured_depth_m, const NavState* truth,
               const StaticSpan* static_span = nullptr);

  /// Records the tie-on row (SurveyStationType::kTieOn) from the navigation's start:
  ///   state:      the start's attitude (before any deliberate initial error; its position is
  ///               not used: the row is at (0, 0, 0))
  ///   covariance: the filter's initial 9 x 9 covariance (as observe()'s)
  /// Inclination and azimuth are the tie-on's direction where known (so that minimum curvature
  /// starts from what the row lists), else the state's. Call once, before the first observe().
  void record_tie_on(const NavState& state, const Eigen::Matrix<double, 9, 9>& covariance);

  /// The tie-on row: as recorded, else from the SurveyTieOn alone (its MD, its direction or NaN,
  /// position (0, 0, 0), time, toolface and sigmas NaN).
  SurveyStation tie_on_station() const;

  /// Closes an open connection at the end of the record (its last stationary epoch becomes a
  /// station). Call once, after the last epoch.
  void finish();

  /// One station per connection: a stationary span that closes within this MD of the last
  /// station (m) is the same connection resumed (a ZUPT rejected in the middle of it, the tool
  /// picked up and set down on the slips again) and replaces that station, so that MD strictly
  /// increases from station to station by more than this. A stand is 9-30 m.
  static constexpr double kSameConnectionMd_m = 1.0;

  const std::vector<SurveyStation>& stations() const { return stations_; }
  /// Errors of the stations that had truth at their epoch (estimate - truth; t_s, md_m and the
  /// sigmas left as the station's, see above), in station order: parallel to stations() when
  /// the run has truth throughout, empty when no station had truth.
  const std::vector<SurveyStation>& station_errors() const { return errors_; }
  /// The INS path in the tie-on frame, thinned (for the plot and well_path.csv).
  const std::vector<WellPathPoint>& ins_path() const { return ins_path_; }
  /// The TRUE path in the tie-on frame at the epochs of ins_path() that had truth (same
  /// thinning, MD the INS point's); empty for a run without truth.
  std::vector<WellPathPoint> truth_path() const;

 private:
  /// (north, east, tvd) of a state in the tie-on frame (m).
  Eigen::Vector3d tie_on_position_m(const NavState& state) const;
  /// The station a state would give (md from the argument or the INS path length).
  SurveyStation station_candidate(const NavState& state,
                                  const Eigen::Matrix<double, 9, 9>& covariance,
                                  const Eigen::Vector3d& position_m, double md_m) const;
  SurveyStation station_error(const SurveyStation& station, const NavState& state,
                              const NavState& truth) const;
  /// Appends the epoch's INS point and its truth point (NaN coordinates without truth).
  void append_to_paths(const WellPathPoint& point, const WellPathPoint& truth_point);
  void close_open_station();

  SurveyTieOn tie_on_;
  std::optional<StationQcBudget> qc_budget_;
  std::optional<DepthReadingSigma> depth_sigma_;
  StationaryDepthMean span_depth_;  ///< the readings of the current stationary span
  double north_m_per_rad_ = 0.0;    ///< (R_M(lat0) + h0): latitude change to north metres
  double east_m_per_rad_ = 0.0;     ///< (R_N(lat0) + h0) cos(lat0): longitude change to east metres
  std::vector<SurveyStation> stations_;
  std::vector<SurveyStation> errors_;
  std::vector<WellPathPoint> ins_path_;
  std::vector<WellPathPoint> truth_path_;  ///< parallel to ins_path_; NaN where no truth
  double ins_path_length_m_ = 0.0;
  std::optional<Eigen::Vector3d> previous_position_m_;  ///< last observed (north, east, tvd)
  std::size_t observed_count_ = 0;         ///< observe() calls so far (index of the next epoch)
  std::size_t path_stride_ = 1;            ///< every path_stride_-th epoch is kept in ins_path_
  bool last_path_point_is_extra_ = false;  ///< ins_path_.back() is the latest, off-stride epoch
  std::optional<SurveyStation> open_station_;
  std::optional<SurveyStation> open_error_;
  std::optional<SurveyStation> tie_on_station_;
};

/// Writes the survey files into temporary files beside their final paths in out_dir and
/// returns them uncommitted: the caller renames them into place (PendingFile::commit) together
/// with the run's other files, so a failed run leaves none of them.
///   survey.csv          the tie-on row, the stations and, with listing.sensor_to_bit_m > 0,
///                       the projection to the bit (header as DESIGN.md, then the QC columns,
///                       then the listing's of experiment/survey_listing.hpp under `listing`,
///                       station_type, ..., map_easting_m, map_northing_m). MD, inclination and azimuth enter the derived
///                       columns as printed (9 significant digits).
///   survey_ft.csv       with listing.length_unit kFoot: survey.csv's rows in international
///                       feet (0.3048 m), DLS/build/turn in deg/100 ft, columns named with
///                       _ft / _100ft (docs/navigation.md); map coordinates are not converted
///                       (their foot is the map projection's: international or US survey)
///   trajectory.xml      the tie-on, the survey stations and the projection to the bit as a
///                       WITSML 1.4.1.1 trajectory (experiment/witsml_trajectory.hpp)
///   survey_errors.csv   the stations' errors (DESIGN.md's and the QC columns, not the
///                       listing's), only when there are any
///   well_path.csv       md_m, north/east/tvd by minimum curvature at the stations, the INS
///                       path's points and, with truth, the true path's (column "source":
///                       minimum_curvature | ins | truth)
///   survey.png          plan view and vertical section along the listing's VS azimuth,
///                       2-sigma horizontal ellipses at the stations, the truth path when
///                       there is truth (when `plot` and gnuplot is installed; silently left
///                       out otherwise; survey/survey_plot.hpp). With one scale for east and
///                       north the ellipses, centred on the minimum-curvature points, and the
///                       +/-2-sigma TVD bars are magnified by the factor in the title (1, 2 or
///                       5 x 10^k) so that the largest ellipse spans about 3 % of the plan; a
///                       long straight hole gets independent axes and true-size ellipses.
///   iscwsa_covariance.csv, survey_uncertainty.png
///                       with `error_model`: the survey tool model's covariance of the stations
///                       beside the filter's (experiment/survey_error_files.hpp)
/// Throws InputError when a file cannot be written or gnuplot fails.
std::vector<std::unique_ptr<PendingFile>> write_survey_files(
    const SurveyRecorder& recorder, const SurveyTieOn& tie_on, const std::filesystem::path& out_dir,
    bool plot, const SurveyListingOptions& listing = {},
    const SurveyErrorModelRequest* error_model = nullptr);

}  // namespace stochnav
