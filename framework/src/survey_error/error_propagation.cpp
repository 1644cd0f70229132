#include "stochnav/survey_error/error_propagation.hpp"

#include <stdexcept>

#include "leg_effects.hpp"
#include "stochnav/survey_error/weighting_functions.hpp"

namespace stochnav::survey_error {
namespace {

using Eigen::Matrix3d;

/// The source's effect at every station; zero at the tie-on (station 0).
std::vector<StationEffect> source_effects(const SurveyErrorModel& model, const ErrorSource& source,
                                          const std::vector<StationGeometry>& geometry,
                                          const WellParameters& well) {
  const bool singular = has_near_vertical_form(source.weighting);
  std::vector<StationEffect> effects(geometry.size());
  for (std::size_t k = 1; k < geometry.size(); ++k) {
    StationGeometry station = geometry[k];
    // Near vertical a 1/sin(I) azimuth weight takes its near-vertical form: the station is
    // evaluated as exactly vertical, its listed azimuth orienting the sideways tilt.
    if (singular && station.inclination_rad < well.vertical_inc_limit_rad) {
      station.inclination_rad = 0.0;
    }
    const ErrorWeights w =
        error_weights(source.weighting, station, well, model.default_tortuosity_rad_per_m);
    effects[k] =
        station_effect(geometry, k, w.depth_m, direction_change_nev(station, w),
                       leg_reach(source.weighting), model.first_station_turns_whole_first_leg);
  }
  return effects;
}

}  // namespace

SurveyCovariance propagate_survey_errors(const SurveyErrorModel& model,
                                         std::span<const ListingStation> stations,
                                         const WellParameters& well) {
  check_listing(stations, well, "survey_error::propagate_survey_errors");
  const std::vector<StationGeometry> geometry = station_geometries(stations, well);
  SurveyCovariance result;
  for (const ListingStation& station : stations) result.md_m.push_back(station.md_m);
  result.total_nev_m2.assign(stations.size(), Matrix3d::Zero());
  const bool grid = well.azimuth_reference == AzimuthReference::kGrid;
  for (const ErrorSource& source : model.sources) {
    SourceCovariance covariance{source.code, source.mode,
                                propagate_effects(source_effects(model, source, geometry, well),
                                                  source.magnitude_si(), source.mode)};
    for (std::size_t k = 0; k < stations.size(); ++k) {
      if (grid) covariance.nev_m2[k] = true_to_grid(covariance.nev_m2[k], well.convergence_rad);
      result.total_nev_m2[k] += covariance.nev_m2[k];
    }
    result.sources.push_back(std::move(covariance));
  }
  return result;
}

std::vector<Matrix3d> correlated_azimuth_error_covariance(std::span<const ListingStation> stations,
                                                          const WellParameters& well,
                                                          const Eigen::MatrixXd& loadings_rad) {
  check_listing(stations, well, "survey_error::correlated_azimuth_error_covariance");
  if (loadings_rad.rows() != static_cast<Eigen::Index>(stations.size())) {
    throw std::invalid_argument(
        "survey_error::correlated_azimuth_error_covariance: the loadings need one row per "
        "station");
  }
  std::vector<Matrix3d> covariance =
      propagate_loadings(unit_azimuth_effects(station_geometries(stations, well)), loadings_rad);
  if (well.azimuth_reference == AzimuthReference::kGrid) {
    for (auto& c : covariance) c = true_to_grid(c, well.convergence_rad);
  }
  return covariance;
}

}  // namespace stochnav::survey_error
