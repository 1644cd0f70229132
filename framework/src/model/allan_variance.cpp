#include "stochnav/model/allan_variance.hpp"

#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

#include "stochnav/model/closed_forms.hpp"

namespace stochnav {

double allan_variance(const NoiseTerm& term, double tau_s) {
  if (!(tau_s > 0.0) || !std::isfinite(tau_s)) return std::numeric_limits<double>::quiet_NaN();
  return std::visit(
      [tau_s](const auto& t) -> double {
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<T, QuantizationTerm>) {
          return closed_form::quantization_avar(t.q, tau_s);
        } else if constexpr (std::is_same_v<T, AngleRandomWalkTerm>) {
          return closed_form::angle_random_walk_avar(t.n, tau_s);
        } else if constexpr (std::is_same_v<T, BiasInstabilityTerm>) {
          return closed_form::bias_instability_avar(t.b);
        } else if constexpr (std::is_same_v<T, RateRandomWalkTerm>) {
          return closed_form::rate_random_walk_avar(t.k, tau_s);
        } else if constexpr (std::is_same_v<T, RateRampTerm>) {
          return closed_form::rate_ramp_avar(t.r, tau_s);
        } else if constexpr (std::is_same_v<T, GaussMarkovTerm>) {
          return closed_form::gauss_markov_avar(t.sigma, t.tau_c, tau_s);
        } else if constexpr (std::is_same_v<T, SinusoidTerm>) {
          return closed_form::sinusoid_avar(t.amplitude, t.frequency_hz, tau_s);
        } else {
          return 0.0;  // nonstationary: visible in DAVAR only
        }
      },
      term);
}

double allan_variance(const NoiseModel& model, double tau_s) {
  if (!(tau_s > 0.0) || !std::isfinite(tau_s)) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (const auto& term : model.terms) sum += allan_variance(term, tau_s);
  return sum;
}

}  // namespace stochnav
