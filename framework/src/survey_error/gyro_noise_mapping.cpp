#include "stochnav/survey_error/gyro_noise_mapping.hpp"

#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "stochnav/core/units.hpp"
#include "stochnav/model/closed_forms.hpp"

namespace stochnav::survey_error {
namespace {

[[noreturn]] void reject_mapping_input(const std::string& reason) {
  throw std::invalid_argument("survey_error::map_gyro_noise_model: " + reason);
}

/// The variances (SI) the terms add to the three magnitudes.
struct MagnitudeVariances {
  double noise = 0.0;        ///< (rad/s)^2
  double drift = 0.0;        ///< (rad/s)^2
  double random_walk = 0.0;  ///< rad^2/s
};

/// The constant drift variance (rad/s)^2 equal, at the run's end, to that of the integral of a
/// Gauss-Markov bias started at 0 over the run; 0 for a run of no length.
double gauss_markov_drift_variance(const GaussMarkovTerm& term, double run_s) {
  if (!(run_s > 0.0)) return 0.0;
  const double tau = term.tau_c;
  return 2.0 * term.sigma * term.sigma * tau * tau * closed_form::ou_integral_shape(run_s / tau) /
         (run_s * run_s);
}

}  // namespace

MappedGyroTerms map_gyro_noise_model(const NoiseModel& model, double gyrocompass_time_s,
                                     double continuous_run_time_s,
                                     const ContinuousGyroTerms& tool) {
  if (quantity_of(model.unit) != Quantity::kAngularRate) {
    reject_mapping_input("the noise model is in " + unit_name(model.unit) +
                         ", not a gyro rate unit");
  }
  if (!(std::isfinite(gyrocompass_time_s) && gyrocompass_time_s > 0.0)) {
    reject_mapping_input("the gyrocompass averaging time must be finite and > 0");
  }
  if (!(std::isfinite(continuous_run_time_s) && continuous_run_time_s >= 0.0)) {
    reject_mapping_input("the continuous running time must be finite and >= 0");
  }
  const double t = gyrocompass_time_s;
  const double run_s = continuous_run_time_s;
  MagnitudeVariances v;
  MappedGyroTerms mapped{tool, {}};
  for (const NoiseTerm& term : model.terms) {
    std::visit(
        [&]([[maybe_unused]] const auto& x) {
          using Term = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<Term, AngleRandomWalkTerm>) {
            v.random_walk += x.n * x.n;
            v.noise += x.n * x.n / t;
          } else if constexpr (std::is_same_v<Term, QuantizationTerm>) {
            v.noise += 2.0 * x.q * x.q / (t * t);
          } else if constexpr (std::is_same_v<Term, BiasInstabilityTerm>) {
            v.drift += closed_form::kFlickerFloorPerB2 * x.b * x.b;
          } else if constexpr (std::is_same_v<Term, RateRandomWalkTerm>) {
            v.drift += x.k * x.k * run_s / 3.0;
          } else if constexpr (std::is_same_v<Term, GaussMarkovTerm>) {
            v.drift += gauss_markov_drift_variance(x, run_s);
          } else {
            mapped.ignored_terms.emplace_back(term_type_name(term_type(term)));
          }
        },
        term);
  }
  mapped.terms.noise_rad_s = std::sqrt(v.noise);
  mapped.terms.drift_rad_s = std::sqrt(v.drift);
  mapped.terms.random_walk_rad_per_sqrt_s = std::sqrt(v.random_walk);
  return mapped;
}

double continuous_run_time_s(std::span<const ListingStation> stations,
                             const ContinuousGyroTerms& terms) {
  const std::size_t initialising = continuous_initialisation_station(stations, terms);
  if (initialising + 1 >= stations.size()) return 0.0;
  return (stations.back().md_m - stations[initialising].md_m) / terms.running_speed_m_s;
}

}  // namespace stochnav::survey_error
