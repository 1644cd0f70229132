#include "stochnav/fit/implied_wavelet_variance.hpp"

#include <array>

namespace stochnav {

bool has_wavelet_variance_form(TermType type) {
  switch (type) {
    case TermType::kQuantization:
    case TermType::kAngleRandomWalk:
    case TermType::kBiasInstability:
    case TermType::kRateRandomWalk:
    case TermType::kRateRamp:
    case TermType::kGaussMarkov:
      return true;
    default:
      return false;
  }
}

double implied_wavelet_variance(const NoiseTerm& term, double scale_s) {
  const TermType type = term_type(term);
  if (!has_wavelet_variance_form(type)) return 0.0;
  std::array<double, 2> parameters{};
  for (std::size_t k = 0; k < parameter_specs(type).size() && k < parameters.size(); ++k) {
    parameters[k] = parameter_value(term, k).value_or(0.0);
  }
  return term_wavelet_variance(type, parameters.data(), scale_s);
}

double implied_wavelet_variance(const NoiseModel& model, double scale_s) {
  double sum = 0.0;
  for (const auto& term : model.terms) sum += implied_wavelet_variance(term, scale_s);
  return sum;
}

}  // namespace stochnav
