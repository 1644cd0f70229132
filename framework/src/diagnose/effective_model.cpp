#include "stochnav/diagnose/effective_model.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

namespace stochnav {

const NonstationaryTerm* find_nonstationary(const NoiseModel& model) {
  for (const NoiseTerm& term : model.terms) {
    if (const auto* nonstationary = std::get_if<NonstationaryTerm>(&term)) return nonstationary;
  }
  return nullptr;
}

NoiseModel stationary_part(const NoiseModel& model) {
  NoiseModel result{model.unit, model.rate_hz, {}};
  for (const NoiseTerm& term : model.terms) {
    if (term_type(term) != TermType::kNonstationary) result.terms.push_back(term);
  }
  return result;
}

namespace {

// Mean of scale^power over [t0, t1).
double mean_power(const NonstationaryTerm* term, double t0, double t1, int power) {
  if (term == nullptr || !(t1 > t0)) return 1.0;
  double inside = 0.0;
  double sum = 0.0;
  for (const auto& segment : term->segments) {
    const double overlap = std::min(segment.end_s, t1) - std::max(segment.start_s, t0);
    if (overlap <= 0.0) continue;
    inside += overlap;
    sum += overlap * std::pow(segment.scale, power);
  }
  return (sum + (t1 - t0 - inside)) / (t1 - t0);
}

}  // namespace

double mean_scale_power(const NoiseModel& model, double duration_s, int power) {
  return mean_power(find_nonstationary(model), 0.0, duration_s, power);
}

double mean_scale_squared(const NoiseModel& model, double t0_s, double t1_s) {
  return mean_power(find_nonstationary(model), t0_s, t1_s, 2);
}

NoiseTerm scale_amplitude(const NoiseTerm& term, double factor) {
  NoiseTerm result = term;
  std::visit(
      [factor](auto& t) {
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<T, QuantizationTerm>) {
          t.q *= factor;
        } else if constexpr (std::is_same_v<T, AngleRandomWalkTerm>) {
          t.n *= factor;
        } else if constexpr (std::is_same_v<T, BiasInstabilityTerm>) {
          t.b *= factor;
        } else if constexpr (std::is_same_v<T, RateRandomWalkTerm>) {
          t.k *= factor;
        } else if constexpr (std::is_same_v<T, RateRampTerm>) {
          t.r *= factor;
        } else if constexpr (std::is_same_v<T, GaussMarkovTerm>) {
          t.sigma *= factor;
        } else if constexpr (std::is_same_v<T, SinusoidTerm>) {
          t.amplitude *= factor;
        }
      },
      result);
  return result;
}

StationaryEquivalent stationary_equivalent(const NoiseModel& model, double duration_s) {
  StationaryEquivalent result;
  result.variance_factor = mean_scale_power(model, duration_s, 2);
  const double fourth = mean_scale_power(model, duration_s, 4);
  result.variance_inflation = result.variance_factor > 0.0
                                  ? fourth / (result.variance_factor * result.variance_factor)
                                  : 1.0;
  result.model = NoiseModel{model.unit, model.rate_hz, {}};
  const double amplitude = std::sqrt(result.variance_factor);
  for (const NoiseTerm& term : model.terms) {
    if (term_type(term) == TermType::kNonstationary) continue;
    result.model.terms.push_back(scale_amplitude(term, amplitude));
  }
  return result;
}

}  // namespace stochnav
