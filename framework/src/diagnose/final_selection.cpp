// Stage 4 of diagnose(): the final model selection (diagnose_stages.hpp).
//
// The terms were added one at a time with the others held. Refitted together (the same types),
// or with one added term replaced by another candidate type (a Gauss-Markov term taken early
// can stand for a rate random walk once the rest is in), the model may explain the record
// better. Each variant is refitted jointly and assessed exactly; the one with the lowest pooled
// chi-square plus parameter_price per parameter is kept, when it lowers the pooled chi-square,
// does not widen the gap and a consistent model stays consistent.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "diagnose_stages.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/candidate_fit.hpp"

namespace stochnav::diagnose_stages {
namespace {

// The slot of a term of `type` in a layout to refit: refit_jointly reads the terms' types only,
// so the values are make_term's defaults (an angle random walk for the types the Allan loop does
// not add, which have no Allan-variance form).
NoiseTerm layout_slot_of_type(TermType type) {
  switch (type) {
    case TermType::kNonstationary:
    case TermType::kBiasStep:
    case TermType::kAuxSensitivity:
      return AngleRandomWalkTerm{};
    default:
      return make_term(type);
  }
}

// A layout of the final model to refit jointly.
struct FinalLayout {
  NoiseModel model;
  std::optional<TermType> replaced;    // the added type replaced or dropped, if any
  std::optional<TermType> substitute;  // the type replacing it (none: dropped)
};

// The last term of `type` in `model` (the one a step added), or model.terms.rend().
auto last_term_of_type(NoiseModel& model, TermType type) {
  return std::find_if(model.terms.rbegin(), model.terms.rend(),
                      [type](const NoiseTerm& term) { return term_type(term) == type; });
}

// The layouts to refit: the model as it is; then, for each stochastic term a step added, the
// model without it and with it replaced by each candidate type of fewer parameters.
std::vector<FinalLayout> final_layouts(const DiagnoseResult& result,
                                       const DiagnoseOptions& options) {
  const NoiseModel& layout = result.final_assessment().model;
  std::vector<FinalLayout> layouts{{layout, std::nullopt, std::nullopt}};
  for (const DiagnoseIteration& step : result.iterations) {
    const TermType added = step.effect;
    if (is_deterministic(added) || added == TermType::kNonstationary) continue;
    {
      // The added term dropped: a term that only carried a refit of the others.
      NoiseModel variant = layout;
      if (auto it = last_term_of_type(variant, added); it != variant.terms.rend()) {
        variant.terms.erase(std::next(it).base());
      }
      layouts.push_back({std::move(variant), added, std::nullopt});
    }
    for (TermType type : options.candidates) {
      if (type == added || is_deterministic(type)) continue;
      if (has_type(layout, type) && !repeatable(type)) continue;
      // Only by a term of fewer parameters: the step chose its term against every other
      // candidate of its size; what the end can revisit is a two-parameter term (a
      // Gauss-Markov of long correlation time, a sinusoid) standing in for a simpler one once
      // the rest is in.
      if (added_parameters(layout_slot_of_type(type)) >=
          added_parameters(layout_slot_of_type(added))) {
        continue;
      }
      NoiseModel variant = layout;
      if (auto it = last_term_of_type(variant, added); it != variant.terms.rend()) {
        *it = layout_slot_of_type(type);
      }
      layouts.push_back({std::move(variant), added, type});
    }
  }
  return layouts;
}

// The pooled chi-square plus parameter_price per parameter of the whole model.
double selection_criterion(const Gap& gap, const NoiseModel& model,
                           const DiagnoseOptions& options) {
  return gap.chi_square + options.parameter_price * total_parameters(model);
}

}  // namespace

std::optional<FinalVariant> choose_final_variant(const DiagnoseResult& result,
                                                 const StochasticContext& context) {
  const MeasuredStatistics& measured = context.measured;
  const DiagnoseOptions& options = context.options;
  const ModelAssessment& last = result.final_assessment();
  const std::vector<FinalLayout> layouts = final_layouts(result, options);
  std::optional<FinalVariant> chosen;
  double chosen_score = selection_criterion(last.gap, last.model, options);
  const RandomWalkTest last_walk = context.walk_test(last.model);
  for (const FinalLayout& layout : layouts) {
    auto refit =
        refit_jointly(layout.model, measured.dense_fit, measured.duration_s, layout.substitute);
    if (!refit) continue;
    try {
      FinalVariant variant;
      variant.gap = combine_gap(avar_gap(refit->model, measured.octave_avar),
                                stationarity_test(measured.windows, refit->model), options.alpha);
      if (!std::isfinite(variant.gap.value)) continue;
      // The same terms refitted must fit better; a substitution may fit a little worse with
      // fewer parameters (the criterion decides), but must not widen an inconsistent gap.
      if (!layout.replaced && !(variant.gap.chi_square < last.gap.chi_square)) continue;
      if (!(variant.gap.value <= last.gap.value) && !variant.gap.consistent) continue;
      // The block means' exact likelihood tells long-tau alternatives (a Gauss-Markov term
      // of long correlation time, a flicker floor, a random walk) apart where the last
      // octaves cannot: added to the criterion as the change from the step-by-step model.
      variant.walk = context.walk_test(refit->model);
      const double variant_score = selection_criterion(variant.gap, refit->model, options) +
                                   (variant.walk.minus_two_log_l - last_walk.minus_two_log_l);
      if (!(variant_score < chosen_score)) continue;
      const bool variant_consistent = variant.gap.consistent && !variant.walk.significant;
      if (result.consistent && !variant_consistent) continue;
      variant.replaced = layout.replaced;
      if (layout.substitute) {
        for (const NoiseTerm& term : refit->model.terms) {
          if (term_type(term) == *layout.substitute) variant.substitute = term;
        }
      }
      variant.model = std::move(refit->model);
      chosen_score = variant_score;
      chosen = std::move(variant);
    } catch (const ConfigError&) {
      // no usable assessment: this variant is out
    }
  }
  return chosen;
}

void apply_final_variant(const FinalVariant& chosen, const StochasticContext& context,
                         DiagnoseResult& result) {
  const DiagnoseOptions& options = context.options;
  const MeasuredStatistics& measured = context.measured;
  ModelAssessment assessment =
      assessment_with_band(chosen.model, chosen.gap, measured, context.options);
  const ModelAssessment& last = result.final_assessment();
  const double gap_before = last.gap.value;
  const double last_chi_square = last.gap.chi_square;
  const bool now_consistent = chosen.gap.consistent && !chosen.walk.significant;
  const bool substituted = chosen.replaced && chosen.substitute;
  const bool dropped = chosen.replaced && !chosen.substitute;
  if (substituted) {
    // A substitution is a step: the new term is named, the replaced one said.
    DiagnoseIteration step;
    step.effect = term_type(*chosen.substitute);
    step.added_term = *chosen.substitute;
    step.refitted = true;
    step.gap_before = gap_before;
    step.gap_after = chosen.gap.value;
    step.signature = signature_of(last.gap, last.model, measured);
    step.evidence = fmt::format(
        "Final model selection: with all terms refitted jointly, the {} term added earlier "
        "is better described as {}: pooled chi-square {:.1f} -> {:.1f} on {:.0f} dof with "
        "{:.0f} -> {:.0f} parameters (price {:.0f} each); gap {:.3g} -> {:.3g}. Replaced by: "
        "{}.",
        term_type_name(*chosen.replaced), term_type_name(step.effect), last_chi_square,
        chosen.gap.chi_square, chosen.gap.dof, total_parameters(last.model),
        total_parameters(chosen.model), options.parameter_price, gap_before, chosen.gap.value,
        describe_term_short(step.added_term, measured.unit));
    step.after = std::move(assessment);
    result.iterations.push_back(std::move(step));  // `last` may dangle from here
  } else {
    result.joint_refit = std::move(assessment);
  }
  if (substituted) {
    result.final_selection =
        fmt::format("replaced {} by {} (all terms refitted jointly): gap {:.3g} -> {:.3g}",
                    term_type_name(*chosen.replaced),
                    term_type_name(result.iterations.back().effect), gap_before, chosen.gap.value);
  } else if (dropped) {
    result.final_selection = fmt::format(
        "dropped {} (the other terms refitted jointly without it): gap {:.3g} -> {:.3g}",
        term_type_name(*chosen.replaced), gap_before, chosen.gap.value);
  } else {
    result.final_selection = fmt::format("all terms refitted jointly: gap {:.3g} -> {:.3g}",
                                         gap_before, chosen.gap.value);
  }
  if (now_consistent && !result.consistent) {
    result.consistent = true;
    result.conclusion = fmt::format(
        "After {} step(s) and the final joint refit the model is consistent with the "
        "record (gap {:.3g}).",
        result.iterations.size(), chosen.gap.value);
  } else if (substituted) {
    result.conclusion +=
        fmt::format(" Final model selection replaced the {} term by {}: gap {:.3g} -> {:.3g}.",
                    term_type_name(*chosen.replaced),
                    term_type_name(result.iterations.back().effect), gap_before, chosen.gap.value);
  } else if (dropped) {
    result.conclusion += fmt::format(
        " Final model selection dropped the {} term (the others refitted without it "
        "explain the record as well: pooled chi-square {:.1f} -> {:.1f}, one term fewer): "
        "gap {:.3g} -> {:.3g}.",
        term_type_name(*chosen.replaced), last_chi_square, chosen.gap.chi_square, gap_before,
        chosen.gap.value);
  } else {
    result.conclusion += fmt::format(" A joint refit of all terms: gap {:.3g} -> {:.3g}.",
                                     gap_before, chosen.gap.value);
  }
}

}  // namespace stochnav::diagnose_stages
