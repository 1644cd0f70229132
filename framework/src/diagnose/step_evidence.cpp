// Stage 3c of diagnose(): the texts of a stochastic step (diagnose_stages.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "diagnose_stages.hpp"
#include "stochnav/diagnose/effective_model.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav::diagnose_stages {

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

namespace {

// The best other candidate by the gap the kept one is reported with: the exact gap. The
// screening gaps of the candidates never assessed exactly are a cheaper approximation on
// another scale, so they are not compared with it.
std::string runner_up_text(const std::vector<CandidateOutcome>& outcomes, TermType effect) {
  const CandidateOutcome* runner = nullptr;
  for (const auto& outcome : outcomes) {
    if (!outcome.usable || !outcome.exact || outcome.type == effect) continue;
    if (runner == nullptr || outcome.gap < runner->gap) runner = &outcome;
  }
  if (runner == nullptr) return " (no other candidate was assessed exactly)";
  return fmt::format(" (next best, assessed the same way: {} at {:.3g})",
                     term_type_name(runner->type), runner->gap);
}

// A kept term whose fit ended on a search bound: flagged, never silently added.
std::string at_bound_text(const std::vector<std::string>& at_bound) {
  if (at_bound.empty()) return {};
  std::string names;
  for (const auto& name : at_bound) names += (names.empty() ? "" : ", ") + name;
  return " Flagged: " + names + " ended on the search bound of the fit: a limit of the range "
         "searched, not an estimate; read the term with care (a longer record, or a term of "
         "another type, may describe the effect).";
}

}  // namespace

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
  text += fmt::format("Of {} candidate fits, {} ({}) shrinks the gap most: {:.3g} -> {:.3g}",
                      outcomes.size(), term_type_name(effect),
                      kept.outcome.refitted ? "other terms refitted" : "other terms held",
                      before.value, kept.gap.value);
  text += runner_up_text(outcomes, effect);
  text += ". Added: " + describe_term_short(kept.term, unit) + ".";
  text += at_bound_text(kept.outcome.at_bound);
  if (effect != TermType::kNonstationary && signature.found && signature.above &&
      signature.suggested != effect) {
    text += fmt::format(" The signature alone suggested {}; the fits decided.",
                        term_type_name(signature.suggested));
  }
  return text;
}

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

std::string walk_evidence_text(const RandomWalkTest& walk, const RandomWalkTest& walk_after,
                               double alpha, Unit unit) {
  const Quantity quantity = quantity_of(unit);
  return fmt::format(
      " No Allan-variance candidate was accepted, but the block means ({} of {:.4g} s) show a "
      "rate random walk the model lacks: likelihood ratio {:.1f} against {:.1f} (alpha "
      "{:.0e}), profiled K = {:.3g} {}; with the term the ratio is {:.1f}.",
      walk.blocks, walk.block_s, walk.statistic, walk.threshold, alpha,
      to_reported(quantity, ParameterDimension::kRatePerRootTime, walk.k),
      reported_unit_name(quantity, ParameterDimension::kRatePerRootTime), walk_after.statistic);
}

}  // namespace stochnav::diagnose_stages
