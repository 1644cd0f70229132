#pragma once
// The stages of diagnose(), one file each; diagnose.cpp runs them in order and holds the loop
// (steps 3 and 7). Step numbers are those of the workflow in the file comment of
// stochnav/diagnose/diagnose.hpp. Private to the framework: none of this is API.
//
//   diagnose_inputs.cpp        inputs checked, the model split, the record as the stages read
//                              it (natural rate, aligned aux channels, residual records), and
//                              the time-domain rate-random-walk test (step 1)
//   deterministic_stage.cpp    deterministic effects, each kept only when it does not widen the
//                              gap ("before step 2")
//   candidate_screening.cpp    the candidates of one stochastic step, screened (step 4)
//   stochastic_step.cpp        one stochastic step: exact assessment and acceptance in two tiers,
//                              the time-domain fallback, the iteration kept (steps 4-6)
//   step_evidence.cpp          the texts of a step: evidence, time range, why none was kept
//   final_selection.cpp        joint refit, replace and drop variants after the loop (step 8)
//   wavelet_stage.cpp          the wavelet-variance findings after the loop: outliers from the
//                              classical/robust split, a short-tau Gauss-Markov term by GMWM
//   diagnose_common.cpp        helpers the stages share
//
// Units: rates and terms in natural units (SI) unless a name says otherwise; times in seconds.
// Names here live in stochnav::diagnose_stages; file-local helpers have names unique across
// framework/src/diagnose (the sanitizer presets build the framework as unity sources).

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "stochnav/diagnose/diagnose.hpp"

namespace stochnav::diagnose_stages {

// ---- Helpers the stages share (diagnose_common.cpp) -------------------------------------------

/// The dense and octave averaging factors of `measured` together, sorted, unique: the simulated
/// band is drawn over the dense curve and tabulated at the octave points.
std::vector<std::size_t> band_factors(const MeasuredStatistics& measured);

/// An assessment of `model` with `gap` already computed; the simulated band added when
/// options.seeds > 0 (deterministic: the seeds are options.seed onwards).
ModelAssessment assessment_with_band(const NoiseModel& model, const Gap& gap,
                                     const MeasuredStatistics& measured,
                                     const DiagnoseOptions& options);

/// Parameters `term` adds to a model: 2 for Gauss-Markov and sinusoid, 3 per segment of a
/// nonstationary term, 1 otherwise.
std::size_t added_parameters(const NoiseTerm& term);

/// added_parameters summed over the terms of `model`.
double total_parameters(const NoiseModel& model);

/// True when `model` has a term of `type`.
bool has_type(const NoiseModel& model, TermType type);

/// Power-law terms appear once: a second one is the first with a larger coefficient (the
/// refitted variant covers that). Gauss-Markov and sinusoid terms may repeat.
bool repeatable(TermType type);

/// describe(term) in the quantity of `unit`, without trailing newlines.
std::string describe_term_short(const NoiseTerm& term, Unit unit);

/// The signature of `gap` against `model` over the dense measured curve of `measured`.
Signature signature_of(const Gap& gap, const NoiseModel& model, const MeasuredStatistics& measured);

// ---- Stage 1: inputs (diagnose_inputs.cpp) ----------------------------------------------------

/// Throws ConfigError, with the first problem found, for invalid options, a model issue
/// (find_model_issue) or a model whose unit measures another quantity than the record's.
void check_diagnose_inputs(const Record& record, const NoiseModel& model,
                           const DiagnoseOptions& options);

/// A model split into its deterministic terms (removed from the record) and the rest, the
/// stochastic model the assessments hold. Both keep the model's order.
struct SplitModel {
  NoiseModel stochastic;
  std::vector<NoiseTerm> deterministic;
};
SplitModel split_model(const NoiseModel& model);

/// The record as the stages read it: its natural rate and the aux channels cut to the rate
/// samples. Holds a reference to the record, which must outlive it.
class RecordResiduals {
 public:
  /// Throws ConfigError when an aux channel has fewer values than the record has rate samples.
  RecordResiduals(const Record& record, const std::vector<AuxChannel>& aux);

