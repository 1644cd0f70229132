#pragma once
// Generalized Method of Wavelet Moments (GMWM; Guerrier, Skaloud, Stebler, Victoria-Feser,
// JASA 2013; the R package `gmwm`, SMAC-Group): the noise terms whose implied Haar wavelet
// variance nu(theta) (fit/implied_wavelet_variance.hpp) is closest to the measured one nu_hat,
//   theta_hat = argmin (nu_hat - nu(theta))^T Omega (nu_hat - nu(theta)),
// solved with Ceres (Levenberg-Marquardt on the whitened residuals).
//
// Omega: diagonal, Omega_jj = 1 / V_jj with V_jj = ((wv_hi_j - wv_lo_j) / (2 z_0.975))^2, the
// variance of nu_hat_j read off its 95 % chi-square interval. This is the `gmwm` package's fast
// diagonal approximation (its diag(1 / (ci_high - ci_low)^2), here rescaled by (2 z)^2 so the
// objective is a chi-square statistic). For the robust wavelet variance the interval is wider
// (1 / efficiency), and so is V.
//
// Parameters: the natural logarithm of each coefficient (Q, N, B, K, |R|, Gauss-Markov sigma
// and tau_c): positive by construction (the package's log sigma^2 and transformed phi, in the
// units of DESIGN.md), bounded to a wide box around the data's scale (tau_c to
// [tau0 / 4, 10 tau_J]: kGmwmMinCorrelationTimeSamples). A Gauss-Markov term's wavelet variance
// is that of interval means of the process (default) or of its point samples, the package's
// discrete AR1 (GmwmOptions::gauss_markov_sampling; they differ for tau_c within a few tau0).
// A parameter left on its bound marks its term failed: GmwmOptions::drop_terms_at_bound drops
// such terms and refits, as the Allan fit does.
//
// Starting values: every term's wavelet variance is linear in its variance coefficient (Q^2,
// N^2, B^2, K^2, R^2, sigma^2) once the Gauss-Markov correlation times are set. So for every
// combination of correlation times on a grid over the scales (tau0 / 4 .. tau_J, two or more
// per octave, tau_c ascending across repeated Gauss-Markov terms, none equal), the variances
// come from a non-negative weighted least-squares solve (exact, by enumeration of the active
// set), and the `starts` best combinations, with distinct correlation times, start Ceres; the
// best optimum is kept. A start on the grid never puts a Gauss-Markov term at a correlation
// time the wavelet variance does not support, which is where single starts land in
// short-correlation-time local minima.
//
// Uncertainties: delta method, Cov(log theta) = (A^T Omega A)^-1, A = d nu / d log theta at the
// optimum (valid when Omega = V^-1 and the model is right); c_sigma = c sigma_log c. NaN when
// A^T Omega A is singular.
//
// Goodness of fit (J-test): with Omega = V^-1 the objective is about chi-square with
// scales - free parameters degrees of freedom when the model is right. Assumption: the wavelet
// variances of different scales are independent (Omega diagonal); they are nearly so for
// white noise, positively correlated for the random walk, where the test is then liberal.
// FitDiagnostics::chi_square holds the objective, failed() applies the test at 1e-6.
//
// Model ranking: WIC = objective + optimism, the `gmwm` package's `rank_models` criterion
// (Guerrier et al.) with the optimism's asymptotic form 2 tr(Omega A (A^T Omega A)^-1 A^T Omega
// V), which is 2 (free parameters) when V = Omega^-1 as here.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "stochnav/fit/fit_noise_terms.hpp"
#include "stochnav/fit/gmwm_data.hpp"
#include "stochnav/fit/implied_wavelet_variance.hpp"
#include "stochnav/fit/parameter_control.hpp"

namespace stochnav {

struct GmwmOptions {
  /// The terms, repeats allowed for gauss_markov (quantization, angle_random_walk,
  /// bias_instability, rate_random_walk, rate_ramp, gauss_markov).
  std::vector<TermType> terms;
  /// Starting values, fixed values and bounds of the terms' parameters (fit/parameter_control.hpp).
  std::vector<ParameterControl> controls;
  std::size_t starts = 4;   ///< best grid starts optimised, >= 1
  int max_iterations = 200;  ///< Ceres iterations per start, >= 1
  /// How the record samples a Gauss-Markov term (fit/implied_wavelet_variance.hpp): kPoint is
  /// the discrete AR1 of the `gmwm` package, kIntervalMean the convention of sim/ and of the
  /// Allan fit. They differ only for tau_c within a few sampling intervals.
  GaussMarkovSampling gauss_markov_sampling = GaussMarkovSampling::kIntervalMean;
  /// A term left with a parameter on its search bound is a failed term: true drops it and
  /// refits without it (repeatedly, while a term is left that is not on a bound; controls of a
  /// dropped term go with it), naming it in FitDiagnostics::dropped_terms and warnings, as the
  /// Allan fit's FitOptions::drop_terms_at_bound does; false (default) keeps it (at_bound).
  bool drop_terms_at_bound = false;

  /// Empty when valid; otherwise the reason (a term without a GMWM form, a control refused by
  /// check_parameter_controls: out of range, every parameter fixed, two Gauss-Markov terms
  /// starting or fixed at the same tau_c).
  std::string validate() const;
};

/// Fits the terms. Throws InputError for unusable data (validate(data)), ConfigError for
/// invalid options, fewer scales than free parameters + 1, or a rate_ramp with fewer than
/// kGmwmRampMinScales scales. The result's diagnostics carry method kGmwm, cost = chi_square =
/// the objective, criterion_value = WIC, points = scales, parameters = free parameters.
FitResult fit_gmwm(const GmwmData& data, const GmwmOptions& options);

/// A drift (rate_ramp) is told from a random walk by the curvature of the top octaves of the
/// wavelet variance (slope 2 against 1): it needs at least this many scales (512 samples).
inline constexpr std::size_t kGmwmRampMinScales = 8;

/// The shortest Gauss-Markov correlation time searched, in sampling intervals. Below it a
/// Gauss-Markov term is white noise for the wavelet variance (interval means: density
/// 2 sigma^2 tau_c and a lag-1 correlation of about tau_c / (2 tau0); point samples: phi < 0.02)
/// and trades off with a white-noise term along a flat valley of the objective. On the ADIS16405
/// gyro the optimum is at 0.26 tau0, inside the bound (docs/gmwm.md).
inline constexpr double kGmwmMinCorrelationTimeSamples = 0.25;

/// Fits every candidate term list (each with `common`'s starts, iteration limit, sampling and
/// drop_terms_at_bound; controls are not used) and returns them ranked by WIC, best first:
/// FitResult::ranking of the first holds the whole ranking, each entry with the candidate's
/// terms as given (and those dropped from it). Candidates that cannot be fitted (too few
/// scales) throw as fit_gmwm does.
std::vector<FitResult> rank_gmwm_models(const GmwmData& data,
                                        std::span<const std::vector<TermType>> candidates,
                                        const GmwmOptions& common);

}  // namespace stochnav
