#pragma once
// A noise term's implied Haar wavelet variance in closed form, for the GMWM fit (gmwm_fit.hpp)
// and the plots. Natural units throughout (model/noise_term.hpp): scale_s in s, the result in
// signal^2 ((rad/s)^2 for gyros).
//
// The Haar MODWT coefficient at scale tau_j is half the difference of the means of the two
// halves of a window of tau_j (stats/wavelet_variance.hpp), and the Allan variance is half the
// mean squared difference of two adjacent means over tau, so for every term
//   nu^2(tau_j) = AVAR(tau_j / 2) / 2,
// exactly, with the AVAR closed forms of model/closed_forms.hpp (which are exact for records
// whose samples are interval means of the continuous rate, as sim/ makes them). So:
//   quantization       6 Q^2 / tau^2          angle_random_walk  N^2 / tau
//   rate_random_walk   K^2 tau / 12           rate_ramp          R^2 tau^2 / 16
//   bias_instability   (ln 2 / pi) B^2        gauss_markov       AVAR_GM(tau / 2) / 2
// The sinusoid and the time-domain terms have no GMWM form here.

#include <span>

#include "stochnav/model/closed_forms.hpp"
#include "stochnav/model/noise_model.hpp"
#include "stochnav/model/noise_term.hpp"

namespace stochnav {

/// Whether term_wavelet_variance has a form for this type (quantization, angle_random_walk,
/// bias_instability, rate_random_walk, rate_ramp, gauss_markov).
bool has_wavelet_variance_form(TermType type);

/// nu^2(scale_s) of one term of type `type` whose parameters, in parameter_specs(type) order and
/// natural units, are `parameters` (Q | N | B | K | R | sigma, tau_c). T is double or a
/// ceres::Jet. Types without a form (has_wavelet_variance_form false) give 0.
template <typename T>
T term_wavelet_variance(TermType type, const T* parameters, double scale_s) {
  const double half = 0.5 * scale_s;
  switch (type) {
    case TermType::kQuantization:
      return 0.5 * closed_form::quantization_avar(parameters[0], half);
    case TermType::kAngleRandomWalk:
      return 0.5 * closed_form::angle_random_walk_avar(parameters[0], half);
    case TermType::kBiasInstability:
      return 0.5 * closed_form::bias_instability_avar(parameters[0]);
    case TermType::kRateRandomWalk:
      return 0.5 * closed_form::rate_random_walk_avar(parameters[0], half);
    case TermType::kRateRamp:
      return 0.5 * closed_form::rate_ramp_avar(parameters[0], half);
    case TermType::kGaussMarkov:
      return 0.5 * closed_form::gauss_markov_avar(parameters[0], parameters[1], half);
    default:
      return T(0.0);
  }
}

/// nu^2(scale_s) of a term (0 for types without a form); scale_s > 0.
double implied_wavelet_variance(const NoiseTerm& term, double scale_s);

/// The sum over a model's terms.
double implied_wavelet_variance(const NoiseModel& model, double scale_s);

}  // namespace stochnav
