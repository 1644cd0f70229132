#include "stochnav/experiment/survey.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/minimum_curvature.hpp"
#include "stochnav/experiment/navigation_errors.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"

namespace stochnav {
namespace {

// Positions in kErrorMetricNames of the metrics a station uses.
constexpr std::size_t kInclinationMetric = 3;
constexpr std::size_t kToolfaceMetric = 4;
constexpr std::size_t kAzimuthMetric = 5;
static_assert(kErrorMetricNames[kInclinationMetric] == "inclination_err_deg");
static_assert(kErrorMetricNames[kToolfaceMetric] == "toolface_err_deg");
static_assert(kErrorMetricNames[kAzimuthMetric] == "azimuth_err_deg");

/// The INS path keeps at most this many points; beyond it every other point is dropped.
constexpr std::size_t kMaxInsPathPoints = 4000;

/// Keeps the points at even positions (those on a doubled stride). Returns whether the last
/// point was dropped (it was at an odd position).
bool keep_every_other_point(std::vector<WellPathPoint>& path) {
  const bool last_dropped = path.size() % 2 == 0;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < path.size(); i += 2) path[kept++] = path[i];
  path.resize(kept);
  return last_dropped;
}

}  // namespace

std::string_view station_type_name(SurveyStationType type) {
  switch (type) {
    case SurveyStationType::kTieOn:
      return "tie_on";
    case SurveyStationType::kSurvey:
      return "survey";
    case SurveyStationType::kProjectionToBit:
      return "projection_to_bit";
  }
  return "survey";
}

SurveyStation projected_to_bit(const SurveyStation& last, double distance_m) {
  SurveyStation projection = last;
  projection.type = SurveyStationType::kProjectionToBit;
  const Eigen::Vector3d step_ned =
      distance_m *
      hole_direction_nev(last.inclination_deg * kRadPerDeg, last.azimuth_deg * kRadPerDeg);
  projection.md_m += distance_m;
  projection.north_m += step_ned.x();
  projection.east_m += step_ned.y();
  projection.tvd_m += step_ned.z();
  projection.qc = station_qc(StaticSpan{}, StationQcBudget{}, last.t_s, last.inclination_deg,
                             last.inclination_sigma_deg, last.azimuth_deg, last.azimuth_sigma_deg);
  return projection;
}

std::vector<WellPathPoint> minimum_curvature_path(
    const std::vector<SurveyStation>& stations, double tie_on_md_m,
    const std::optional<SurveyDirection>& tie_on_direction) {
  std::vector<WellPathPoint> path;
  path.reserve(stations.size());
  WellPathPoint point{tie_on_md_m, 0.0, 0.0, 0.0};
  Eigen::Vector3d previous_direction;
  if (tie_on_direction) {
    previous_direction = hole_direction_nev(tie_on_direction->inclination_deg * kRadPerDeg,
                                            tie_on_direction->azimuth_deg * kRadPerDeg);
  }
  for (std::size_t i = 0; i < stations.size(); ++i) {
    const Eigen::Vector3d direction = hole_direction_nev(stations[i].inclination_deg * kRadPerDeg,
                                                         stations[i].azimuth_deg * kRadPerDeg);
    // A tie-on without an attitude of its own: the first segment is straight along the first
    // station's direction.
    if (i == 0 && !tie_on_direction) previous_direction = direction;
    const double md_step_m = stations[i].md_m - point.md_m;
    const Eigen::Vector3d step_ned =
        minimum_curvature_step(previous_direction, direction, md_step_m);
    point = {stations[i].md_m, point.north_m + step_ned.x(), point.east_m + step_ned.y(),
             point.tvd_m + step_ned.z()};
    path.push_back(point);
    previous_direction = direction;
  }
  return path;
}

SurveyRecorder::SurveyRecorder(const SurveyTieOn& tie_on, std::optional<StationQcBudget> qc_budget,
                               std::optional<DepthReadingSigma> depth_sigma)
    : tie_on_(tie_on), qc_budget_(qc_budget), depth_sigma_(depth_sigma) {
  const EarthRadii radii = earth_radii(tie_on.latitude_rad);
  north_m_per_rad_ = radii.meridian_m + tie_on.height_m;
  east_m_per_rad_ = (radii.transverse_m + tie_on.height_m) * std::cos(tie_on.latitude_rad);
}

