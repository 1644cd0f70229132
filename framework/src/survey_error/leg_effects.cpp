#include "leg_effects.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace stochnav::survey_error {

using Eigen::Matrix3d;
using Eigen::Vector3d;

void check_listing(std::span<const ListingStation> stations, const WellParameters& well,
                   const char* caller) {
  const auto reject = [caller](const std::string& reason) {
    throw std::invalid_argument(std::string(caller) + ": " + reason);
  };
  if (stations.size() < 2) reject("fewer than two stations");
  for (std::size_t k = 0; k < stations.size(); ++k) {
    const ListingStation& s = stations[k];
    if (!std::isfinite(s.md_m) || !std::isfinite(s.inclination_rad) ||
        !std::isfinite(s.azimuth_rad)) {
      reject("station " + std::to_string(k) + " is not finite");
    }
    if (s.inclination_rad < 0.0 || s.inclination_rad > std::numbers::pi) {
      reject("station " + std::to_string(k) + " has an inclination outside [0, pi]");
    }
    if (k > 0 && !(s.md_m > stations[k - 1].md_m)) {
      reject("MD not strictly increasing at station " + std::to_string(k));
    }
  }
  if (stations.front().md_m != 0.0 && !well.tie_on_tvd_m) {
    reject("the listing starts below MD 0 and the tie-on TVD is not given");
  }
}

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
      // The leg's vertical step by minimum curvature.
      tvd_m += minimum_curvature_step(
                   hole_direction_nev(previous.inclination_rad, previous.true_azimuth_rad),
                   hole_direction_nev(g.inclination_rad, g.true_azimuth_rad),
                   g.md_m - previous.md_m)
                   .z();
    }
    g.tvd_m = tvd_m;
    g.previous_md_m = previous.md_m;
    g.previous_inclination_rad = previous.inclination_rad;
    g.previous_true_azimuth_rad = previous.true_azimuth_rad;
  }
  return geometry;
}

Vector3d direction_change_nev(const StationGeometry& station, const ErrorWeights& weights) {
  const double sin_i = std::sin(station.inclination_rad);
  const double cos_i = std::cos(station.inclination_rad);
  const double sin_a = std::sin(station.true_azimuth_rad);
  const double cos_a = std::cos(station.true_azimuth_rad);
  const Vector3d d_direction_d_inclination(cos_i * cos_a, cos_i * sin_a, -sin_i);
  const Vector3d horizontal_turn(-sin_a, cos_a, 0.0);
  return weights.inclination_rad * d_direction_d_inclination +
         weights.lateral_rad * horizontal_turn;
}

StationEffect station_effect(const std::vector<StationGeometry>& geometry, std::size_t k,
                             double depth_change_m, const Vector3d& direction_change,
                             LegReach reach, bool whole_first_leg) {
  const double step_before_m = geometry[k].md_m - geometry[k - 1].md_m;
  StationEffect effect;
  if (reach == LegReach::kWholeLegBefore) {
    effect.before = step_before_m * direction_change;
    effect.before_and_after = effect.before;
    return effect;
  }
  const auto direction_at = [&](std::size_t i) {
    return hole_direction_nev(geometry[i].inclination_rad, geometry[i].true_azimuth_rad);
  };
  const Vector3d t = direction_at(k);
  const double turned_before_m = k == 1 && whole_first_leg ? step_before_m : step_before_m / 2.0;
  effect.before =
      depth_change_m * (direction_at(k - 1) + t) / 2.0 + turned_before_m * direction_change;
  effect.before_and_after = effect.before;
  if (k + 1 < geometry.size()) {
    const double step_after_m = geometry[k + 1].md_m - geometry[k].md_m;
    effect.before_and_after +=
        -depth_change_m * (t + direction_at(k + 1)) / 2.0 + step_after_m / 2.0 * direction_change;
  }
  return effect;
}

std::vector<StationEffect> unit_azimuth_effects(const std::vector<StationGeometry>& geometry) {
  std::vector<StationEffect> effects(geometry.size());
  for (std::size_t k = 1; k < geometry.size(); ++k) {
    const ErrorWeights azimuth{0.0, 0.0, std::sin(geometry[k].inclination_rad)};
    effects[k] = station_effect(geometry, k, 0.0, direction_change_nev(geometry[k], azimuth),
                                LegReach::kHalfLegsAround, false);
  }
  return effects;
}

std::vector<Matrix3d> propagate_effects(const std::vector<StationEffect>& effects, double magnitude,
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

std::vector<Matrix3d> propagate_loadings(const std::vector<StationEffect>& unit_effects,
                                         const Eigen::MatrixXd& loadings) {
  const std::size_t n = unit_effects.size();
  const auto variables = static_cast<std::size_t>(loadings.cols());
  // For each variable z_m: the sum over k < K of e_k loadings(k, m), the displacement of
  // station K by the errors of the stations before it.
  std::vector<Vector3d> passed_on(variables, Vector3d::Zero());
  std::vector<Matrix3d> covariance(n, Matrix3d::Zero());
  for (std::size_t k = 0; k < n; ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    for (std::size_t m = 0; m < variables; ++m) {
      const double loading = loadings(row, static_cast<Eigen::Index>(m));
      const Vector3d displacement = passed_on[m] + loading * unit_effects[k].before;
      covariance[k] += displacement * displacement.transpose();
      passed_on[m] += loading * unit_effects[k].before_and_after;
    }
  }
  return covariance;
}

Matrix3d true_to_grid(const Matrix3d& covariance, double convergence_rad) {
  // A true azimuth a is the grid azimuth a - convergence.
  Matrix3d rotation = Matrix3d::Identity();
  rotation(0, 0) = std::cos(convergence_rad);
  rotation(0, 1) = std::sin(convergence_rad);
  rotation(1, 0) = -std::sin(convergence_rad);
  rotation(1, 1) = std::cos(convergence_rad);
  return rotation * covariance * rotation.transpose();
}

}  // namespace stochnav::survey_error
