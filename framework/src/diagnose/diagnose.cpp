#include "stochnav/diagnose/diagnose.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "diagnose_stages.hpp"
#include "stochnav/core/work_limits.hpp"

namespace stochnav {

std::string DiagnoseOptions::validate() const {
  if (seeds < 0 || seeds == 1 || seeds > limits::kMaxDiagnoseSeeds) {
    return fmt::format("seeds: {}; expected 0 (no simulated band) or 2 to {} (a band needs two "
                       "records at least; {} is the limit on work)",
                       seeds, limits::kMaxDiagnoseSeeds, limits::kMaxDiagnoseSeeds);
  }
  if (max_iterations < 0 || max_iterations > limits::kMaxDiagnoseIterations) {
    return fmt::format("max_iterations: {}; expected 0 to {} (the limit on work)", max_iterations,
                       limits::kMaxDiagnoseIterations);
  }
  if (!(alpha > 0.0 && alpha < 0.5)) return fmt::format("alpha: {}; expected in (0, 0.5)", alpha);
  if (windows < 4 || windows > limits::kMaxStationarityWindows) {
    return fmt::format("windows: {}; expected 4 to {} (the limit on work)", windows,
                       limits::kMaxStationarityWindows);
  }
  if (!(min_term_share >= 0.0 && min_term_share < 1.0)) {
    return fmt::format("min_term_share: {}; expected in [0, 1)", min_term_share);
  }
  if (!(parameter_price >= 0.0) || !std::isfinite(parameter_price)) {
    return fmt::format("parameter_price: {}; expected a number >= 0", parameter_price);
  }
  if (!(min_relative_shrink >= 0.0 && min_relative_shrink < 1.0)) {
    return fmt::format("min_relative_shrink: {}; expected in [0, 1)", min_relative_shrink);
  }
  for (TermType type : candidates) {
    if (type == TermType::kNonstationary) {
      return "candidates: nonstationary is offered by try_nonstationary; expected stationary types";
    }
    if (is_deterministic(type) && type != TermType::kRateRamp) {
      return fmt::format("candidates: {} is found in the time domain (try_deterministic)",
                         term_type_name(type));
    }
  }
  return {};
}

ModelAssessment assess_model(const NoiseModel& model, const MeasuredStatistics& measured,
                             const DiagnoseOptions& options) {
  const Gap gap = combine_gap(avar_gap(model, measured.octave_avar),
                              stationarity_test(measured.windows, model), options.alpha);
  return diagnose_stages::assessment_with_band(model, gap, measured, options);
}

NoiseModel DiagnoseResult::final_model() const {
  NoiseModel model = final_assessment().model;
  for (const NoiseTerm& term : deterministic) model.terms.push_back(term);
  return model;
}

namespace {

// The conclusion before any stochastic step, when the model (with the deterministic terms
// found) passes the gap; empty when it does not.
std::string conclusion_before_steps(const DiagnoseResult& result, const RandomWalkTest& walk) {
  const ModelAssessment& current = result.final_assessment();
  if (!current.gap.consistent) return {};
  if (walk.significant) {
    return fmt::format(
        "The gap ({:.3g}) passes, but the time-domain test finds a rate random walk the model "
        "lacks (likelihood ratio {:.1f} against {:.1f}).",
        current.gap.value, walk.statistic, walk.threshold);
  }
  return result.iterations.empty()
             ? fmt::format("The model is consistent with the record (gap {:.3g}): nothing to add.",
                           current.gap.value)
             : fmt::format(
                   "After {} deterministic term(s) the model is consistent with the record "
                   "(gap {:.3g}).",
                   result.iterations.size(), current.gap.value);
}

// One stage of diagnose() done, for a progress display (DiagnoseOptions::stages_done).
void count_diagnose_stage(const DiagnoseOptions& options) {
  if (options.stages_done != nullptr) options.stages_done->fetch_add(1, std::memory_order_relaxed);
}

bool added_stochastic_term(const DiagnoseResult& result) {
  return std::any_of(result.iterations.begin(), result.iterations.end(),
                     [](const DiagnoseIteration& step) { return !is_deterministic(step.effect); });
}

}  // namespace

DiagnoseResult diagnose(const Record& record, const NoiseModel& model,
                        const DiagnoseOptions& options, const std::vector<AuxChannel>& aux) {
  namespace stages = diagnose_stages;
  // Inputs (step 1): the model's deterministic terms come off the record; the rest is the
  // stochastic model.
  stages::check_diagnose_inputs(record, model, options);
  stages::SplitModel split = stages::split_model(model);
  DiagnoseResult result;
  result.deterministic = std::move(split.deterministic);
  const stages::RecordResiduals residuals(record, aux);
  result.measured = measure_record(
      result.deterministic.empty() ? record : residuals.record_without(result.deterministic),
      options.windows);
  count_diagnose_stage(options);
  result.initial = assess_model(split.stochastic, result.measured, options);
  count_diagnose_stage(options);

  // Deterministic effects (before step 2), found in the time domain and removed from the record.
  const std::vector<DeterministicFinding> findings =
      stages::find_record_effects(residuals, split.stochastic, result, options);
  // Room for every step (+1: a substitution of the final model selection), so that references
  // into the iterations stay valid while they grow.
  result.iterations.reserve(static_cast<std::size_t>(options.max_iterations) + findings.size() + 1);
  stages::accept_deterministic_findings(findings, residuals, split.stochastic, options, result);

  // The stochastic loop (steps 3-7): one term a step while the gap or the time-domain test
  // says the model is inconsistent. result.measured stays as it is from here.
  const stages::TimeDomainWalkTest walk_test(residuals, result.deterministic, options);
  const stages::StochasticContext context{result.measured, options, walk_test};
  RandomWalkTest walk = walk_test(result.final_assessment().model);
  result.conclusion = conclusion_before_steps(result, walk);
  result.consistent = result.final_assessment().gap.consistent && !walk.significant;
  for (int iteration = 0; !result.consistent && iteration < options.max_iterations; ++iteration) {
    stages::StepResult step =
        stages::take_stochastic_step(result.final_assessment(), walk, context);
    if (!step.iteration) {
      result.conclusion = std::move(step.rejection);
      break;
    }
    result.iterations.push_back(std::move(*step.iteration));
    count_diagnose_stage(options);
    const ModelAssessment& current = result.iterations.back().after;
    walk = walk_test(current.model);
    if (current.gap.consistent && !walk.significant) {
      result.consistent = true;
      result.conclusion =
          fmt::format("After {} step(s) the model is consistent with the record (gap {:.3g}).",
                      result.iterations.size(), current.gap.value);
    } else if (iteration + 1 == options.max_iterations) {
      result.conclusion = fmt::format(
          "Stopped after the maximum of {} steps; the model is still inconsistent (gap {:.3g}).",
          options.max_iterations, current.gap.value);
    }
  }
  if (!result.consistent && options.max_iterations == 0) {
    result.conclusion = "The model is inconsistent with the record; no steps were allowed.";
  }

  // Final model selection (step 8): the terms refitted jointly, or an added term replaced or
  // dropped.
  if (options.joint_refit && added_stochastic_term(result)) {
    if (const auto chosen = stages::choose_final_variant(result, context)) {
      walk = chosen->walk;
      stages::apply_final_variant(*chosen, context, result);
    }
  }
  result.final_walk_test = walk;
  stages::check_wavelet_variance(residuals, walk_test, options, result);
  count_diagnose_stage(options);
  const ModelAssessment& last = result.final_assessment();
  result.final_signature = stages::signature_of(last.gap, last.model, result.measured);
  return result;
}

}  // namespace stochnav
