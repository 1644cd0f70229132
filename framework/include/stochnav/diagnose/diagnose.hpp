#pragma once
// The discrepancy workflow (DESIGN.md): find where a record and its noise model disagree, name
// the missing effect, add it, and show the gap shrink.
//
//   1. measure the record once (diagnose/measured_statistics.hpp);
//   2. assess the model: the gap (diagnose/gap.hpp: closed forms and the exact estimator
//      covariance, plus the stationarity test across windows) and the band of records simulated
//      from it (diagnose/simulated_band.hpp);
//   3. if the model is consistent, stop: no iterations, no false alarms;
//   4. otherwise read the signature (diagnose/signature.hpp: tau range and shape) and try every
//      candidate: each stationary vocabulary type, held and refitted (diagnose/candidate_fit.hpp),
//      and, when the windows disagree, a nonstationary term built from them
//      (diagnose/stationarity.hpp). Each candidate model is screened with the current model's
//      estimator scatter (screening_avar_gap); a new stationary term that nowhere makes up
//      `min_term_share` of the model's Allan variance is left out (immaterial);
//   5. in two tiers, first the candidates that keep the model's terms as they are (held, or a
//      nonstationary term), then, only if none of those is accepted, all of them (refits too: a
//      refit can soak a second effect into the old coefficients, so it is the fallback for a
//      model whose own coefficients are off): rank by pooled chi-square (diagnose/gap.hpp) plus
//      `parameter_price` per parameter of the new term, assess the best three exactly (the
//      rest too, in that order, when none of the three is accepted), and keep the best accepted
//      one: accepted when it shrinks the gap significantly: the pooled chi-square drops by more
//      than the (1 - alpha) quantile of chi2(p), p the new term's parameter count, the gap
//      itself shrinks, and the chi-square beyond its dof shrinks by at least
//      `min_relative_shrink`; otherwise (after step 6) stop (nothing helps, and no term is added
//      that does not shrink the gap);
//   6. when no Allan-variance candidate is accepted but the time-domain test finds a rate random
//      walk the model lacks (diagnose/deterministic_effects.hpp, test_rate_random_walk: the
//      exact likelihood of the block means, far more powerful at long taus than the last
//      octaves of the Allan variance), the rate random walk candidates (its time-domain
//      estimate, and the held and refitted Allan fits) are assessed exactly, and the one with
//      the lowest pooled chi-square is kept when the gap shrinks and the time-domain statistic
//      drops by more than its threshold;
//   7. repeat from 2 while the gap or the time-domain test says inconsistent, up to
//      max_iterations;
//   8. final model selection (joint refit): the model's stationary terms refitted together
//      (diagnose/candidate_fit.hpp, refit_jointly), and variants with one term a step added
//      dropped or replaced by a candidate of fewer parameters (a Gauss-Markov term of long
//      correlation time taken early for a rate random walk), each refitted jointly and
//      assessed exactly. Criterion: pooled chi-square + parameter_price per parameter of the
//      whole model + the change in the block means' -2 ln L (test_rate_random_walk's
//      minus_two_log_l, which tells long-tau alternatives apart where the last octaves cannot).
//      The best variant is kept when it beats the step-by-step model, does not widen an
//      inconsistent gap, and a consistent model stays consistent (the plain refit must also
//      lower the pooled chi-square). A replacement is reported as an extra iteration; a refit
//      or a drop in `joint_refit` and `final_selection`.
// Before step 2, deterministic effects (rate_ramp, bias_step, aux_sensitivity) are found in
// the time domain (diagnose/deterministic_effects.hpp: GLS regressions of block means with
// likelihood-ratio tests against the stochastic alternatives), each reported as an iteration
// and removed from the record; steps 2-6 then diagnose the stochastic remainder. A
// deterministic term is kept when its time-domain test passes and the record gap does not grow
// by its removal. The model's own deterministic terms are removed from the record first.
// The effect's name is the type of the kept candidate; the signature is reported beside it as
// evidence (they usually agree; the report says when they do not).
//
// The result types do not depend on where the discrepancy evidence came from: a later source
// (a filter run's innovations, `diagnose --run`) adds a component to Gap and candidates to the
// same loop, and DiagnoseIteration stays as it is.