  /// The natural rate with `terms` removed: natural units, one value per rate sample.
  std::vector<double> rate_without(const std::vector<NoiseTerm>& terms) const;
  /// The record with `terms` removed, as a rate record in the record's unit (to measure).
  Record record_without(const std::vector<NoiseTerm>& terms) const;

  const Record& record() const { return record_; }
  /// The natural rate of the record, one value per rate sample (natural units).
  const std::vector<double>& rate() const { return rate_; }
  const std::vector<AuxChannel>& aux_rate() const { return aux_rate_; }

 private:
  const Record& record_;
  std::vector<double> rate_;          // natural units
  std::vector<AuxChannel> aux_rate_;  // aligned with rate_
};

/// The time-domain rate-random-walk test (test_rate_random_walk) on the stochastic remainder of
/// the record: the natural rate with every deterministic term removed.
class TimeDomainWalkTest {
 public:
  /// `deterministic`: every deterministic term (the model's and those found). Does nothing
  /// when options.try_time_domain_walk is false.
  TimeDomainWalkTest(const RecordResiduals& residuals, const std::vector<NoiseTerm>& deterministic,
                     const DiagnoseOptions& options);
  /// The test of `model`; RandomWalkTest{} (not significant, statistic 0) when the test is off
  /// or the record is too short for blocks.
  RandomWalkTest operator()(const NoiseModel& model) const;
  /// The natural rate with every deterministic term removed (natural units); empty when the
  /// test is not enabled.
  const std::vector<double>& stochastic_rate() const { return stochastic_rate_; }

