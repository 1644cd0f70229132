#pragma once
// Robust least-squares fit of the noise terms to a measured Allan-variance curve (Ceres).
//
// Model: sigma^2(tau) = sum of the closed forms of model/closed_forms.hpp over the chosen terms.
//
// Residuals, one per point, in the log domain where the estimator's scatter is nearly Gaussian:
//   r_i = (log model(tau_i) - log avar_i + b_i) / s_i,
// with nu_i the point's EDF and, for an estimate distributed as avar chi2(nu)/nu,
//   b_i = E[log(chi2(nu)/nu)] = digamma(nu/2) - log(nu/2)   (about -1/nu: removes the bias of
//                                                            the log of a noisy variance),
//   s_i^2 = Var[log(chi2(nu)/nu)] = trigamma(nu/2)           (about 2/nu).
// So each r_i is about N(0, 1) when the model is right. The cost 1/2 sum rho(r_i^2) uses a robust
// loss (default Huber with scale 2: quadratic within 2 sigma, linear beyond, so a single bad
// point pulls like a 2-sigma one).
//
// Weights: a pilot fit uses the input edf, made non-increasing in tau (an EDF that grows with tau
// is a noise misidentification). When FitData::phase_count is known (OADEV of one record), the
// EDF of each point and the correlation matrix R of the points then come from the covariance of
// the estimates under the pilot model (fit/oadev_covariance.hpp); the terms are selected (or
// fitted) again with those EDFs, reweighted once more with the final model and refitted.
//
// Parameters: the natural logarithm of each coefficient (Q, N, B, K, |R|, Gauss-Markov sigma and
// tau_c, sinusoid amplitude and frequency), which keeps them positive and well scaled, bounded
// to a wide box around the data's scale. Uncertainties: ceres::Covariance of the log parameters
// (dense SVD pseudo-inverse) C = (J^T J)^-1 at the optimum, and with correlated points the
// sandwich C J^T R J C (neighbouring octave taus correlate at about 0.5 to 0.9, so treating them
// as independent would understate the uncertainties by up to 2x); mapped to each coefficient c
// as sigma_c = c sigma_log c. A parameter at its bound (a term the data do not support) gets NaN.
//
// Term selection: with an explicit term list, those terms are fitted (added one at a time, each
// from several starts, then refitted jointly). Otherwise, greedy forward selection over
// `candidates`: start from the best single term, then add the candidate that lowers the
// information criterion most, while it lowers it by more than min_criterion_improvement (10 by
// default); then drop any term whose removal does not raise it by that much. Criteria on the
// robust cost: AIC = 2 cost + 2 p, BIC = 2 cost + p ln(n), p parameters, n points. A term set with
// a parameter on its search bound is never selected (the data do not determine it: on white noise
// such a term "lowered" the criterion and made the fit a failed one).
//
// Steering (FitOptions::controls, fit/parameter_control.hpp): given starts and fixed values
// replace the searched starts of their parameter, fixed parameters are constants of the cost
// (uncertainty 0), given bounds replace the default search range.
//
// Starting values: the slope read-offs (fit/slope_readoffs.hpp) scaled by 0.7, 0.2 and 0.03;
// Gauss-Markov starts with tau_c = tau_i / 1.89 (the AVAR peak) at every measured tau; sinusoid
// starts at the three best local minima of a scan over frequency (16 per octave, the amplitude
// solved in closed form at each: where the curve's dips match the nulls at tau = k / f), then
// with f = 0.371 / tau_i (its AVAR peak). The best optimum over the starts is kept.

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "stochnav/fit/fit_data.hpp"
#include "stochnav/fit/implied_wavelet_variance.hpp"
#include "stochnav/fit/parameter_control.hpp"
#include "stochnav/fit/slope_readoffs.hpp"
#include "stochnav/model/noise_model.hpp"

