#include "stochnav/survey_error/error_propagation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "leg_effects.hpp"
#include "stochnav/survey_error/continuous_gyro.hpp"
#include "stochnav/survey_error/weighting_functions.hpp"

namespace stochnav::survey_error {
namespace {

using Eigen::Matrix3d;

/// The gyrocompass station whose azimuth error a gyrocompass term has at station k: k itself,
/// or in a continuous survey the initialising station.
std::size_t gyrocompass_station(std::size_t k, std::size_t initialising) {
  return k > initialising ? initialising : k;
}

/// The tool constant a gyrocompass weight is multiplied by: the model's noise reduction factor
/// for GXY-RN, 1 for the others.
double gyrocompass_weight_factor(const SurveyErrorModel& model, WeightingFunction function) {
  return function == WeightingFunction::kGxyRn ? model.noise_reduction_factor : 1.0;
}

/// The source's effect at every station; zero at the tie-on (station 0). `initialising`: the
/// station that initialises a continuous survey (the number of stations when there is none).
std::vector<StationEffect> source_effects(const SurveyErrorModel& model, const ErrorSource& source,
                                          const std::vector<StationGeometry>& geometry,
                                          const WellParameters& well, std::size_t initialising) {
  const bool singular = has_near_vertical_form(source.weighting);
  const bool gyrocompass = is_gyrocompass_weighting(source.weighting);
  std::vector<StationEffect> effects(geometry.size());
  for (std::size_t k = 1; k < geometry.size(); ++k) {
    StationGeometry station = geometry[k];
    // Near vertical a 1/sin(I) azimuth weight takes its near-vertical form: the station is
    // evaluated as exactly vertical, its listed azimuth orienting the sideways tilt.
    if (singular && station.inclination_rad < well.vertical_inc_limit_rad) {
      station.inclination_rad = 0.0;
    }
    ErrorWeights w =
        error_weights(source.weighting, station, well, model.default_tortuosity_rad_per_m);
    if (gyrocompass) {
      // A continuous survey keeps the azimuth error of its initialising gyrocompass; it turns
      // this station's hole by sin(I) of this station.
      const StationGeometry& compass = geometry[gyrocompass_station(k, initialising)];
      w = {0.0, 0.0,
           std::sin(station.inclination_rad) * gyrocompass_weight_factor(model, source.weighting) *
               gyrocompass_azimuth_weight_s(source.weighting, compass, well)};
    }
    effects[k] =
        station_effect(geometry, k, w.depth_m, direction_change_nev(station, w),
                       leg_reach(source.weighting), model.first_station_turns_whole_first_leg);
  }
  return effects;
}

/// A model with gyrocompass terms needs a latitude and Earth rate a gyrocompass can work with,
/// and every gyrocompass station below 90 deg inclination (the weights divide by cos I).
void check_gyrocompass_geometry(const SurveyErrorModel& model,
                                const std::vector<StationGeometry>& geometry,
                                const WellParameters& well, std::size_t initialising) {
  const bool any = std::any_of(model.sources.begin(), model.sources.end(),
                               [](const auto& s) { return is_gyrocompass_weighting(s.weighting); });
  if (!any) return;
  const auto reject = [](const std::string& reason) {
    throw std::invalid_argument("survey_error::propagate_survey_errors: " + reason);
  };
  if (!(well.earth_rate_rad_s > 0.0)) reject("the Earth rate must be > 0");
  if (!(std::abs(well.latitude_rad) < std::numbers::pi / 2.0)) {
    reject("a gyrocompass needs a latitude below 90 deg");
  }
  for (std::size_t k = 1; k < geometry.size() && k <= initialising; ++k) {
    if (!(geometry[k].inclination_rad < std::numbers::pi / 2.0)) {
      reject(fmt::format(
          "the gyrocompass station at MD {:g} m is at 90 deg inclination or above, where the "
          "gyrocompass terms diverge (they divide by cos I); survey it with another model",
          geometry[k].md_m));
    }
  }
}

}  // namespace

SurveyCovariance propagate_survey_errors(const SurveyErrorModel& model,
                                         std::span<const ListingStation> stations,
                                         const WellParameters& well) {
  check_listing(stations, well, "survey_error::propagate_survey_errors");
  const std::vector<StationGeometry> geometry = station_geometries(stations, well);
  const std::size_t initialising =
      model.continuous_start_inclination_rad
          ? continuous_initialisation_station(stations, *model.continuous_start_inclination_rad)
          : stations.size();
  check_gyrocompass_geometry(model, geometry, well, initialising);
  SurveyCovariance result;
  for (const ListingStation& station : stations) result.md_m.push_back(station.md_m);
  result.total_nev_m2.assign(stations.size(), Matrix3d::Zero());
  const bool grid = well.azimuth_reference == AzimuthReference::kGrid;
  for (const ErrorSource& source : model.sources) {
    SourceCovariance covariance{
        source.code, source.mode,
        propagate_effects(source_effects(model, source, geometry, well, initialising),
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