 private:
  bool enabled_;
  double alpha_;
  double rate_hz_;
  std::vector<double> stochastic_rate_;  // natural units; empty when not enabled_
};

// ---- Stage 2: deterministic effects (deterministic_stage.cpp) ---------------------------------

/// The deterministic effects (rate ramp, bias step, aux sensitivity) the time domain finds in
/// the record with result.deterministic removed, against `stochastic`, in the order found;
/// empty when options.try_deterministic is false.
std::vector<DeterministicFinding> find_record_effects(const RecordResiduals& residuals,
                                                      const NoiseModel& stochastic,
                                                      const DiagnoseResult& result,
                                                      const DiagnoseOptions& options);

/// Removes `findings` from the record one at a time, in order, and stops at the first that
/// widens the gap of `stochastic` (never a term that widens the gap). Each one kept appends an
/// iteration (with its `after` assessment) and its term to result.deterministic, and replaces
/// result.measured by the statistics of the record without it. Requires result.initial.
void accept_deterministic_findings(const std::vector<DeterministicFinding>& findings,
                                   const RecordResiduals& residuals, const NoiseModel& stochastic,
                                   const DiagnoseOptions& options, DiagnoseResult& result);

// ---- Stages 3 and 4: the stochastic loop and the final selection ------------------------------

/// What a stochastic step and the final selection read: fixed once the deterministic effects
/// are off the record. References: the caller keeps the objects alive and unchanged.
struct StochasticContext {
  const MeasuredStatistics& measured;  ///< the record without every deterministic term
  const DiagnoseOptions& options;
  const TimeDomainWalkTest& walk_test;
};

/// A candidate model of a stochastic step: the term tried, the model with it and its gap
/// (the screening gap until outcome.exact; default when the fit failed or its gap threw).
struct Trial {
  CandidateOutcome outcome;
  NoiseModel model;  ///< empty when the fit failed
  NoiseTerm term;
  Gap gap;
};

/// Stage 3a (candidate_screening.cpp): every candidate for the step from `current`, with its
/// screening gap (current's estimator scatter): first a nonstationary term (when offered and the
/// windows disagree), then each type of options.candidates held, then refitted. A candidate
/// below options.min_term_share everywhere is not usable (immaterial).
std::vector<Trial> screen_candidates(const ModelAssessment& current,
                                     const StochasticContext& context);

/// The outcome of one stochastic step.
struct StepResult {
  /// The iteration kept (its `after` assessment with band); empty when none was accepted.
  std::optional<DiagnoseIteration> iteration;
  /// When none was accepted: why, one sentence (the conclusion of diagnose).
  std::string rejection;
};

/// Stage 3b (stochastic_step.cpp): one step of the stochastic loop from `current`, whose
/// time-domain walk test is `walk`: screens the candidates, assesses the best exactly in two
/// tiers (held terms first, then refits), falls back to the time-domain rate random walk, and
/// builds the iteration with its evidence.
StepResult take_stochastic_step(const ModelAssessment& current, const RandomWalkTest& walk,
                                const StochasticContext& context);

// ---- Stage 3c: the texts of a stochastic step (step_evidence.cpp) ------------------------------

/// The record time spanned by the segments of `term` (a nonstationary term) that `base` did not
/// have; empty for another term or when no segment is new.
std::optional<std::array<double, 2>> segment_time_range(const NoiseTerm& term,
                                                        const NoiseModel& base);

/// The evidence paragraph of a step that kept `kept`: what the gap or the windows showed
/// (`signature`, `before`: read before the step), how the candidates (`outcomes`) ranked, the
/// term added. `time_range`: of a nonstationary term's new segments; `unit`: the record's.
std::string evidence_text(const Signature& signature, const Gap& before, const Trial& kept,
                          const std::vector<CandidateOutcome>& outcomes,
                          const std::optional<std::array<double, 2>>& time_range, Unit unit);

/// Appended to the evidence when the time-domain fallback kept the step: what the block means
/// showed before (`walk`) and with the term (`walk_after`); K reported in `unit`'s quantity.
std::string walk_evidence_text(const RandomWalkTest& walk, const RandomWalkTest& walk_after,
                               double alpha, Unit unit);

/// Why a step accepted no candidate (the conclusion of diagnose); `best`: the lowest score
/// assessed exactly, or null.
std::string rejection_text(const Gap& before, const RandomWalkTest& walk, const Trial* best);

/// A variant of the final model, refitted jointly and assessed exactly.
struct FinalVariant {
  NoiseModel model;
  Gap gap;
  RandomWalkTest walk;                  ///< its time-domain test
  std::optional<TermType> replaced;     ///< the added type replaced or dropped, if any
  std::optional<NoiseTerm> substitute;  ///< the term replacing it (none: it was dropped)
};

/// Stage 4 (final_selection.cpp): the variants of result.final_assessment() (all terms refitted
/// jointly; one added term dropped; one replaced by a candidate type of fewer parameters), each
/// refitted jointly; the best by pooled chi-square + parameter_price per parameter + the change
/// in the block means' -2 ln L, when it beats the step-by-step model, does not widen an
/// inconsistent gap and keeps a consistent model consistent. Empty: keep the step-by-step model.
std::optional<FinalVariant> choose_final_variant(const DiagnoseResult& result,
                                                 const StochasticContext& context);

/// Records `chosen` in `result`: a substitution as an iteration, otherwise as
/// result.joint_refit; result.final_selection, and the conclusion (consistent now, or what the
/// selection changed).
void apply_final_variant(const FinalVariant& chosen, const StochasticContext& context,
                         DiagnoseResult& result);

// ---- After the loop: the wavelet-variance findings (wavelet_stage.cpp) ------------------------

/// Sets result.wavelet_outliers and result.short_tau_gauss_markov from the record without
/// result.deterministic (against result.final_assessment().model): the walk test's copy of it
/// when it holds one (no further copy of the record), otherwise the residuals' rate, or a
/// copy without the deterministic terms. Does nothing when options.try_wavelet is false or the
/// record is too short for 3 scales.
void check_wavelet_variance(const RecordResiduals& residuals, const TimeDomainWalkTest& walk_test,
                            const DiagnoseOptions& options, DiagnoseResult& result);

}  // namespace stochnav::diagnose_stages