namespace stochnav {

enum class RobustLoss { kNone, kHuber, kCauchy };
enum class InformationCriterion { kAic, kBic };
/// How a fit was made: to the Allan variance (this header) or by GMWM to the Haar wavelet
/// variance (fit/gmwm_fit.hpp).
enum class FitMethod { kAvar, kGmwm };

struct FitOptions {
  /// Terms to fit, in any order (repeats allowed, e.g. two Gauss-Markov terms). Empty: choose
  /// automatically among `candidates`. Nonstationary terms cannot be fitted to an AVAR curve.
  std::vector<TermType> terms;
  /// Starting values, fixed values and bounds of parameters of `terms` (natural units;
  /// fit/parameter_control.hpp), as GmwmOptions::controls. Needs `terms` (the automatic
  /// selection is not steered). A start or fixed value replaces the searched starts of its
  /// parameter; a fixed parameter keeps its value, with uncertainty 0, and is not counted in
  /// FitDiagnostics::parameters; a bound replaces the default search range.
  std::vector<ParameterControl> controls;
  /// Terms held at their values (natural units): their closed-form Allan variance is added to
  /// the fitted terms' at every tau, and they weigh the points with the fitted terms, but they
  /// are not in FitResult::model. Used to fit one new term beside a known model (diagnose).
  /// Nonstationary terms are not allowed here either.
  std::vector<NoiseTerm> fixed_terms;
  /// Terms automatic selection may use, each at most once.
  std::vector<TermType> candidates = {TermType::kQuantization,   TermType::kAngleRandomWalk,
                                      TermType::kBiasInstability, TermType::kRateRandomWalk,
                                      TermType::kRateRamp,       TermType::kGaussMarkov};
  RobustLoss loss = RobustLoss::kHuber;
  double loss_scale = 2.0;  ///< in units of the standardized residual r_i, > 0
  InformationCriterion criterion = InformationCriterion::kBic;
  /// A term is added (or kept) only when it lowers the criterion by more than this, >= 0. The
  /// default 10 is "very strong" evidence on the BIC scale (Kass and Raftery 1995): the cost
  /// treats the points as independent while neighbouring octave taus correlate at 0.5 to 0.9,
  /// so a plain "lower" (0) added a spurious term to 15 of 60 pure white-noise records.
  double min_criterion_improvement = 10.0;
  int max_iterations = 200;                ///< Ceres iterations per solve, >= 1
  /// A given term (options.terms) with a parameter left on its search bound is a failed term:
  /// true drops it and refits without it (repeatedly, keeping at least one term), recording
  /// it in FitDiagnostics::dropped_terms; false (default) keeps it, with a warning.
  bool drop_terms_at_bound = false;

