// Stage 3b of diagnose(): one step of the stochastic loop, from the screened candidates to the
// iteration kept; its texts are in step_evidence.cpp (diagnose_stages.hpp).
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>

#include "diagnose_stages.hpp"
#include "stochnav/core/errors.hpp"

namespace stochnav::diagnose_stages {
namespace {

// The exact gap of a trial (simulated band and stationarity), once; false when it cannot be
// computed for this model.
bool assess_trial_exactly(Trial& trial, const StochasticContext& context) {
  if (trial.outcome.exact) return true;
  try {
    trial.gap = combine_gap(avar_gap(trial.model, context.measured.octave_avar),
                            stationarity_test(context.measured.windows, trial.model),
                            context.options.alpha);
  } catch (const ConfigError&) {
    return false;
  }
  trial.outcome.gap = trial.gap.value;
  trial.outcome.exact = true;
  return true;
}

// The pooled chi-square plus a price per parameter of the new term.
double trial_score(const Trial& trial, double price) {
  return trial.gap.chi_square + price * static_cast<double>(added_parameters(trial.term));
}

// The drop in chi-square is significant for the new term's parameters, the gap shrinks, and
// the part of the chi-square beyond its expectation shrinks by min_relative_shrink.
bool trial_accepted(const Trial& trial, const Gap& before, const DiagnoseOptions& options) {
  const double drop = before.chi_square - trial.gap.chi_square;
  const double parameters = static_cast<double>(added_parameters(trial.term));
  const boost::math::chi_squared_distribution<double> distribution(parameters);
  const double needed = boost::math::quantile(distribution, 1.0 - options.alpha);
  const double excess_before = before.chi_square - before.dof;
  const double excess_after = trial.gap.chi_square - trial.gap.dof;
  return drop > needed && trial.gap.value < before.value &&
         excess_after <= (1.0 - options.min_relative_shrink) * excess_before;
}

struct GapChoice {
  std::optional<std::size_t> best;  // index into the trials; the lowest score assessed exactly
  bool accepted = false;            // `best` is accepted
};

// Two tiers: first the candidates that keep the model as it is (held terms, a nonstationary
// term); only when none of them is accepted, also those that refit the old terms. A refit can
// soak up a second effect into the old terms' coefficients, so it is the fallback for a model
// whose own coefficients are off.
GapChoice choose_by_gap(std::vector<Trial>& trials, const Gap& before,
                        const StochasticContext& context) {
  const double price = context.options.parameter_price;
  const auto score = [price](const Trial* trial) { return trial_score(*trial, price); };
  const Trial* best = nullptr;
  bool accepted = false;
  for (bool with_refits : {false, true}) {
    std::vector<Trial*> contenders;
    for (Trial& trial : trials) {
      if (trial.outcome.usable && (with_refits || !trial.outcome.refitted)) {
        contenders.push_back(&trial);
      }
    }
    // Ranked by the pooled chi-square plus a price per parameter of the new term.
    std::sort(contenders.begin(), contenders.end(),
              [&](const Trial* a, const Trial* b) { return score(a) < score(b); });
    // The best few by screening get the exact gap (their own estimator covariance); when
    // none of them is accepted, the rest too: every usable candidate has its chance.
    constexpr std::size_t kExactlyAssessed = 3;
    const Trial* tier_best = nullptr;
    const Trial* tier_accepted = nullptr;
    for (std::size_t index = 0; index < contenders.size(); ++index) {
      if (index >= kExactlyAssessed && tier_accepted != nullptr) break;
      Trial* trial = contenders[index];
      if (!assess_trial_exactly(*trial, context)) continue;
      if (tier_best == nullptr || score(trial) < score(tier_best)) tier_best = trial;
      if (trial_accepted(*trial, before, context.options) &&
          (tier_accepted == nullptr || score(trial) < score(tier_accepted))) {
        tier_accepted = trial;
      }
    }
    if (tier_best != nullptr && (best == nullptr || score(tier_best) < score(best))) {
      best = tier_best;
    }
    if (tier_accepted != nullptr) {
      best = tier_accepted;
      accepted = true;
      break;
    }
  }
  GapChoice choice;
  if (best != nullptr) choice.best = static_cast<std::size_t>(best - trials.data());
  choice.accepted = accepted;
  return choice;
}

// The rate random walk the block means estimate (walk.k), merged into the model's own rate
// random walk when it has one; not usable when the estimate is 0.
Trial trial_from_block_means(const NoiseModel& base, const RandomWalkTest& walk) {
  Trial trial;
  NoiseModel candidate = base;
  double k2 = walk.k * walk.k;
  bool merged = false;
  for (NoiseTerm& term : candidate.terms) {
    if (auto* old = std::get_if<RateRandomWalkTerm>(&term)) {
      k2 += old->k * old->k;
      old->k = std::sqrt(k2);
      merged = true;
    }
  }
  if (!merged) candidate.terms.push_back(RateRandomWalkTerm{walk.k});
  trial.outcome.type = TermType::kRateRandomWalk;
  trial.outcome.refitted = false;
  trial.outcome.usable = walk.k > 0.0;
  trial.term = RateRandomWalkTerm{std::sqrt(k2)};
  trial.model = std::move(candidate);
  return trial;
}

struct WalkChoice {
  std::size_t index = 0;      // into the trials
  RandomWalkTest walk_after;  // the time-domain test of its model
};

// The time-domain fallback: a rate random walk the block means show but the last octaves of
// the Allan variance cannot resolve. The candidates: the block means' own estimate and the
// Allan fits of a rate random walk; the one with the lowest exact chi-square among those that
// shrink the gap and remove the walk the test found. The estimate, when chosen, is appended to
// `trials`.
std::optional<WalkChoice> choose_by_walk_test(std::vector<Trial>& trials, const NoiseModel& base,
                                              const Gap& before, const RandomWalkTest& walk,
                                              const StochasticContext& context) {
  std::vector<Trial*> walkers;
  Trial from_blocks = trial_from_block_means(base, walk);
  if (from_blocks.outcome.usable) walkers.push_back(&from_blocks);
  // The Allan fits of a rate random walk too, even when screened out as immaterial there:
  // the time domain is the evidence here.
  for (Trial& trial : trials) {
    if (trial.outcome.type == TermType::kRateRandomWalk && !trial.model.terms.empty() &&
        std::isfinite(trial.gap.value)) {
      walkers.push_back(&trial);
    }
  }
  Trial* walk_best = nullptr;
  RandomWalkTest walk_after;
  for (Trial* trial : walkers) {
    if (!assess_trial_exactly(*trial, context)) continue;
    if (!std::isfinite(trial->gap.value) || !(trial->gap.value < before.value)) continue;
    const RandomWalkTest after = context.walk_test(trial->model);
    if (after.statistic > walk.statistic - walk.threshold) continue;
    if (walk_best == nullptr || trial->gap.chi_square < walk_best->gap.chi_square) {
      walk_best = trial;
      walk_after = after;
    }
  }
  if (walk_best == nullptr) return std::nullopt;
  walk_best->outcome.usable = true;
  WalkChoice choice;
  choice.walk_after = walk_after;
  if (walk_best == &from_blocks) {
    trials.push_back(std::move(from_blocks));
    choice.index = trials.size() - 1;
  } else {
    choice.index = static_cast<std::size_t>(walk_best - trials.data());
  }
  return choice;
}

}  // namespace

StepResult take_stochastic_step(const ModelAssessment& current, const RandomWalkTest& walk,
                                const StochasticContext& context) {
  const Gap& before = current.gap;
  const NoiseModel& base = current.model;
  const MeasuredStatistics& measured = context.measured;
  const Signature signature = signature_of(before, base, measured);

  std::vector<Trial> trials = screen_candidates(current, context);
  const GapChoice by_gap = choose_by_gap(trials, before, context);
  std::optional<WalkChoice> by_walk;
  if (!by_gap.accepted && walk.significant) {
    by_walk = choose_by_walk_test(trials, base, before, walk, context);
  }
  StepResult result;
  if (!by_gap.accepted && !by_walk) {
    result.rejection = rejection_text(before, walk, by_gap.best ? &trials[*by_gap.best] : nullptr);
    return result;
  }
  const Trial& best = trials[by_walk ? by_walk->index : *by_gap.best];

  std::vector<CandidateOutcome> outcomes;
  for (const Trial& trial : trials) outcomes.push_back(trial.outcome);
  DiagnoseIteration step;
  step.effect = best.outcome.type;
  step.refitted = best.outcome.refitted;
  step.added_term = best.term;
  step.added_term_at_bound = best.outcome.at_bound;
  step.gap_before = before.value;
  step.gap_after = best.gap.value;
  step.signature = signature;
  step.candidates = outcomes;
  if (step.effect == TermType::kNonstationary) {
    step.time_range_s = segment_time_range(best.term, base);
  } else {
    step.tau_range_s = signature.tau_range_s;
  }
  step.evidence =
      evidence_text(signature, before, best, outcomes, step.time_range_s, measured.unit);
  if (by_walk) {
    step.evidence +=
        walk_evidence_text(walk, by_walk->walk_after, context.options.alpha, measured.unit);
  }
  step.after = assessment_with_band(best.model, best.gap, measured, context.options);
  result.iteration = std::move(step);
  return result;
}

}  // namespace stochnav::diagnose_stages