#include <array>
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "stochnav/diagnose/deterministic_effects.hpp"
#include "stochnav/diagnose/gap.hpp"
#include "stochnav/diagnose/measured_statistics.hpp"
#include "stochnav/diagnose/short_tau_gauss_markov.hpp"
#include "stochnav/diagnose/signature.hpp"
#include "stochnav/diagnose/simulated_band.hpp"
#include "stochnav/diagnose/wavelet_outliers.hpp"
#include "stochnav/io/record.hpp"
#include "stochnav/model/noise_model.hpp"

namespace stochnav {

struct DiagnoseOptions {
  int seeds = 6;             ///< simulated records per model assessment, >= 2 (0: no band)
  std::uint64_t seed = 1;    ///< first simulation seed
  int max_iterations = 4;    ///< >= 0
  double alpha = 1e-3;       ///< false-alarm probability of the consistency test, (0, 0.5)
  std::size_t windows = 32;  ///< stationarity windows, >= 4
  /// A kept term removes at least this fraction of the chi-square beyond its dof.
  double min_relative_shrink = 0.2;
  /// Chi-square a candidate pays per parameter of its new term when candidates are ranked
  /// (2: Akaike's price; a two-parameter term must explain 2 more than a one-parameter one).
  double parameter_price = 2.0;
  /// A new stationary term must make up at least this share of the model's Allan variance at
  /// some octave tau; a smaller one is a refit of the old terms in disguise, not an effect.
  double min_term_share = 0.1;
  /// Stationary term types tried as the missing effect.
  std::vector<TermType> candidates = {TermType::kQuantization,    TermType::kAngleRandomWalk,
                                      TermType::kBiasInstability, TermType::kRateRandomWalk,
                                      TermType::kGaussMarkov,     TermType::kSinusoid};
  /// Look for deterministic effects (rate ramp, bias step, aux channels) in the time domain.
  bool try_deterministic = true;
  bool try_nonstationary = true;  ///< offer a nonstationary term when the windows disagree
  /// Test the model for a missing rate random walk in the time domain
  /// (diagnose/deterministic_effects.hpp, test_rate_random_walk) besides the gap: the loop goes
  /// on while either says the model is inconsistent.
  bool try_time_domain_walk = true;
  /// Refit all stationary terms together after the loop (kept when the pooled chi-square drops
  /// and the gap does not widen).
  bool joint_refit = true;
  /// After the loop, read the record's classical and robust Haar wavelet variance: flag
  /// outliers by their split (diagnose/wavelet_outliers.hpp) and test the final model for a
  /// missing short-tau Gauss-Markov term by GMWM (diagnose/short_tau_gauss_markov.hpp). Both
  /// are findings reported beside the loop's; they change neither the iterations nor the model.
  bool try_wavelet = true;
  /// When set, one is added per stage done (the measured statistics, the model's assessment,
  /// each iteration, the final choice): diagnose_stage_count(max_iterations) in all, fewer
  /// when the loop stops early. A progress display's counter (core/progress_bar.hpp,
  /// ProgressTicker).
  std::atomic<std::uint64_t>* stages_done = nullptr;