Eigen::Vector3d SurveyRecorder::tie_on_position_m(const NavState& state) const {
  // The tie-on's local level frame, linearised at the tie-on: a well spans a few km, where the
  // curvature of the Earth changes north/east by millimetres.
  return {(state.latitude_rad - tie_on_.latitude_rad) * north_m_per_rad_,
          std::remainder(state.longitude_rad - tie_on_.longitude_rad, 2.0 * std::numbers::pi) *
              east_m_per_rad_,
          tie_on_.height_m - state.height_m};
}

SurveyStation SurveyRecorder::station_candidate(const NavState& state,
                                                const Eigen::Matrix<double, 9, 9>& covariance,
                                                const Eigen::Vector3d& position_m,
                                                double md_m) const {
  const MwdAttitude attitude = mwd_from_quaternion(state.q_nb);
  const auto sigmas = navigation_error_sigmas(state, covariance);
  SurveyStation station;
  station.t_s = state.t_s;
  station.md_m = md_m;
  station.inclination_deg = attitude.inclination_rad * kDegPerRad;
  station.azimuth_deg = attitude.azimuth_rad * kDegPerRad;
  station.toolface_deg = attitude.toolface_rad * kDegPerRad;
  station.north_m = position_m.x();
  station.east_m = position_m.y();
  station.tvd_m = position_m.z();
  station.inclination_sigma_deg = sigmas[kInclinationMetric];
  station.azimuth_sigma_deg = sigmas[kAzimuthMetric];
  // The covariance's position block is ENU: index 0 east, 1 north, 2 up (TVD is -up, same
  // variance).
  station.north_sigma_m = std::sqrt(covariance(1, 1));
  station.east_sigma_m = std::sqrt(covariance(0, 0));
  station.tvd_sigma_m = std::sqrt(covariance(2, 2));
  station.horizontal_covariance_m2 << covariance(1, 1), covariance(1, 0), covariance(0, 1),
      covariance(0, 0);
  // ENU -> (north, east, down): N = E_1, E = E_0, down = -U.
  Eigen::Matrix3d enu_to_nev;
  enu_to_nev << 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0;
  station.position_covariance_nev_m2 =
      enu_to_nev * covariance.topLeftCorner<3, 3>() * enu_to_nev.transpose();
  return station;
}

SurveyStation SurveyRecorder::station_error(const SurveyStation& station, const NavState& state,
                                            const NavState& truth) const {
  // Time, MD and sigmas stay the station's: the row is read as "error vs its sigma at MD".
  SurveyStation error = station;
  const auto angle_errors = navigation_errors(state, truth);
  error.inclination_deg = angle_errors[kInclinationMetric];
  error.azimuth_deg = angle_errors[kAzimuthMetric];
  error.toolface_deg = angle_errors[kToolfaceMetric];
  const Eigen::Vector3d true_position_m = tie_on_position_m(truth);
  error.north_m = station.north_m - true_position_m.x();
  error.east_m = station.east_m - true_position_m.y();
  error.tvd_m = station.tvd_m - true_position_m.z();
  return error;
}

void SurveyRecorder::observe(const NavState& state, const Eigen::Matrix<double, 9, 9>& covariance,
                             bool stationary, std::optional<double> measured_depth_m,
                             const NavState* truth, const StaticSpan* static_span) {
  const Eigen::Vector3d position_m = tie_on_position_m(state);
  if (previous_position_m_) ins_path_length_m_ += (position_m - *previous_position_m_).norm();
  previous_position_m_ = position_m;
  const double md_m = measured_depth_m.value_or(tie_on_.measured_depth_m + ins_path_length_m_);
  WellPathPoint truth_point{md_m, std::nan(""), std::nan(""), std::nan("")};
  if (truth != nullptr) {
    const Eigen::Vector3d true_position_m = tie_on_position_m(*truth);
    truth_point = {md_m, true_position_m.x(), true_position_m.y(), true_position_m.z()};
  }
  append_to_paths({md_m, position_m.x(), position_m.y(), position_m.z()}, truth_point);

  if (!stationary) {
    close_open_station();
    span_depth_.reset();
    return;
  }
  if (measured_depth_m) span_depth_.add(*measured_depth_m);
  // Still in the connection: this epoch replaces the previous candidate, so the station ends
  // up at the connection's last stationary epoch, after all of its ZUPTs, at the mean depth
  // of its readings so far.
  const bool has_readings = span_depth_.count() > 0;
  open_station_ =
      station_candidate(state, covariance, position_m, has_readings ? span_depth_.mean_m() : md_m);
  if (has_readings && depth_sigma_) {
    open_station_->md_sigma_m = span_depth_.sigma_m(*depth_sigma_, tie_on_.measured_depth_m);
  }
  open_station_->qc =
      station_qc(qc_budget_ && static_span ? *static_span : StaticSpan{},
                 qc_budget_.value_or(StationQcBudget{}), state.t_s, open_station_->inclination_deg,
                 open_station_->inclination_sigma_deg, open_station_->azimuth_deg,
                 open_station_->azimuth_sigma_deg);
  open_error_.reset();
  if (truth != nullptr) open_error_ = station_error(*open_station_, state, *truth);
}

