#pragma once
// A Gauss-Markov (AR1) term of short correlation time, named from the Haar wavelet variance by
// a GMWM fit (fit/gmwm_fit.hpp), for `stochnav diagnose` (record mode).
//
// Why the wavelet variance: a Gauss-Markov term whose correlation time tau_c is below a few
// sampling intervals tau0 bends the finest scales only (its Allan variance is white-noise like,
// 2 sigma^2 tau_c / tau, beyond a few tau_c, and below that line at tau0). The Allan candidate
// fits of diagnose search tau_c >= tau0 and read octaves whose estimator covariance smears the
// first ones together, so they either miss it or leave it on their bound. The GMWM closed form
// of the interval-mean Gauss-Markov term (fit/implied_wavelet_variance.hpp) resolves tau_c down
// to tau0 / 4 at scales whose wavelet variances are nearly independent.
//
// Test (natural units; scales as the `wv` package's):
//   base   the model's terms with a wavelet-variance form, once each (Gauss-Markov terms as often
//          as they are there), plus angle_random_walk when absent, minus Gauss-Markov terms with
//          tau_c <= kShortTauMaxSamples tau0 (what is tested). A sinusoid is held at its value:
//          its implied wavelet variance, AVAR(tau_j / 2) / 2, comes off the measured one (levels
//          left <= 0 are dropped). A model with a nonstationary term is not tested (its windows
//          disagree: the stationary wavelet variance does not describe it).
//   fits   A: the base by GMWM; B: the base plus one Gauss-Markov term, tau_c searched in
//          [kGmwmMinCorrelationTimeSamples, kShortTauMaxSamples] tau0. Terms left on a search
//          bound are dropped and the rest refitted (GmwmOptions::drop_terms_at_bound).
//   named  when B's objective (a chi-square: Omega = V^-1, gmwm_fit.hpp) is lower than A's by
//          more than chi2_2(1 - alpha) (two more parameters), the new term's tau_c is not on the
//          upper end of the searched range (within 1 %: a longer correlation, the Allan loop's
//          business), and the new term makes up at least min_term_share of B's wavelet variance
//          at some scale (material; as DiagnoseOptions::min_term_share for the Allan loop). A tau_c
//          on the lower end (tau0 / 4) is named and flagged: the significant drop says the finest
//          scales are not white, the bound says the correlation time is of that order or shorter
//          (not an estimate).
// The false-alarm rate and the detection rate on simulated records are measured by
// tests/diagnose/wavelet_findings_test.cpp (docs/diagnose.md has the numbers).

#include <cstddef>
#include <string>
#include <vector>

#include "stochnav/fit/gmwm_data.hpp"
#include "stochnav/model/noise_model.hpp"
#include "stochnav/stats/noise_id.hpp"  // lag1_autocorrelation, for callers

namespace stochnav {

/// The longest correlation time, in sampling intervals, tested as "short".
inline constexpr double kShortTauMaxSamples = 4.0;

struct ShortTauOptions {
  double alpha = 1e-3;          ///< false-alarm probability of the objective drop, (0, 0.5)
  double min_term_share = 0.1;  ///< the new term's least share at some scale, [0, 1)
};

struct ShortTauGaussMarkovCheck {
  bool applicable = false;
  std::string not_applicable;  ///< why not, when !applicable
  bool robust = false;         ///< fitted to the robust wavelet variance (outliers flagged)
  std::vector<TermType> base_terms;
  std::size_t scales = 0;              ///< wavelet-variance levels fitted
  double objective_without = 0.0;      ///< fit A (chi-square)
  double objective_with = 0.0;         ///< fit B
  double threshold = 0.0;              ///< chi2_2(1 - alpha)
  bool significant = false;            ///< objective_without - objective_with > threshold
  bool at_lower_end = false;           ///< tau_c within 1 % of the searched range's lower end
  bool at_upper_end = false;           ///< within 1 % of its upper end (not short: not named)
  double largest_share = 0.0;          ///< the new term's largest share of B's wavelet variance
  double largest_share_scale_s = 0.0;  ///< the scale where it is largest (s)
  bool named = false;                  ///< significant, material, not at_upper_end
  /// The model already had a Gauss-Markov term with tau_c <= kShortTauMaxSamples tau0 (the
  /// Allan loop may add one on its tau_c bound): the fit here places it.
  bool in_model = false;
  NoiseTerm term = GaussMarkovTerm{};  ///< the new term of fit B (natural units)
  double sigma_sigma = 0.0;            ///< 1-sigma uncertainty of sigma (natural units)
  double tau_c_sigma = 0.0;            ///< of tau_c (s)
  NoiseModel fitted;                   ///< fit B's model (natural units)
  double lag1_model = 0.0;             ///< lag-1 autocorrelation of fit B's stationary short terms
  double lag1_record = 0.0;            ///< the record's lag-1 autocorrelation (as given)

  /// One paragraph: the finding (or why not) with numbers, in the reporting units of `unit`.
  std::string summary(Unit unit) const;
};

/// The test above. `data`: the record's wavelet variance (natural units; classical, or robust
/// when outliers were flagged: `robust` says which); `model`: the final stochastic model of
/// diagnose (natural units); `lag1_record`: the record's lag-1 autocorrelation, reported beside
/// the fit's. Never throws for a fit that cannot be made: the check is then not applicable.
ShortTauGaussMarkovCheck check_short_tau_gauss_markov(const GmwmData& data, bool robust,
                                                      const NoiseModel& model, double lag1_record,
                                                      const ShortTauOptions& options = {});

}  // namespace stochnav