  /// Empty when valid; otherwise the reason, naming the option.
  std::string validate() const;
};

/// The stages diagnose() counts in DiagnoseOptions::stages_done when every iteration runs.
constexpr std::uint64_t diagnose_stage_count(int max_iterations) {
  return 3 + static_cast<std::uint64_t>(max_iterations);
}

/// A model held against the record.
struct ModelAssessment {
  NoiseModel model;
  Gap gap;
  SimulatedBand band;  ///< at the dense and octave taus (empty when DiagnoseOptions::seeds == 0)
};

/// One candidate tried in an iteration.
struct CandidateOutcome {
  TermType type = TermType::kAngleRandomWalk;
  bool refitted = false;  ///< the model's terms were refitted with it
  bool usable = false;    ///< the fit produced a model
  /// The candidate model's gap (when usable): screening value (diagnose/gap.hpp,
  /// screening_avar_gap) unless `exact`.
  double gap = 0.0;
  bool exact = false;       ///< assessed with its own estimator covariance
  bool immaterial = false;  ///< left out: below DiagnoseOptions::min_term_share everywhere
  /// Parameters its fit left on a search bound ("gauss_markov.tau_c"); a kept candidate's are
  /// flagged in the step's evidence and in report.json ("added_term_at_bound").
  std::vector<std::string> at_bound = {};
};

struct DiagnoseIteration {
  TermType effect = TermType::kAngleRandomWalk;       ///< the name: the kept candidate's type
  std::string evidence;                               ///< one paragraph, numbers included
  std::optional<std::array<double, 2>> tau_range_s;   ///< where the AVAR leaves the band
  std::optional<std::array<double, 2>> time_range_s;  ///< deviating windows (record time)
  NoiseTerm added_term;                               ///< natural units
  /// 1-sigma uncertainties of added_term's parameters by JSON name, natural units (the
  /// deterministic terms; empty for the Allan-variance fits).
  std::vector<std::pair<std::string, double>> added_term_sigma;
  /// Parameters of added_term (or of the terms refitted with it) its fit left on a search
  /// bound: flagged in the evidence, and in report.json as "added_term_at_bound" when any.
  std::vector<std::string> added_term_at_bound;
  bool refitted = false;                              ///< the other terms were refitted too
  double gap_before = 0.0;
  double gap_after = 0.0;
  Signature signature;                       ///< read before the step
  std::vector<CandidateOutcome> candidates;  ///< every candidate tried, in order
  ModelAssessment after;                     ///< the model after the step
};

struct DiagnoseResult {
  MeasuredStatistics measured;
  ModelAssessment initial;
  std::vector<DiagnoseIteration> iterations;
  bool consistent = false;  ///< the final model passes the consistency test
  std::string conclusion;   ///< why the loop stopped, one sentence
  /// Signature of the final model (what is left, when not consistent).
  Signature final_signature;

  /// Deterministic terms (the model's own, then those found), removed from the record before
  /// `measured` was taken; the assessments hold the stochastic part only.
  std::vector<NoiseTerm> deterministic;

  /// The joint refit of all stationary terms after the loop, when kept (it then is the final
  /// assessment); gap_before is the last step's gap.
  std::optional<ModelAssessment> joint_refit;
  /// What the final model selection did, one line ("all terms refitted jointly: gap a -> b",
  /// "replaced gauss_markov by rate_random_walk ...", "dropped rate_random_walk ..."); empty when
  /// it kept the step-by-step model.
  std::string final_selection;
  /// The time-domain rate-random-walk test of the final model (statistic 0 when not run).
  RandomWalkTest final_walk_test;

  /// The classical/robust wavelet-variance split of the record (without the deterministic
  /// terms); empty when DiagnoseOptions::try_wavelet is false.
  std::optional<WaveletOutlierCheck> wavelet_outliers;
  /// The short-tau Gauss-Markov test of the final stochastic model on the record's wavelet
  /// variance (the robust one when outliers were flagged); empty when try_wavelet is false.
  std::optional<ShortTauGaussMarkovCheck> short_tau_gauss_markov;

  const ModelAssessment& final_assessment() const {
    if (joint_refit) return *joint_refit;
    return iterations.empty() ? initial : iterations.back().after;
  }
  /// The final stochastic model with the deterministic terms appended.
  NoiseModel final_model() const;
};

/// Runs the workflow. Throws ConfigError for invalid options, a model whose unit measures
/// another quantity than the record's, or a model with no positive Allan variance; InputError
/// for a record too short to measure. `aux`: auxiliary channels of the record (one value per
/// sample of `record`), tested as aux_sensitivity; a model's aux_sensitivity term must find its
/// column among them (ConfigError otherwise).
DiagnoseResult diagnose(const Record& record, const NoiseModel& model,
                        const DiagnoseOptions& options = {},
                        const std::vector<AuxChannel>& aux = {});

/// Assesses one model against measured statistics (steps 2 of the file comment).
ModelAssessment assess_model(const NoiseModel& model, const MeasuredStatistics& measured,
                             const DiagnoseOptions& options);

}  // namespace stochnav
