#include "stochnav/survey_error/continuous_gyro.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "leg_effects.hpp"
#include "stochnav/survey_error/weighting_functions.hpp"

namespace stochnav::survey_error {
namespace {

[[noreturn]] void reject_gyro_input(const std::string& reason) {
  throw std::invalid_argument("survey_error::continuous_gyro_covariance: " + reason);
}

/// The gyrocompass azimuth error per unit rate noise (s): NRF sqrt(1 - cos^2 AzT sin^2 I) /
/// (Omega cos phi cos I), the weighting function GXY-RN.
double gyrocompass_noise_gain_s(const StationGeometry& station, const WellParameters& well,
                                double noise_reduction_factor) {
  return noise_reduction_factor *
         gyrocompass_azimuth_weight_s(WeightingFunction::kGxyRn, station, well);
}

/// The continuous leg from the previous station to `to`: its running time and the sine of its
/// mean inclination.
struct ContinuousLeg {
  double time_s;
  double mean_sine;
};

ContinuousLeg continuous_leg(const StationGeometry& to, const ContinuousGyroTerms& terms) {
  return {(to.md_m - to.previous_md_m) / terms.running_speed_m_s,
          std::sin((to.inclination_rad + to.previous_inclination_rad) / 2.0)};
}

void check_gyro_inputs(const ContinuousGyroTerms& terms, const WellParameters& well,
                       const std::vector<StationGeometry>& geometry, std::size_t initialising) {
  if (!(terms.running_speed_m_s > 0.0)) reject_gyro_input("the running speed must be > 0");
  if (!(well.earth_rate_rad_s > 0.0)) reject_gyro_input("the Earth rate must be > 0");
  if (!(std::abs(well.latitude_rad) < std::numbers::pi / 2.0)) {
    reject_gyro_input("a gyrocompass needs a latitude below 90 deg");
  }
  if (!(terms.continuous_start_inclination_rad > 0.0 &&
        terms.continuous_start_inclination_rad < std::numbers::pi / 2.0)) {
    reject_gyro_input("the continuous start inclination must be in (0, 90) deg");
  }
  if (initialising < geometry.size() &&
      !(geometry[initialising].inclination_rad < std::numbers::pi / 2.0)) {
    reject_gyro_input("the initialising gyrocompass station is at 90 deg inclination or above");
  }
}

}  // namespace

ContinuousGyroTerms owsg_gyro_ns_ct_terms() {
  constexpr double kRadPerDegPerHour = kRadPerDeg / 3600.0;
  ContinuousGyroTerms terms;
  terms.noise_rad_s = 0.4 * kRadPerDegPerHour;
  terms.noise_reduction_factor = 0.4082;
  terms.drift_rad_s = 0.5 * kRadPerDegPerHour;
  terms.random_walk_rad_per_sqrt_s = 0.25 * kRadPerDeg / std::sqrt(3600.0);
  terms.running_speed_m_s = 2743.2 / 3600.0;
  terms.continuous_start_inclination_rad = 15.0 * kRadPerDeg;
  return terms;
}

std::size_t continuous_initialisation_station(std::span<const ListingStation> stations,
                                              double start_inclination_rad) {
  for (std::size_t k = 1; k < stations.size(); ++k) {
    if (stations[k].inclination_rad >= start_inclination_rad) return k;
  }
  return stations.size();
}

std::size_t continuous_initialisation_station(std::span<const ListingStation> stations,
                                              const ContinuousGyroTerms& terms) {
  return continuous_initialisation_station(stations, terms.continuous_start_inclination_rad);
}

std::vector<SourceCovariance> continuous_gyro_covariance(const ContinuousGyroTerms& terms,
                                                         std::span<const ListingStation> stations,
                                                         const WellParameters& well) {
  check_listing(stations, well, "survey_error::continuous_gyro_covariance");
  const std::vector<StationGeometry> geometry = station_geometries(stations, well);
  const std::size_t n = geometry.size();
  const std::size_t initialising = continuous_initialisation_station(stations, terms);
  check_gyro_inputs(terms, well, geometry, initialising);
  const auto row = [](std::size_t k) { return static_cast<Eigen::Index>(k); };

  // Loadings: the azimuth error (rad) of station k per unit of each independent variable.
  // GXY-RN: one variable per gyrocompass station (the tie-on has no error); the initialising
  // station's error stays in every later, continuous, station.
  Eigen::MatrixXd noise = Eigen::MatrixXd::Zero(row(n), row(n));
  for (std::size_t k = 1; k < n && k <= initialising; ++k) {
    const double gain = terms.noise_rad_s *
                        gyrocompass_noise_gain_s(geometry[k], well, terms.noise_reduction_factor);
    const std::size_t last = k == initialising ? n - 1 : k;
    for (std::size_t station = k; station <= last; ++station) noise(row(station), row(k)) = gain;
  }
  // GXY-GD: one variable, its error growing leg by leg; GXY-GRW: one variable per continuous
  // leg, its increment carried on to every later station.
  Eigen::MatrixXd drift = Eigen::MatrixXd::Zero(row(n), 1);
  Eigen::MatrixXd random_walk = Eigen::MatrixXd::Zero(row(n), row(n));
  double drift_error_rad = 0.0;
  for (std::size_t j = initialising + 1; j < n; ++j) {
    const ContinuousLeg leg = continuous_leg(geometry[j], terms);
    drift_error_rad += terms.drift_rad_s * leg.time_s / leg.mean_sine;
    drift(row(j), 0) = drift_error_rad;
    const double increment_rad =
        terms.random_walk_rad_per_sqrt_s * std::sqrt(leg.time_s) / leg.mean_sine;
    for (std::size_t station = j; station < n; ++station) {
      random_walk(row(station), row(j)) = increment_rad;
    }
  }

  return {
      {"GXY-RN", PropagationMode::kRandom,
       correlated_azimuth_error_covariance(stations, well, noise)},
      {"GXY-GD", PropagationMode::kSystematic,
       correlated_azimuth_error_covariance(stations, well, drift)},
      {"GXY-GRW", PropagationMode::kSystematic,
       correlated_azimuth_error_covariance(stations, well, random_walk)},
  };
}

}  // namespace stochnav::survey_error