void SurveyRecorder::record_tie_on(const NavState& state,
                                   const Eigen::Matrix<double, 9, 9>& covariance) {
  SurveyStation row =
      station_candidate(state, covariance, Eigen::Vector3d::Zero(), tie_on_.measured_depth_m);
  row.type = SurveyStationType::kTieOn;
  if (tie_on_.direction) {
    row.inclination_deg = tie_on_.direction->inclination_deg;
    row.azimuth_deg = tie_on_.direction->azimuth_deg;
  }
  row.md_sigma_m = 0.0;  // the reference of the others' MD sigmas
  row.qc = station_qc(StaticSpan{}, StationQcBudget{}, state.t_s, row.inclination_deg,
                      row.inclination_sigma_deg, row.azimuth_deg, row.azimuth_sigma_deg);
  tie_on_station_ = row;
}

SurveyStation SurveyRecorder::tie_on_station() const {
  if (tie_on_station_) return *tie_on_station_;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SurveyStation row;
  row.type = SurveyStationType::kTieOn;
  row.t_s = nan;
  row.md_m = tie_on_.measured_depth_m;
  row.inclination_deg = tie_on_.direction ? tie_on_.direction->inclination_deg : nan;
  row.azimuth_deg = tie_on_.direction ? tie_on_.direction->azimuth_deg : nan;
  row.toolface_deg = nan;
  row.inclination_sigma_deg = row.azimuth_sigma_deg = nan;
  row.north_sigma_m = row.east_sigma_m = row.tvd_sigma_m = nan;
  row.horizontal_covariance_m2.setConstant(nan);
  row.position_covariance_nev_m2.setConstant(nan);
  row.md_sigma_m = 0.0;
  row.qc = station_qc(StaticSpan{}, StationQcBudget{}, nan, nan, nan, nan, nan);
  return row;
}

void SurveyRecorder::finish() { close_open_station(); }

void SurveyRecorder::close_open_station() {
  if (!open_station_) return;
  const bool same_connection =
      !stations_.empty() && open_station_->md_m <= stations_.back().md_m + kSameConnectionMd_m;
  if (same_connection) {
    // The later span replaces the earlier one (after more ZUPTs), its error too.
    const bool had_error = !errors_.empty() && errors_.back().t_s == stations_.back().t_s;
    if (had_error) errors_.pop_back();
    stations_.pop_back();
  }
  stations_.push_back(*open_station_);
  if (open_error_) errors_.push_back(*open_error_);
  open_station_.reset();
  open_error_.reset();
}

std::vector<WellPathPoint> SurveyRecorder::truth_path() const {
  std::vector<WellPathPoint> path;
  for (const WellPathPoint& p : truth_path_) {
    if (!std::isnan(p.north_m)) path.push_back(p);
  }
  return path;
}

void SurveyRecorder::append_to_paths(const WellPathPoint& point, const WellPathPoint& truth_point) {
  // Memory stays flat over a 200-h record: the path keeps epochs 0, s, 2s, ... (s doubles
  // whenever it is full) plus the latest epoch, so it always reaches the current position.
  // The truth path is thinned alike, point for point.
  const std::size_t epoch = observed_count_++;
  if (last_path_point_is_extra_) {
    ins_path_.pop_back();
    truth_path_.pop_back();
  }
  ins_path_.push_back(point);
  truth_path_.push_back(truth_point);
  last_path_point_is_extra_ = epoch % path_stride_ != 0;
  if (last_path_point_is_extra_ || ins_path_.size() < kMaxInsPathPoints) return;
  keep_every_other_point(truth_path_);
  if (keep_every_other_point(ins_path_)) {
    ins_path_.push_back(point);
    truth_path_.push_back(truth_point);
    last_path_point_is_extra_ = true;
  }
  path_stride_ *= 2;
}

}  // namespace stochnav
