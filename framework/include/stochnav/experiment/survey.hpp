#pragma once
// Survey stations of a drilling run: at every connection (the tool stationary, ZUPT applied)
// the filter's attitude and position become one station, as an MWD survey reports it.
//
// Conventions (DESIGN.md, `survey.csv`):
//   md_m          measured depth along the hole (m): from the aid data's "measured_depth_m" at the
//                 station when the run has it, else the tie-on depth plus the INS path length
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
// Minimum curvature (the industry's standard well-path method): between consecutive stations
// with (I1, A1) and (I2, A2) and a measured-depth step dMD, the dogleg angle
//   beta = acos(cos(I2 - I1) - sin I1 sin I2 (1 - cos(A2 - A1)))
// and ratio factor RF = (2 / beta) tan(beta / 2) (1 when beta = 0) give
//   dN = dMD / 2 (sin I1 cos A1 + sin I2 cos A2) RF
//   dE = dMD / 2 (sin I1 sin A1 + sin I2 sin A2) RF
//   dTVD = dMD / 2 (cos I1 + cos I2) RF,
// starting at the tie-on (0, 0, 0) with the first station's attitude.

#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "stochnav/ins/nav_state.hpp"
#include "stochnav/io/atomic_file.hpp"

namespace stochnav {

/// Where the well's local frame starts: the tie-on point (a known position on the well path).
struct SurveyTieOn {
  double latitude_rad = 0.0;      ///< geodetic latitude (rad)
  double longitude_rad = 0.0;     ///< longitude (rad)
  double height_m = 0.0;          ///< ellipsoidal height (m)
  double measured_depth_m = 0.0;  ///< MD of the tie-on point (m)
};

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
};

/// The point of the minimum-curvature well path at a station.
struct WellPathPoint {
  double md_m = 0.0;
  double north_m = 0.0;
  double east_m = 0.0;
  double tvd_m = 0.0;
};

/// Minimum-curvature positions of the stations (inclination and azimuth in deg), from the
/// tie-on at (0, 0, 0) and its measured depth; the first segment uses the first station's
/// attitude at both ends. One point per station.
std::vector<WellPathPoint> minimum_curvature_path(const std::vector<SurveyStation>& stations,
                                                  double tie_on_md_m);

/// Collects stations while a run goes, and an INS path (thinned) for the plot.
class SurveyRecorder final {
 public:
  explicit SurveyRecorder(const SurveyTieOn& tie_on);

  /// Call at every epoch at which any aid measured (and may be called at others).
  ///   state:        the navigator's state after the epoch's updates
  ///   covariance:   the 9 x 9 top-left block of P (dr ENU m, dv ENU m/s, phi rad)
  ///   stationary:   a zero-velocity update was accepted at this epoch
  ///   measured_depth_m: the aid data's measured depth at this epoch, if the run has one
  ///   truth:        the true state at this epoch, when there is truth (for survey_errors.csv)
  void observe(const NavState& state, const Eigen::Matrix<double, 9, 9>& covariance,
               bool stationary, std::optional<double> measured_depth_m, const NavState* truth);

  /// Closes an open connection at the end of the record (its last stationary epoch becomes a
  /// station). Call once, after the last epoch.
  void finish();

  const std::vector<SurveyStation>& stations() const { return stations_; }
  /// Errors of each station (estimate - truth; sigmas left as the station's), parallel to
  /// stations(); empty when the run had no truth at the stations.
  const std::vector<SurveyStation>& station_errors() const { return errors_; }
  /// The INS path in the tie-on frame, thinned (for the plot and well_path.csv).
  const std::vector<WellPathPoint>& ins_path() const { return ins_path_; }

 private:
  // Private members are the implementation's to choose.
  SurveyTieOn tie_on_;
  std::vector<SurveyStation> stations_;
  std::vector<SurveyStation> errors_;
  std::vector<WellPathPoint> ins_path_;
  double ins_path_length_m_ = 0.0;
  std::optional<NavState> previous_state_;
  std::optional<SurveyStation> open_station_;
  std::optional<SurveyStation> open_error_;
};

/// Writes the survey files into temporary files beside their final paths in out_dir and
/// returns them uncommitted: the caller renames them into place (PendingFile::commit) together
/// with the run's other files, so a failed run leaves none of them.
///   survey.csv          the stations (header exactly as DESIGN.md)
///   survey_errors.csv   the stations' errors (same columns), only when there are any
///   well_path.csv       md_m, north/east/tvd by minimum curvature at the stations, and the INS
///                       path's points (column "source": minimum_curvature | ins)
///   survey.png          plan view and vertical section, 2-sigma horizontal ellipses at the
///                       stations (when `plot` and gnuplot is installed)
std::vector<std::unique_ptr<PendingFile>> write_survey_files(const SurveyRecorder& recorder,
                                                             const SurveyTieOn& tie_on,
                                                             const std::filesystem::path& out_dir,
                                                             bool plot);

}  // namespace stochnav
