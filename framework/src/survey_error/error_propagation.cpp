#include "stochnav/survey_error/error_propagation.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "stochnav/survey_error/weighting_functions.hpp"

namespace stochnav::survey_error {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

[[noreturn]] void reject_listing(const std::string& reason) {
  throw std::invalid_argument("survey_error::propagate_survey_errors: " + reason);
}

void check_listing(std::span<const ListingStation> stations, const WellParameters& well) {
  if (stations.size() < 2) reject_listing("fewer than two stations");
  for (std::size_t k = 0; k < stations.size(); ++k) {
    const ListingStation& s = stations[k];
    if (!std::isfinite(s.md_m) || !std::isfinite(s.inclination_rad) ||
        !std::isfinite(s.azimuth_rad)) {
      reject_listing("station " + std::to_string(k) + " is not finite");
    }
    if (s.inclination_rad < 0.0 || s.inclination_rad > std::numbers::pi) {
      reject_listing("station " + std::to_string(k) + " has an inclination outside [0, pi]");
    }
    if (k > 0 && !(s.md_m > stations[k - 1].md_m)) {
      reject_listing("MD not strictly increasing at station " + std::to_string(k));
    }
  }
  if (stations.front().md_m != 0.0 && !well.tie_on_tvd_m) {
    reject_listing("the listing starts below MD 0 and the tie-on TVD is not given");
  }
}

/// Unit hole direction in NEV (V down).
Vector3d hole_direction(double inclination_rad, double azimuth_rad) {
  return {std::sin(inclination_rad) * std::cos(azimuth_rad),
          std::sin(inclination_rad) * std::sin(azimuth_rad), std::cos(inclination_rad)};
}

/// The station's geometry in the model's terms: true and magnetic azimuths, TVD by minimum
/// curvature, the previous station.
std::vector<StationGeometry> station_geometries(std::span<const ListingStation> stations,
                                                const WellParameters& well) {
  const double to_true_rad =
      well.azimuth_reference == AzimuthReference::kGrid ? well.convergence_rad : 0.0;
  std::vector<StationGeometry> geometry(stations.size());
  double tvd_m = well.tie_on_tvd_m.value_or(0.0);
  for (std::size_t k = 0; k < stations.size(); ++k) {
    StationGeometry& g = geometry[k];
    g.md_m = stations[k].md_m;
    g.inclination_rad = stations[k].inclination_rad;
    g.true_azimuth_rad = stations[k].azimuth_rad + to_true_rad;
    g.magnetic_azimuth_rad = g.true_azimuth_rad - well.declination_rad;
    const StationGeometry& previous = geometry[k == 0 ? 0 : k - 1];
    if (k > 0) {
      // Minimum curvature: the leg's vertical step is dMD / 2 (cos I1 + cos I2) times the ratio
      // factor (2 / dogleg) tan(dogleg / 2), the dogleg from the directions' half-angle form.
      const Vector3d t1 = hole_direction(previous.inclination_rad, previous.true_azimuth_rad);
      const Vector3d t2 = hole_direction(g.inclination_rad, g.true_azimuth_rad);
      const double dogleg_rad = 2.0 * std::atan2((t2 - t1).norm(), (t2 + t1).norm());
      const double ratio = dogleg_rad < 1e-9 ? 1.0 + dogleg_rad * dogleg_rad / 12.0
                                             : 2.0 / dogleg_rad * std::tan(dogleg_rad / 2.0);
      tvd_m += (g.md_m - previous.md_m) / 2.0 * (t1.z() + t2.z()) * ratio;
    }
    g.tvd_m = tvd_m;
    g.previous_md_m = previous.md_m;
    g.previous_inclination_rad = previous.inclination_rad;
    g.previous_true_azimuth_rad = previous.true_azimuth_rad;
  }
  return geometry;
}

/// How one unit of a source at a station moves the path: the leg before the station, and the
/// leg before plus the leg after (error_propagation.hpp: b_k and b_k + a_k without s).
struct StationEffect {
  Vector3d before = Vector3d::Zero();
  Vector3d before_and_after = Vector3d::Zero();
};

/// The source's effect at every station; zero at the tie-on (station 0).
std::vector<StationEffect> station_effects(const SurveyErrorModel& model, const ErrorSource& source,
                                           const std::vector<StationGeometry>& geometry,
                                           const WellParameters& well) {
  const std::size_t n = geometry.size();
  const bool whole_leg = leg_reach(source.weighting) == LegReach::kWholeLegBefore;
  const bool singular = has_near_vertical_form(source.weighting);
  std::vector<StationEffect> effects(n);
  for (std::size_t k = 1; k < n; ++k) {
    StationGeometry station = geometry[k];
    // Near vertical a 1/sin(I) azimuth weight takes its near-vertical form: the station is
    // evaluated as exactly vertical, its listed azimuth orienting the sideways tilt.
    if (singular && station.inclination_rad < well.vertical_inc_limit_rad) {
      station.inclination_rad = 0.0;
    }
    const ErrorWeights w =
        error_weights(source.weighting, station, well, model.default_tortuosity_rad_per_m);
    const double sin_i = std::sin(station.inclination_rad);
    const double cos_i = std::cos(station.inclination_rad);
    const double sin_a = std::sin(station.true_azimuth_rad);
    const double cos_a = std::cos(station.true_azimuth_rad);
    const Vector3d d_direction_d_inclination(cos_i * cos_a, cos_i * sin_a, -sin_i);
    const Vector3d horizontal_turn(-sin_a, cos_a, 0.0);
    const Vector3d direction_change =
        w.inclination_rad * d_direction_d_inclination + w.lateral_rad * horizontal_turn;
    const double step_before_m = geometry[k].md_m - geometry[k - 1].md_m;

    StationEffect& effect = effects[k];
    if (whole_leg) {
      effect.before = step_before_m * direction_change;
      effect.before_and_after = effect.before;
      continue;
    }
    const Vector3d t = hole_direction(geometry[k].inclination_rad, geometry[k].true_azimuth_rad);
    const Vector3d t_before =
        hole_direction(geometry[k - 1].inclination_rad, geometry[k - 1].true_azimuth_rad);
    const double turned_before_m =
        k == 1 && model.first_station_turns_whole_first_leg ? step_before_m : step_before_m / 2.0;
    effect.before = w.depth_m * (t_before + t) / 2.0 + turned_before_m * direction_change;
    effect.before_and_after = effect.before;
    if (k + 1 < n) {
      const Vector3d t_after =
          hole_direction(geometry[k + 1].inclination_rad, geometry[k + 1].true_azimuth_rad);
      const double step_after_m = geometry[k + 1].md_m - geometry[k].md_m;
      effect.before_and_after +=
          -w.depth_m * (t + t_after) / 2.0 + step_after_m / 2.0 * direction_change;
    }
  }
  return effects;
}

/// The covariance of one source at every station from its effects (error_propagation.hpp).
std::vector<Matrix3d> propagate_source(const std::vector<StationEffect>& effects, double magnitude,
                                       PropagationMode mode) {
  std::vector<Matrix3d> covariance(effects.size(), Matrix3d::Zero());
  Matrix3d random_sum = Matrix3d::Zero();      // sum over k < K of e_k e_k^T
  Vector3d correlated_sum = Vector3d::Zero();  // sum over k < K of e_k
  for (std::size_t k = 0; k < effects.size(); ++k) {
    const Vector3d at_station = magnitude * effects[k].before;
    const Vector3d passed_on = magnitude * effects[k].before_and_after;
    if (mode == PropagationMode::kRandom) {
      covariance[k] = random_sum + at_station * at_station.transpose();
      random_sum += passed_on * passed_on.transpose();
    } else {
      const Vector3d total = correlated_sum + at_station;
      covariance[k] = total * total.transpose();
      correlated_sum += passed_on;
    }
  }
  return covariance;
}

/// Rotates the horizontal axes of a true-north NEV covariance to grid north.
Matrix3d true_to_grid(const Matrix3d& covariance, double convergence_rad) {
  // A true azimuth a is the grid azimuth a - convergence.
  Matrix3d rotation = Matrix3d::Identity();
  rotation(0, 0) = std::cos(convergence_rad);
  rotation(0, 1) = std::sin(convergence_rad);
  rotation(1, 0) = -std::sin(convergence_rad);
  rotation(1, 1) = std::cos(convergence_rad);
  return rotation * covariance * rotation.transpose();
}

}  // namespace

SurveyCovariance propagate_survey_errors(const SurveyErrorModel& model,
                                         std::span<const ListingStation> stations,
                                         const WellParameters& well) {
  check_listing(stations, well);
  const std::vector<StationGeometry> geometry = station_geometries(stations, well);
  SurveyCovariance result;
  for (const ListingStation& station : stations) result.md_m.push_back(station.md_m);
  result.total_nev_m2.assign(stations.size(), Matrix3d::Zero());
  const bool grid = well.azimuth_reference == AzimuthReference::kGrid;
  for (const ErrorSource& source : model.sources) {
    SourceCovariance covariance{source.code, source.mode,
                                propagate_source(station_effects(model, source, geometry, well),
                                                 source.magnitude_si(), source.mode)};
    for (std::size_t k = 0; k < stations.size(); ++k) {
      if (grid) covariance.nev_m2[k] = true_to_grid(covariance.nev_m2[k], well.convergence_rad);
      result.total_nev_m2[k] += covariance.nev_m2[k];
    }
    result.sources.push_back(std::move(covariance));
  }
  return result;
}

}  // namespace stochnav::survey_error
