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
//
// Gauss-Markov sampling. The two ways a Gauss-Markov process of standard deviation sigma and
// correlation time tau_c becomes samples at interval tau0 are different discrete processes
// when tau_c is near tau0 or below it (for tau_c >> tau0 both forms agree):
//   - interval means (kIntervalMean, the convention of sim/ and of the Allan closed forms): the
//     samples are an ARMA(1,1); as tau_c / tau0 -> 0 the term fades to white noise of spectral
//     density 2 sigma^2 tau_c, lag-1 correlation (tau_c / tau0) / 2 for small tau_c / tau0;
//   - point samples (kPoint): the samples x_k = x(k tau0) are exactly the discrete AR1
//     x_k = phi x_(k-1) + w_k, phi = exp(-tau0 / tau_c), Var x_k = sigma^2, which is the
//     `gmwm` package's AR1(phi, sigma2 = sigma^2 (1 - phi^2)) and what a filter's
//     Gauss-Markov state (Phi = exp(-dt / tau_c)) adds to a sample. Lag-k correlation phi^k;
//     as tau_c -> 0 it becomes white noise of variance sigma^2 per sample.
// The point form (derived from the AR1 autocovariance sigma^2 phi^|k|, m = tau / (2 tau0)):
//   nu^2(tau) = sigma^2 [m (1 - phi^2) - 3 phi + 4 phi^(m+1) - phi^(2m+1)] / (2 m^2 (1 - phi)^2).

#include <cmath>
#include <span>

#include "stochnav/model/closed_forms.hpp"
#include "stochnav/model/noise_model.hpp"
#include "stochnav/model/noise_term.hpp"

namespace stochnav {

/// How a Gauss-Markov term's samples are taken (see the header comment).
enum class GaussMarkovSampling {
  kIntervalMean,  ///< samples are means of the process over their interval (sim/, avar fit)
  kPoint,         ///< samples are the process at instants: a discrete AR1 (the gmwm package's)
};

/// "mean" | "point".
std::string_view gauss_markov_sampling_name(GaussMarkovSampling sampling);

/// The numerator f(m, h) = m (1 - phi^2) - 3 phi + 4 phi^(m+1) - phi^(2m+1), phi = exp(-h), of
/// the point-sampled Gauss-Markov wavelet variance. f ~ (2 m^3 + m) h^3 / 3 for small h, where
/// the closed expression cancels: an exact Taylor series is used below (2m + 1) h = 0.1,
/// sum_(k>=3) (-1)^k [4 (m+1)^k - (2m+1)^k - 2^k m - 3] h^k / k! (terms k = 1, 2 vanish).
template <typename T>
T point_gauss_markov_numerator(double m, const T& h) {
  using std::exp;
  using std::expm1;
  if (h * (2.0 * m + 1.0) < T(0.1)) {
    T sum(0.0);
    T power = h * h;
    double factorial = 2.0;
    for (int k = 3; k <= 16; ++k) {
      power = power * h;
      factorial *= k;
      const double coefficient =
          4.0 * std::pow(m + 1.0, k) - std::pow(2.0 * m + 1.0, k) - std::exp2(k) * m - 3.0;
      sum = sum + power * ((k % 2 == 0 ? 1.0 : -1.0) * coefficient / factorial);
    }
    return sum;
  }
  // m (1 - phi^2) - 4 phi (1 - phi^m) + phi (1 - phi^(2m)), each 1 - phi^n as -expm1(-n h).
  const T phi = exp(-h);
  return -m * expm1(T(-2.0) * h) + T(4.0) * phi * expm1(-m * h) - phi * expm1(T(-2.0 * m) * h);
}

/// nu^2(scale_s) of a Gauss-Markov term (sigma, tau_c) point-sampled at tau0_s: the discrete
/// AR1's exact Haar wavelet variance. scale_s = 2 m tau0_s (m >= 1; m need not be an integer).
template <typename T>
T point_gauss_markov_wavelet_variance(const T& sigma, const T& tau_c, double tau0_s,
                                      double scale_s) {
  using std::expm1;
  const double m = 0.5 * scale_s / tau0_s;
  const T h = T(tau0_s) / tau_c;
  const T one_minus_phi = -expm1(-h);
  return sigma * sigma * point_gauss_markov_numerator(m, h) /
         (T(2.0 * m * m) * one_minus_phi * one_minus_phi);
}

/// Whether term_wavelet_variance has a form for this type (quantization, angle_random_walk,
/// bias_instability, rate_random_walk, rate_ramp, gauss_markov).
bool has_wavelet_variance_form(TermType type);

/// nu^2(scale_s) of one term of type `type` whose parameters, in parameter_specs(type) order and
/// natural units, are `parameters` (Q | N | B | K | R | sigma, tau_c), for a record sampled at
/// tau0_s (> 0; only the point-sampled Gauss-Markov form uses it). T is double or a
/// ceres::Jet. Types without a form (has_wavelet_variance_form false) give 0.
template <typename T>
T term_wavelet_variance(TermType type, const T* parameters, double scale_s, double tau0_s,
                        GaussMarkovSampling sampling) {
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
      if (sampling == GaussMarkovSampling::kPoint) {
        return point_gauss_markov_wavelet_variance(parameters[0], parameters[1], tau0_s, scale_s);
      }
      return 0.5 * closed_form::gauss_markov_avar(parameters[0], parameters[1], half);
    default:
      return T(0.0);
  }
}

/// nu^2(scale_s) of a term (0 for types without a form); scale_s > 0, tau0_s > 0.
double implied_wavelet_variance(const NoiseTerm& term, double scale_s, double tau0_s,
                                GaussMarkovSampling sampling);

/// The sum over a model's terms, sampled at 1 / model.rate_hz.
double implied_wavelet_variance(const NoiseModel& model, double scale_s,
                                GaussMarkovSampling sampling);

/// The autocovariance at lag `lag` samples (natural units squared) of the samples at tau0_s of
/// the stationary terms with a lag structure (angle_random_walk: N^2 / tau0 at lag 0;
/// quantization: 2 Q^2 / tau0^2 at lag 0, -Q^2 / tau0^2 at lag 1; gauss_markov as `sampling`
/// gives it). Other terms give 0 (rate_random_walk, rate_ramp, bias_instability have no
/// stationary autocovariance at the sampling interval). Used to compare a fit's lag-1
/// correlation with the record's.
double sampled_autocovariance(const NoiseModel& model, std::size_t lag,
                              GaussMarkovSampling sampling);

}  // namespace stochnav
