#include "stochnav/fit/implied_wavelet_variance.hpp"

#include <array>

namespace stochnav {

std::string_view gauss_markov_sampling_name(GaussMarkovSampling sampling) {
  return sampling == GaussMarkovSampling::kPoint ? "point" : "mean";
}

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

double implied_wavelet_variance(const NoiseTerm& term, double scale_s, double tau0_s,
                                GaussMarkovSampling sampling) {
  const TermType type = term_type(term);
  if (!has_wavelet_variance_form(type)) return 0.0;
  std::array<double, 2> parameters{};
  for (std::size_t k = 0; k < parameter_specs(type).size() && k < parameters.size(); ++k) {
    parameters[k] = parameter_value(term, k).value_or(0.0);
  }
  return term_wavelet_variance(type, parameters.data(), scale_s, tau0_s, sampling);
}

double implied_wavelet_variance(const NoiseModel& model, double scale_s,
                                GaussMarkovSampling sampling) {
  double sum = 0.0;
  for (const auto& term : model.terms) {
    sum += implied_wavelet_variance(term, scale_s, 1.0 / model.rate_hz, sampling);
  }
  return sum;
}

double sampled_autocovariance(const NoiseModel& model, std::size_t lag,
                              GaussMarkovSampling sampling) {
  const double tau0 = 1.0 / model.rate_hz;
  const auto k = static_cast<double>(lag);
  double sum = 0.0;
  for (const auto& term : model.terms) {
    if (const auto* n = std::get_if<AngleRandomWalkTerm>(&term)) {
      if (lag == 0) sum += n->n * n->n / tau0;
    } else if (const auto* q = std::get_if<QuantizationTerm>(&term)) {
      // The rate sample is the difference of two white angle errors of variance Q^2, / tau0.
      const double unit = q->q * q->q / (tau0 * tau0);
      if (lag == 0) sum += 2.0 * unit;
      if (lag == 1) sum -= unit;
    } else if (const auto* g = std::get_if<GaussMarkovTerm>(&term)) {
      const double h = tau0 / g->tau_c;
      const double s2 = g->sigma * g->sigma;
      if (sampling == GaussMarkovSampling::kPoint) {
        sum += s2 * std::exp(-k * h);
        continue;
      }
      // Interval means of the stationary process: Var = 2 s^2 T^2 (h - 1 + e^-h) / tau0^2,
      // Cov(lag k >= 1) = s^2 T^2 (1 - a)^2 a^(k - 1) / tau0^2 with a = e^-h. (Var - Cov(1)
      // = 2 s^2 T^2 g(h) / tau0^2 is the Allan variance at tau0, closed_form::gauss_markov_avar.)
      const double scale = s2 * g->tau_c * g->tau_c / (tau0 * tau0);
      sum += lag == 0 ? 2.0 * scale * (h + std::expm1(-h))
                      : scale * std::expm1(-h) * std::expm1(-h) * std::exp(-(k - 1.0) * h);
    }
  }
  return sum;
}

}  // namespace stochnav
