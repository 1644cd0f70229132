// Stage 3b of diagnose(): one step of the stochastic loop, from the screened candidates to the
// iteration kept (diagnose_stages.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>

#include "diagnose_stages.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/effective_model.hpp"
#include "stochnav/model/reporting_units.hpp"

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

// The record time spanned by the segments of `term` that `base` did not have.
std::optional<std::array<double, 2>> segment_time_range(const NoiseTerm& term,
                                                        const NoiseModel& base) {
  const auto* nonstationary = std::get_if<NonstationaryTerm>(&term);
  if (nonstationary == nullptr) return std::nullopt;
  const NonstationaryTerm* old = find_nonstationary(base);
  std::optional<std::array<double, 2>> range;
  for (const auto& segment : nonstationary->segments) {
    const bool kept =
        old != nullptr &&
        std::any_of(old->segments.begin(), old->segments.end(), [&](const NonstationarySegment& o) {
          return o.start_s == segment.start_s && o.end_s == segment.end_s &&
                 o.scale == segment.scale;
        });
    if (kept) continue;
    if (!range) {
      range = std::array<double, 2>{segment.start_s, segment.end_s};
    } else {
      (*range)[0] = std::min((*range)[0], segment.start_s);
      (*range)[1] = std::max((*range)[1], segment.end_s);
    }
  }
  return range;
}

std::string evidence_text(const Signature& signature, const Gap& before, const Trial& kept,
                          const std::vector<CandidateOutcome>& outcomes,
                          const std::optional<std::array<double, 2>>& time_range, Unit unit) {
  std::string text;
  const TermType effect = kept.outcome.type;
  if (effect == TermType::kNonstationary) {
    const auto& test = before.stationarity;
    const auto deviating = std::count(test.deviating.begin(), test.deviating.end(), true);
    double max_z = 0.0;
    for (double z : test.z) max_z = std::max(max_z, std::abs(z));
    text += fmt::format(
        "The short-tau Allan variance of the {} windows disagrees between windows: "
        "chi-square {:.1f} on {:.0f} dof (reduced {:.2f}, p = {:.2g}); {} windows deviate from "
        "the median level by more than 4 sigma (largest |z| = {:.1f})",
        test.z.size(), test.chi_square, test.dof, test.reduced_chi_square, test.p_value, deviating,
        max_z);
    if (time_range)
      text += fmt::format("; the stretch they point to: t = {:.1f} .. {:.1f} s", (*time_range)[0],
                          (*time_range)[1]);
    text += ". ";
  } else if (signature.found) {
    text += fmt::format(
        "The measured Allan variance lies {} the model's band over tau = {:.4g} .. {:.4g} s "
        "(largest |z| = {:.1f} at tau = {:.4g} s); signature: {}, which reads as {}. ",
        signature.above ? "above" : "below", (*signature.tau_range_s)[0],
        (*signature.tau_range_s)[1], signature.max_abs_z, signature.tau_at_max_s, signature.shape,
        term_type_name(signature.suggested));
  } else {
    text += fmt::format(
        "No octave point leaves the model's 2-sigma band by itself (largest |z| = {:.1f}), but "
        "together they do (AVAR reduced chi-square {:.2f}). ",
        signature.max_abs_z, before.avar.reduced_chi_square);
  }
  // The ranking of the candidates.
  std::vector<CandidateOutcome> ranked;
  for (const auto& outcome : outcomes) {
    if (outcome.usable) ranked.push_back(outcome);
  }
  std::sort(ranked.begin(), ranked.end(),
            [](const auto& a, const auto& b) { return a.gap < b.gap; });
  text += fmt::format("Of {} candidate fits, {} ({}) shrinks the gap most: {:.3g} -> {:.3g}",
                      outcomes.size(), term_type_name(effect),
                      kept.outcome.refitted ? "other terms refitted" : "other terms held",
                      before.value, kept.gap.value);
  if (ranked.size() > 1) {
    const auto runner =
        std::find_if(ranked.begin(), ranked.end(), [&](const auto& o) { return o.type != effect; });
    if (runner != ranked.end()) {
      text += fmt::format(" (next best: {} at {:.3g})", term_type_name(runner->type), runner->gap);
    }
  }
  text += ". Added: " + describe_term_short(kept.term, unit) + ".";
  if (effect != TermType::kNonstationary && signature.found && signature.above &&
      signature.suggested != effect) {
    text += fmt::format(" The signature alone suggested {}; the fits decided.",
                        term_type_name(signature.suggested));
  }
  return text;
}

// Why no candidate was accepted; `best`: the lowest score assessed exactly, if any.
std::string rejection_text(const Gap& before, const RandomWalkTest& walk, const Trial* best) {
  if (before.consistent) {
    return fmt::format(
        "The time-domain test finds a rate random walk (likelihood ratio {:.1f} against "
        "{:.1f}), but no rate random walk term shrinks the gap ({:.3g}), so none was added; "
        "the model stays inconsistent.",
        walk.statistic, walk.threshold, before.value);
  }
  return fmt::format(
      "No candidate shrinks the gap significantly (best: {}), so none was added; the model "
      "stays inconsistent (gap {:.3g}).",
      best != nullptr
          ? fmt::format("{} at {:.3g}", term_type_name(best->outcome.type), best->gap.value)
          : std::string("none usable"),
      before.value);
}

// What the block means showed when the time-domain fallback kept the step.
std::string walk_evidence_text(const RandomWalkTest& walk, const RandomWalkTest& walk_after,
                               const StochasticContext& context) {
  const Quantity quantity = quantity_of(context.measured.unit);
  return fmt::format(
      " No Allan-variance candidate was accepted, but the block means ({} of {:.4g} s) show a "
      "rate random walk the model lacks: likelihood ratio {:.1f} against {:.1f} (alpha "
      "{:.0e}), profiled K = {:.3g} {}; with the term the ratio is {:.1f}.",
      walk.blocks, walk.block_s, walk.statistic, walk.threshold, context.options.alpha,
      to_reported(quantity, ParameterDimension::kRatePerRootTime, walk.k),
      reported_unit_name(quantity, ParameterDimension::kRatePerRootTime), walk_after.statistic);
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
  if (by_walk) step.evidence += walk_evidence_text(walk, by_walk->walk_after, context);
  step.after = assessment_with_band(best.model, best.gap, measured, context.options);
  result.iteration = std::move(step);
  return result;
}

}  // namespace stochnav::diagnose_stages
