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

// A term of `type` whose values do not matter (refit_jointly reads the types only); an angle
// random walk for the types the Allan loop does not add.
NoiseTerm placeholder_term(TermType type) {
  switch (type) {
    case TermType::kNonstationary:
    case TermType::kBiasStep:
    case TermType::kAuxSensitivity:
      return AngleRandomWalkTerm{};
    default:
      return make_term(type);
  }
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
  // (+1: a substitution of the final model selection)
  result.iterations.reserve(static_cast<std::size_t>(options.max_iterations) + findings.size() + 1);
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
  // The stochastic remainder in natural units, for the time-domain rate-random-walk test.
  const std::vector<double> stochastic_rate =
      options.try_time_domain_walk
          ? remove_deterministic(rate, record.rate_hz, result.deterministic, aux_rate)
          : std::vector<double>{};
  const auto walk_test = [&](const NoiseModel& m) {
    if (!options.try_time_domain_walk) return RandomWalkTest{};
    try {
      return test_rate_random_walk(stochastic_rate, record.rate_hz, m, options.alpha);
    } catch (const ConfigError&) {
      return RandomWalkTest{};  // a record too short for blocks: the test is not run
    }
  };
  const std::vector<double> dense_tau = measured.dense_fit.tau_s;
  const std::vector<double> dense_avar = measured.dense_fit.avar;
  const std::vector<double> dense_edf = measured.dense_fit.edf;

  const ModelAssessment* current =
      result.iterations.empty() ? &result.initial : &result.iterations.back().after;
  RandomWalkTest walk = walk_test(current->model);
  if (current->gap.consistent && !walk.significant) {
    result.consistent = true;
    result.conclusion =
        result.iterations.empty()
            ? fmt::format("The model is consistent with the record (gap {:.3g}): nothing to add.",
                          current->gap.value)
            : fmt::format("After {} deterministic term(s) the model is consistent with the record "
                          "(gap {:.3g}).",
                          result.iterations.size(), current->gap.value);
  }
  if (current->gap.consistent && walk.significant) {
    result.conclusion = fmt::format(
        "The gap ({:.3g}) passes, but the time-domain test finds a rate random walk the model "
        "lacks (likelihood ratio {:.1f} against {:.1f}).",
        current->gap.value, walk.statistic, walk.threshold);
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
    // The exact gap of a trial (simulated band and stationarity), once; false when it cannot be
    // computed for this model.
    const auto assess_exactly = [&](Trial& trial) {
      if (trial.outcome.exact) return true;
      try {
        trial.gap = combine_gap(avar_gap(trial.model, measured.octave_avar),
                                stationarity_test(measured.windows, trial.model), options.alpha);
      } catch (const ConfigError&) {
        return false;
      }
      trial.outcome.gap = trial.gap.value;
      trial.outcome.exact = true;
      return true;
    };
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
      // The best few by screening get the exact gap (their own estimator covariance); when
      // none of them is accepted, the rest too: every usable candidate has its chance.
      constexpr std::size_t kExactlyAssessed = 3;
      const Trial* tier_best = nullptr;
      const Trial* tier_accepted = nullptr;
      for (std::size_t index = 0; index < contenders.size(); ++index) {
        if (index >= kExactlyAssessed && tier_accepted != nullptr) break;
        Trial* trial = contenders[index];
        if (!assess_exactly(*trial)) continue;
        if (tier_best == nullptr || score(trial) < score(tier_best)) tier_best = trial;
        if (accepts(trial) && (tier_accepted == nullptr || score(trial) < score(tier_accepted))) {
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
    // The time-domain fallback: a rate random walk the block means show but the last octaves
    // of the Allan variance cannot resolve.
    bool by_walk_test = false;
    RandomWalkTest walk_after;
    if (!accepted && walk.significant) {
      std::vector<Trial*> walkers;
      Trial from_blocks;
      {
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
        from_blocks.outcome.type = TermType::kRateRandomWalk;
        from_blocks.outcome.refitted = false;
        from_blocks.outcome.usable = walk.k > 0.0;
        from_blocks.term = RateRandomWalkTerm{std::sqrt(k2)};
        from_blocks.model = std::move(candidate);
      }
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
      for (Trial* trial : walkers) {
        if (!assess_exactly(*trial)) continue;
        if (!std::isfinite(trial->gap.value) || !(trial->gap.value < before.value)) continue;
        const RandomWalkTest after = walk_test(trial->model);
        if (after.statistic > walk.statistic - walk.threshold) continue;
        if (walk_best == nullptr || trial->gap.chi_square < walk_best->gap.chi_square) {
          walk_best = trial;
          walk_after = after;
        }
      }
      if (walk_best != nullptr) {
        walk_best->outcome.usable = true;
        if (walk_best == &from_blocks) trials.push_back(std::move(from_blocks));
        best = walk_best == &from_blocks ? &trials.back() : walk_best;
        accepted = true;
        by_walk_test = true;
      }
    }
    std::vector<CandidateOutcome> outcomes;
    for (const Trial& trial : trials) outcomes.push_back(trial.outcome);
    if (!accepted) {
      if (before.consistent) {
        result.conclusion = fmt::format(
            "The time-domain test finds a rate random walk (likelihood ratio {:.1f} against "
            "{:.1f}), but no rate random walk term shrinks the gap ({:.3g}), so none was added; "
            "the model stays inconsistent.",
            walk.statistic, walk.threshold, before.value);
      } else {
        result.conclusion = fmt::format(
            "No candidate shrinks the gap significantly (best: {}), so none was added; the model "
            "stays inconsistent (gap {:.3g}).",
            best != nullptr
                ? fmt::format("{} at {:.3g}", term_type_name(best->outcome.type), best->gap.value)
                : std::string("none usable"),
            before.value);
      }
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
    if (by_walk_test) {
      step.evidence += fmt::format(
          " No Allan-variance candidate was accepted, but the block means ({} of {:.4g} s) show a "
          "rate random walk the model lacks: likelihood ratio {:.1f} against {:.1f} (alpha "
          "{:.0e}), profiled K = {:.3g} {}; with the term the ratio is {:.1f}.",
          walk.blocks, walk.block_s, walk.statistic, walk.threshold, options.alpha,
          to_reported(quantity_of(measured.unit), ParameterDimension::kRatePerRootTime, walk.k),
          reported_unit_name(quantity_of(measured.unit), ParameterDimension::kRatePerRootTime),
          walk_after.statistic);
    }
    step.after.model = best->model;
    step.after.gap = best->gap;
    if (options.seeds > 0) {
      step.after.band = simulate_band(best->model, measured.samples, measured.rate_hz,
                                      band_factors(measured), options.seeds, options.seed);
    }
    result.iterations.push_back(std::move(step));
    current = &result.iterations.back().after;
    walk = walk_test(current->model);
    if (current->gap.consistent && !walk.significant) {
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
  // Final model selection: the terms were added one at a time with the others held. Refitted
  // together (the same types), or with one added term replaced by another candidate type (a
  // Gauss-Markov term taken early can stand for a rate random walk once the rest is in), the
  // model may explain the record better. Each variant is refitted jointly and assessed exactly;
  // the one with the lowest pooled chi-square plus parameter_price per parameter is kept, when
  // it lowers the pooled chi-square, does not widen the gap and a consistent model stays
  // consistent.
  const bool added_stochastic =
      std::any_of(result.iterations.begin(), result.iterations.end(),
                  [](const DiagnoseIteration& step) { return !is_deterministic(step.effect); });
  if (options.joint_refit && added_stochastic) {
    const ModelAssessment& last = result.final_assessment();
    const auto total_parameters = [](const NoiseModel& m) {
      std::size_t p = 0;
      for (const NoiseTerm& term : m.terms) p += added_parameters(term);
      return static_cast<double>(p);
    };
    const auto criterion = [&](const Gap& gap, const NoiseModel& m) {
      return gap.chi_square + options.parameter_price * total_parameters(m);
    };
    struct Variant {
      NoiseModel model;
      Gap gap;
      RandomWalkTest walk;
      std::optional<TermType> replaced;  // the added type replaced, if any
      std::optional<NoiseTerm> substitute;
      std::optional<TermType> dropped;  // the added type dropped, if any
    };
    std::vector<NoiseModel> layouts{last.model};
    std::vector<std::optional<TermType>> replaced_of{std::nullopt};
    std::vector<std::optional<TermType>> substitute_of{std::nullopt};
    // One added term at a time replaced by each other candidate type.
    const NoiseModel& layout = last.model;
    for (const DiagnoseIteration& step : result.iterations) {
      const TermType added = step.effect;
      if (is_deterministic(added) || added == TermType::kNonstationary) continue;
      {
        // The added term dropped: a term that only carried a refit of the others.
        NoiseModel variant = layout;
        for (auto it = variant.terms.rbegin(); it != variant.terms.rend(); ++it) {
          if (term_type(*it) == added) {
            variant.terms.erase(std::next(it).base());
            break;
          }
        }
        layouts.push_back(std::move(variant));
        replaced_of.push_back(added);
        substitute_of.push_back(std::nullopt);
      }
      for (TermType type : options.candidates) {
        if (type == added || is_deterministic(type)) continue;
        if (has_type(layout, type) && !repeatable(type)) continue;
        // Only by a term of fewer parameters: the step chose its term against every other
        // candidate of its size; what the end can revisit is a two-parameter term (a
        // Gauss-Markov of long correlation time, a sinusoid) standing in for a simpler one once
        // the rest is in.
        if (added_parameters(placeholder_term(type)) >= added_parameters(placeholder_term(added))) {
          continue;
        }
        NoiseModel variant = layout;
        // The last term of the added type is the one the step added.
        for (auto it = variant.terms.rbegin(); it != variant.terms.rend(); ++it) {
          if (term_type(*it) == added) {
            *it = placeholder_term(type);
            break;
          }
        }
        layouts.push_back(std::move(variant));
        replaced_of.push_back(added);
        substitute_of.push_back(type);
      }
    }
    std::optional<Variant> chosen;
    double chosen_score = criterion(last.gap, last.model);
    const RandomWalkTest last_walk = walk_test(last.model);
    for (std::size_t v = 0; v < layouts.size(); ++v) {
      auto refit =
          refit_jointly(layouts[v], measured.dense_fit, measured.duration_s, substitute_of[v]);
      if (!refit) continue;
      try {
        Variant variant;
        variant.gap = combine_gap(avar_gap(refit->model, measured.octave_avar),
                                  stationarity_test(measured.windows, refit->model), options.alpha);
        if (!std::isfinite(variant.gap.value)) continue;
        // The same terms refitted must fit better; a substitution may fit a little worse with
        // fewer parameters (the criterion decides), but must not widen an inconsistent gap.
        if (!replaced_of[v] && !(variant.gap.chi_square < last.gap.chi_square)) continue;
        if (!(variant.gap.value <= last.gap.value) && !variant.gap.consistent) continue;
        // The block means' exact likelihood tells long-tau alternatives (a Gauss-Markov term
        // of long correlation time, a flicker floor, a random walk) apart where the last
        // octaves cannot: added to the criterion as the change from the step-by-step model.
        variant.walk = walk_test(refit->model);
        const double variant_score = criterion(variant.gap, refit->model) +
                                     (variant.walk.minus_two_log_l - last_walk.minus_two_log_l);
        if (!(variant_score < chosen_score)) continue;
        const bool variant_consistent = variant.gap.consistent && !variant.walk.significant;
        if (result.consistent && !variant_consistent) continue;
        variant.replaced = replaced_of[v];
        if (variant.replaced) {
          for (const NoiseTerm& term : refit->model.terms) {
            if (term_type(term) == *substitute_of[v]) variant.substitute = term;
          }
        }
        variant.model = std::move(refit->model);
        chosen_score = variant_score;
        chosen = std::move(variant);
      } catch (const ConfigError&) {
        // no usable assessment: this variant is out
      }
    }
    if (chosen) {
      ModelAssessment assessment;
      assessment.model = chosen->model;
      assessment.gap = chosen->gap;
      if (options.seeds > 0) {
        assessment.band = simulate_band(assessment.model, measured.samples, measured.rate_hz,
                                        band_factors(measured), options.seeds, options.seed);
      }
      const double gap_before = last.gap.value;
      const bool now_consistent = chosen->gap.consistent && !chosen->walk.significant;
      walk = chosen->walk;
      const double last_chi_square = last.gap.chi_square;
      if (chosen->replaced && !chosen->substitute) {
        chosen->dropped = chosen->replaced;
        chosen->replaced.reset();
      }
      if (chosen->replaced && chosen->substitute) {
        // A substitution is a step: the new term is named, the replaced one said.
        DiagnoseIteration step;
        step.effect = term_type(*chosen->substitute);
        step.added_term = *chosen->substitute;
        step.refitted = true;
        step.gap_before = gap_before;
        step.gap_after = chosen->gap.value;
        step.signature =
            read_signature(last.gap.avar, dense_tau, dense_avar, dense_edf, last.model);
        step.evidence = fmt::format(
            "Final model selection: with all terms refitted jointly, the {} term added earlier "
            "is better described as {}: pooled chi-square {:.1f} -> {:.1f} on {:.0f} dof with "
            "{:.0f} -> {:.0f} parameters (price {:.0f} each); gap {:.3g} -> {:.3g}. Replaced by: "
            "{}.",
            term_type_name(*chosen->replaced), term_type_name(step.effect), last.gap.chi_square,
            chosen->gap.chi_square, chosen->gap.dof, total_parameters(last.model),
            total_parameters(chosen->model), options.parameter_price, gap_before, chosen->gap.value,
            describe_term_short(step.added_term, measured.unit));
        step.after = std::move(assessment);
        result.iterations.push_back(std::move(step));
      } else {
        result.joint_refit = std::move(assessment);
      }
      if (chosen->replaced) {
        result.final_selection = fmt::format(
            "replaced {} by {} (all terms refitted jointly): gap {:.3g} -> {:.3g}",
            term_type_name(*chosen->replaced), term_type_name(result.iterations.back().effect),
            gap_before, chosen->gap.value);
      } else if (chosen->dropped) {
        result.final_selection = fmt::format(
            "dropped {} (the other terms refitted jointly without it): gap {:.3g} -> {:.3g}",
            term_type_name(*chosen->dropped), gap_before, chosen->gap.value);
      } else {
        result.final_selection = fmt::format("all terms refitted jointly: gap {:.3g} -> {:.3g}",
                                             gap_before, chosen->gap.value);
      }
      if (now_consistent && !result.consistent) {
        result.consistent = true;
        result.conclusion = fmt::format(
            "After {} step(s) and the final joint refit the model is consistent with the "
            "record (gap {:.3g}).",
            result.iterations.size(), chosen->gap.value);
      } else if (chosen->replaced) {
        result.conclusion += fmt::format(
            " Final model selection replaced the {} term by {}: gap {:.3g} -> {:.3g}.",
            term_type_name(*chosen->replaced), term_type_name(result.iterations.back().effect),
            gap_before, chosen->gap.value);
      } else if (chosen->dropped) {
        result.conclusion += fmt::format(
            " Final model selection dropped the {} term (the others refitted without it "
            "explain the record as well: pooled chi-square {:.1f} -> {:.1f}, one term fewer): "
            "gap {:.3g} -> {:.3g}.",
            term_type_name(*chosen->dropped), last_chi_square, chosen->gap.chi_square, gap_before,
            chosen->gap.value);
      } else {
        result.conclusion += fmt::format(" A joint refit of all terms: gap {:.3g} -> {:.3g}.",
                                         gap_before, chosen->gap.value);
      }
    }
  }
  result.final_walk_test = walk;
  const ModelAssessment& last = result.final_assessment();
  result.final_signature =
      read_signature(last.gap.avar, dense_tau, dense_avar, dense_edf, last.model);
  return result;
}

}  // namespace stochnav
