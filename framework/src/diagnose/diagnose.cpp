#include "stochnav/diagnose/diagnose.hpp"

#include "stochnav/core/work_limits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/candidate_fit.hpp"
#include "stochnav/diagnose/effective_model.hpp"
#include "stochnav/model/allan_variance.hpp"
#include "stochnav/diagnose/deterministic_effects.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav {

std::string DiagnoseOptions::validate() const {
  if (seeds < 0 || seeds == 1 || seeds > limits::kMaxDiagnoseSeeds) {
    return fmt::format("seeds: {}; expected 0 or 2 to {} (the limit on work)", seeds,
                       limits::kMaxDiagnoseSeeds);
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

namespace {

// The dense and the octave averaging factors together: the band is drawn over the dense curve
// and tabulated at the octave points.
std::vector<std::size_t> band_factors(const MeasuredStatistics& measured) {
  std::vector<std::size_t> m;
  for (const auto& point : measured.dense) m.push_back(point.m);
  for (const auto& point : measured.octave) m.push_back(point.m);
  std::sort(m.begin(), m.end());
  m.erase(std::unique(m.begin(), m.end()), m.end());
  return m;
}

}  // namespace

ModelAssessment assess_model(const NoiseModel& model, const MeasuredStatistics& measured,
                             const DiagnoseOptions& options) {
  ModelAssessment assessment;
  assessment.model = model;
  assessment.gap = combine_gap(avar_gap(model, measured.octave_avar),
                               stationarity_test(measured.windows, model), options.alpha);
  if (options.seeds > 0) {
    assessment.band = simulate_band(model, measured.samples, measured.rate_hz,
                                    band_factors(measured), options.seeds, options.seed);
  }
  return assessment;
}

namespace {

std::size_t added_parameters(const NoiseTerm& term) {
  if (const auto* nonstationary = std::get_if<NonstationaryTerm>(&term)) {
    return 3 * nonstationary->segments.size();
  }
  return term_type(term) == TermType::kGaussMarkov || term_type(term) == TermType::kSinusoid ? 2
                                                                                             : 1;
}

bool has_type(const NoiseModel& model, TermType type) {
  return std::any_of(model.terms.begin(), model.terms.end(),
                     [&](const NoiseTerm& term) { return term_type(term) == type; });
}

// Power-law terms appear once: a second one is the first with a larger coefficient (the
// refitted variant covers that). Gauss-Markov and sinusoid terms may repeat.
bool repeatable(TermType type) {
  return type == TermType::kGaussMarkov || type == TermType::kSinusoid;
}

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

struct Trial {
  CandidateOutcome outcome;
  NoiseModel model;
  NoiseTerm term;
  Gap gap;
};

std::string describe_term_short(const NoiseTerm& term, Unit unit) {
  std::string text = describe(term, quantity_of(unit));
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
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

bool stationarity_fails(const StationarityTest& test, double alpha) {
  return test.dof > 0.0 && test.p_value < alpha;
}

}  // namespace

NoiseModel DiagnoseResult::final_model() const {
  NoiseModel model = final_assessment().model;
  for (const NoiseTerm& term : deterministic) model.terms.push_back(term);
  return model;
}

DiagnoseResult diagnose(const Record& record, const NoiseModel& model,
                        const DiagnoseOptions& options, const std::vector<AuxChannel>& aux) {
  if (const auto problem = options.validate(); !problem.empty()) {
    throw ConfigError("diagnose: " + problem);
  }
  if (const auto issue = find_model_issue(model)) {
    throw ConfigError(issue->pointer + ": " + issue->problem + "; expected " + issue->expected);
  }
  if (quantity_of(model.unit) != quantity_of(record.unit)) {
    throw ConfigError("diagnose: the model is in " + unit_name(model.unit) + " but the record in " +
                      unit_name(record.unit) + "; pass a matching --unit");
  }
  DiagnoseResult result;
  // The model's deterministic terms come off the record; the rest is the stochastic model.
  NoiseModel stochastic{model.unit, model.rate_hz, {}};
  for (const NoiseTerm& term : model.terms) {
    if (is_deterministic(term_type(term))) {
      result.deterministic.push_back(term);
    } else {
      stochastic.terms.push_back(term);
    }
  }
  const std::vector<double> rate = natural_rate(record);
  std::vector<AuxChannel> aux_rate;  // aligned with the rate samples
  for (const AuxChannel& channel : aux) {
    if (channel.values.size() < rate.size()) {
      throw ConfigError(fmt::format("diagnose: aux column \"{}\" has {} values for {} samples",
                                    channel.name, channel.values.size(), rate.size()));
    }
    aux_rate.push_back({channel.name, {channel.values.begin(),
                                       channel.values.begin() + static_cast<std::ptrdiff_t>(rate.size())}});
  }
  const auto residual_record = [&](const std::vector<NoiseTerm>& terms) {
    Record residual = record;
    residual.kind = DataKind::kRate;
    residual.values = remove_deterministic(rate, record.rate_hz, terms, aux_rate);
    const double si = si_per_unit(record.unit);
    for (double& value : residual.values) value /= si;
    return residual;
  };
  result.measured = measure_record(
      result.deterministic.empty() ? record : residual_record(result.deterministic),
      options.windows);
  result.initial = assess_model(stochastic, result.measured, options);

  // Deterministic effects, found in the time domain and removed from the record.
  std::vector<DeterministicFinding> findings;
  if (options.try_deterministic) {
    DeterministicOptions deterministic_options;
    deterministic_options.alpha = options.alpha;
    findings = find_deterministic_effects(
        remove_deterministic(rate, record.rate_hz, result.deterministic, aux_rate),
        record.rate_hz, stochastic, aux_rate, deterministic_options);
  }
  // `current` points into iterations: no reallocation while the loop runs.
  result.iterations.reserve(static_cast<std::size_t>(options.max_iterations) + findings.size());
  {
    const ModelAssessment* previous = &result.initial;
    std::vector<NoiseTerm> removed = result.deterministic;
    for (const DeterministicFinding& finding : findings) {
      removed.push_back(finding.term);
      MeasuredStatistics measured_after =
          measure_record(residual_record(removed), options.windows);
      ModelAssessment after = assess_model(stochastic, measured_after, options);
      if (after.gap.value > previous->gap.value) break;  // never a term that widens the gap
      DiagnoseIteration step;
      step.effect = term_type(finding.term);
      step.added_term = finding.term;
      step.added_term_sigma = finding.sigma;
      step.time_range_s = finding.time_range_s;
      step.gap_before = previous->gap.value;
      step.gap_after = after.gap.value;
      step.evidence = finding.evidence +
                      fmt::format(" Removed from the record: gap {:.3g} -> {:.3g}. Added: {}.",
                                  step.gap_before, step.gap_after,
                                  describe_term_short(finding.term, record.unit));
      step.after = std::move(after);
      result.iterations.push_back(std::move(step));
      result.deterministic.push_back(finding.term);
      result.measured = std::move(measured_after);
      previous = &result.iterations.back().after;
    }
  }
  const MeasuredStatistics& measured = result.measured;
  const std::vector<double> dense_tau = measured.dense_fit.tau_s;
  const std::vector<double> dense_avar = measured.dense_fit.avar;
  const std::vector<double> dense_edf = measured.dense_fit.edf;

  const ModelAssessment* current =
      result.iterations.empty() ? &result.initial : &result.iterations.back().after;
  if (current->gap.consistent) {
    result.consistent = true;
    result.conclusion =
        result.iterations.empty()
            ? fmt::format("The model is consistent with the record (gap {:.3g}): nothing to add.",
                          current->gap.value)
            : fmt::format("After {} deterministic term(s) the model is consistent with the record "
                          "(gap {:.3g}).",
                          result.iterations.size(), current->gap.value);
  }
  for (int iteration = 0; !result.consistent && iteration < options.max_iterations; ++iteration) {
    const Gap& before = current->gap;
    const NoiseModel& base = current->model;
    const Signature signature = read_signature(before.avar, dense_tau, dense_avar, dense_edf, base);

    std::vector<Trial> trials;
    // Screening: every candidate's gap with the current model's estimator scatter.
    const auto evaluate = [&](NoiseModel candidate, NoiseTerm term, TermType type, bool refitted) {
      Trial trial;
      trial.outcome.type = type;
      trial.outcome.refitted = refitted;
      try {
        trial.gap = combine_gap(screening_avar_gap(candidate, measured.octave_avar, before.avar),
                                stationarity_test(measured.windows, candidate), options.alpha);
        trial.outcome.usable = std::isfinite(trial.gap.value);
        trial.outcome.gap = trial.gap.value;
      } catch (const ConfigError&) {
        trial.outcome.usable = false;
      }
      // A term that is nowhere a material part of the model names nothing: its gain comes from
      // the refitted old terms.
      if (trial.outcome.usable && type != TermType::kNonstationary &&
          largest_share(term, candidate, measured) < options.min_term_share) {
        trial.outcome.usable = false;
        trial.outcome.immaterial = true;
      }
      trial.model = std::move(candidate);
      trial.term = std::move(term);
      trials.push_back(std::move(trial));
    };
    if (options.try_nonstationary && stationarity_fails(before.stationarity, options.alpha)) {
      if (auto term = nonstationary_candidate(measured.windows, before.stationarity, base)) {
        NoiseModel candidate = stationary_part(base);
        candidate.terms.push_back(*term);
        evaluate(std::move(candidate), *term, TermType::kNonstationary, false);
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
        evaluate(std::move(fitted->model), std::move(fitted->term), type, refit);
      }
    }
    // Two tiers: first the candidates that keep the model as it is (held terms, a
    // nonstationary term); only when none of them is accepted, also those that refit the old
    // terms. A refit can soak up a second effect into the old terms' coefficients, so it is the
    // fallback for a model whose own coefficients are off.
    const double price = options.parameter_price;
    const auto score = [&](const Trial* trial) {
      return trial->gap.chi_square + price * static_cast<double>(added_parameters(trial->term));
    };
    const auto accepts = [&](const Trial* trial) {
      const double drop = before.chi_square - trial->gap.chi_square;
      const double parameters = static_cast<double>(added_parameters(trial->term));
      const boost::math::chi_squared_distribution<double> distribution(parameters);
      const double needed = boost::math::quantile(distribution, 1.0 - options.alpha);
      // The part of the chi-square beyond its expectation must shrink by min_relative_shrink.
      const double excess_before = before.chi_square - before.dof;
      const double excess_after = trial->gap.chi_square - trial->gap.dof;
      return drop > needed && trial->gap.value < before.value &&
             excess_after <= (1.0 - options.min_relative_shrink) * excess_before;
    };
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
      // The best few by screening get the exact gap (their own estimator covariance).
      constexpr std::size_t kExactlyAssessed = 3;
      if (contenders.size() > kExactlyAssessed) contenders.resize(kExactlyAssessed);
      const Trial* tier_best = nullptr;
      for (Trial* trial : contenders) {
        if (!trial->outcome.exact) {
          try {
            trial->gap =
                combine_gap(avar_gap(trial->model, measured.octave_avar),
                            stationarity_test(measured.windows, trial->model), options.alpha);
          } catch (const ConfigError&) {
            continue;
          }
          trial->outcome.gap = trial->gap.value;
          trial->outcome.exact = true;
        }
        if (tier_best == nullptr || score(trial) < score(tier_best)) tier_best = trial;
      }
      if (tier_best != nullptr && (best == nullptr || score(tier_best) < score(best))) {
        best = tier_best;
      }
      if (tier_best != nullptr && accepts(tier_best)) {
        best = tier_best;
        accepted = true;
        break;
      }
    }
    std::vector<CandidateOutcome> outcomes;
    for (const Trial& trial : trials) outcomes.push_back(trial.outcome);
    if (!accepted) {
      result.conclusion = fmt::format(
          "No candidate shrinks the gap significantly (best: {}), so none was added; the model "
          "stays inconsistent (gap {:.3g}).",
          best != nullptr
              ? fmt::format("{} at {:.3g}", term_type_name(best->outcome.type), best->gap.value)
              : std::string("none usable"),
          before.value);
      break;
    }
    DiagnoseIteration step;
    step.effect = best->outcome.type;
    step.refitted = best->outcome.refitted;
    step.added_term = best->term;
    step.gap_before = before.value;
    step.gap_after = best->gap.value;
    step.signature = signature;
    step.candidates = outcomes;
    if (step.effect == TermType::kNonstationary) {
      step.time_range_s = segment_time_range(best->term, base);
    } else {
      step.tau_range_s = signature.tau_range_s;
    }
    step.evidence =
        evidence_text(signature, before, *best, outcomes, step.time_range_s, measured.unit);
    step.after.model = best->model;
    step.after.gap = best->gap;
    if (options.seeds > 0) {
      step.after.band = simulate_band(best->model, measured.samples, measured.rate_hz,
                                      band_factors(measured), options.seeds, options.seed);
    }
    result.iterations.push_back(std::move(step));
    current = &result.iterations.back().after;
    if (current->gap.consistent) {
      result.consistent = true;
      result.conclusion =
          fmt::format("After {} step(s) the model is consistent with the record (gap {:.3g}).",
                      result.iterations.size(), current->gap.value);
    } else if (iteration + 1 == options.max_iterations) {
      result.conclusion = fmt::format(
          "Stopped after the maximum of {} steps; the model is still inconsistent (gap {:.3g}).",
          options.max_iterations, current->gap.value);
    }
  }
  if (!result.consistent && options.max_iterations == 0) {
    result.conclusion = "The model is inconsistent with the record; no steps were allowed.";
  }
  const ModelAssessment& last = result.final_assessment();
  result.final_signature =
      read_signature(last.gap.avar, dense_tau, dense_avar, dense_edf, last.model);
  return result;
}

}  // namespace stochnav
