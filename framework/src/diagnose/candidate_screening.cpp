// Stage 3a of diagnose(): the candidates of one stochastic step with their screening gaps
// (diagnose_stages.hpp).
#include <algorithm>
#include <cmath>

#include "diagnose_stages.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/candidate_fit.hpp"
#include "stochnav/diagnose/effective_model.hpp"
#include "stochnav/model/allan_variance.hpp"

namespace stochnav::diagnose_stages {
namespace {

// Largest share of the term in the model's Allan variance over the octave taus.
double largest_share(const NoiseTerm& term, const NoiseModel& model,
                     const MeasuredStatistics& measured) {
  const StationaryEquivalent equivalent = stationary_equivalent(model, measured.duration_s);
  const NoiseTerm scaled = scale_amplitude(term, std::sqrt(equivalent.variance_factor));
  double share = 0.0;
  for (double tau : measured.octave_avar.tau_s) {
    const double total = allan_variance(equivalent.model, tau);
    if (total > 0.0) share = std::max(share, allan_variance(scaled, tau) / total);
  }
  return share;
}

bool stationarity_fails(const StationarityTest& test, double alpha) {
  return test.dof > 0.0 && test.p_value < alpha;
}

// A candidate with its screening gap: `candidate` (the model with `term`) against the octave
// points with the estimator scatter of the model before the step (`before`).
Trial screened_trial(NoiseModel candidate, NoiseTerm term, TermType type, bool refitted,
                     const AvarGap& before, const StochasticContext& context) {
  const MeasuredStatistics& measured = context.measured;
  Trial trial;
  trial.outcome.type = type;
  trial.outcome.refitted = refitted;
  try {
    trial.gap = combine_gap(screening_avar_gap(candidate, measured.octave_avar, before),
                            stationarity_test(measured.windows, candidate), context.options.alpha);
    trial.outcome.usable = std::isfinite(trial.gap.value);
    trial.outcome.gap = trial.gap.value;
  } catch (const ConfigError&) {
    trial.outcome.usable = false;
  }
  // A term that is nowhere a material part of the model names nothing: its gain comes from
  // the refitted old terms.
  if (trial.outcome.usable && type != TermType::kNonstationary &&
      largest_share(term, candidate, measured) < context.options.min_term_share) {
    trial.outcome.usable = false;
    trial.outcome.immaterial = true;
  }
  trial.model = std::move(candidate);
  trial.term = std::move(term);
  return trial;
}

}  // namespace

std::vector<Trial> screen_candidates(const ModelAssessment& current,
                                     const StochasticContext& context) {
  const Gap& before = current.gap;
  const NoiseModel& base = current.model;
  const MeasuredStatistics& measured = context.measured;
  const DiagnoseOptions& options = context.options;
  std::vector<Trial> trials;
  if (options.try_nonstationary && stationarity_fails(before.stationarity, options.alpha)) {
    if (auto term = nonstationary_candidate(measured.windows, before.stationarity, base)) {
      NoiseModel candidate = stationary_part(base);
      candidate.terms.push_back(*term);
      trials.push_back(screened_trial(std::move(candidate), *term, TermType::kNonstationary, false,
                                      before.avar, context));
    }
  }
  const bool has_old_terms = !stationary_part(base).terms.empty();
  for (TermType type : options.candidates) {
    const bool present = has_type(base, type);
    for (bool refit : {false, true}) {
      if (refit && !has_old_terms) continue;
      if (!refit && present && !repeatable(type)) continue;
      auto fitted = fit_candidate(base, measured.dense_fit, type, refit, measured.duration_s);
      if (!fitted) {
        Trial failed;
        failed.outcome = {type, refit, false, 0.0, false, false};
        trials.push_back(std::move(failed));
        continue;
      }
      Trial trial = screened_trial(std::move(fitted->model), std::move(fitted->term), type, refit,
                                   before.avar, context);
      trial.outcome.at_bound = std::move(fitted->at_bound);
      trials.push_back(std::move(trial));
    }
  }
  return trials;
}

}  // namespace stochnav::diagnose_stages