  /// Empty when valid; otherwise the reason, naming the option.
  std::string validate() const;
};

struct SelectionStep {
  std::vector<TermType> terms;  ///< the term set tried
  double criterion = 0.0;       ///< its information criterion
  bool accepted = false;        ///< kept as the current model
};

struct FitDiagnostics {
  /// kGmwm: cost and chi_square are the GMWM objective, criterion_value the WIC, loss kNone.
  FitMethod method = FitMethod::kAvar;
  /// How the Gauss-Markov terms were taken to be sampled (the Allan fit: always interval means).
  GaussMarkovSampling gauss_markov_sampling = GaussMarkovSampling::kIntervalMean;
  double cost = 0.0;        ///< final Ceres cost, 1/2 sum rho(r_i^2)
  double chi_square = 0.0;  ///< sum r_i^2 (no robust loss)
  std::size_t points = 0;
  std::size_t parameters = 0;
  InformationCriterion criterion = InformationCriterion::kBic;
  double criterion_value = 0.0;
  RobustLoss loss = RobustLoss::kHuber;
  double loss_scale = 0.0;
  int iterations = 0;       ///< Ceres iterations of the final solve
  bool converged = false;   ///< the final solve met a convergence tolerance
  bool automatic = false;   ///< terms chosen by the criterion (not given)
  /// Points weighted and correlated by the covariance of the estimates under the fitted model
  /// (FitData::phase_count known), rather than by the input edf as independent points.
  bool model_weighting = false;
  std::vector<double> edf_used;  ///< the EDF that set each point's weight
  std::vector<TermType> chosen_terms;  ///< as in the model
  SlopeReadoffs readoffs;              ///< IEEE 952 cross-check, natural units
  std::vector<SelectionStep> selection;  ///< automatic selection history
  std::vector<std::string> warnings;     ///< e.g. parameters at a bound
  /// Parameters left on an edge of their default search range, as "term_type.parameter" (e.g.
  /// "rate_random_walk.K"; "gauss_markov#2.tau_c" when the type repeats in the terms given):
  /// the data do not determine them (a failed term). Bounds the user gave are not counted.
  std::vector<std::string> at_bound;
  /// Parameters inside their search range whose 1-sigma uncertainty is NaN (the covariance of
  /// the fit is singular there), as "term_type.parameter": not determined either.
  std::vector<std::string> undetermined;
  /// Terms dropped by FitOptions::drop_terms_at_bound, as "term_type (param on its bound)".
  std::vector<std::string> dropped_terms;
  /// chi_square / (points - parameters); NaN when there are no degrees of freedom left.
  double reduced_chi_square() const;
  /// Upper tail P(chi2(points - parameters) >= chi_square); NaN without degrees of freedom.
  double chi_square_p_value() const;
  /// A failed fit: a parameter on its search bound, a parameter without an uncertainty
  /// (`undetermined`), or chi_square_p_value() < kFailedFitPValue (the terms do not describe
  /// the record).
  bool failed() const;
  /// Why failed() (empty when it did not): "rate_random_walk.K on its search bound",
  /// "chi-square 2671 for 10 dof (p = 1e-300 < 1e-6)".
  std::string failure() const;
};

/// A fit whose chi-square has an upper-tail probability below this has failed.
inline constexpr double kFailedFitPValue = 1e-6;

/// One model of a GMWM ranking (fit/gmwm_fit.hpp: rank_gmwm_models).
struct RankedModel {
  std::vector<TermType> terms;  ///< as given in the candidate
  double wic = 0.0;             ///< Wavelet Information Criterion (lower is better)
  double objective = 0.0;       ///< the GMWM objective at the optimum
  /// Terms dropped from the candidate (a parameter on its search bound, GmwmOptions::
  /// drop_terms_at_bound): wic and objective are those of the candidate without them.
  std::vector<std::string> dropped_terms;
  bool failed = false;  ///< the candidate's fit failed (FitDiagnostics::failed)
};

struct FitResult {
  /// The fitted terms in TermType order (natural units), unit and rate_hz from the data.
  NoiseModel model;
  /// Per term, the same type holding the 1-sigma uncertainty of each parameter (natural units);
  /// NaN when not determined. Sinusoid phases are not fitted (absent).
  std::vector<NoiseTerm> sigma;
  /// Covariance of the natural logs of all fitted parameters, in model order.
  Eigen::MatrixXd log_covariance;
  FitDiagnostics diagnostics;
  /// Candidate models ranked by WIC, best first (this fit is the first); empty unless ranked.
  std::vector<RankedModel> ranking;
};

/// Fits the noise terms to `data`. Throws ConfigError when the data (validate(data)) or the
/// options are invalid, when a term cannot be fitted (nonstationary), or when there are fewer
/// points than parameters.
FitResult fit_noise_terms(const FitData& data, const FitOptions& options = {});

/// "none", "huber", "cauchy"; "aic", "bic".
std::string_view robust_loss_name(RobustLoss loss);
std::string_view criterion_name(InformationCriterion criterion);
/// "avar", "gmwm".
std::string_view fit_method_name(FitMethod method);

}  // namespace stochnav
