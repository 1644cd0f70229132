#pragma once
// Fitting a candidate term to the measured Allan variance beside the current model (diagnose
// step 5), with the robust Ceres fit of fit/fit_noise_terms.hpp on the dense OADEV points.
//
// Two variants per candidate type:
//   held     the model's stationary terms are held at their values (FitOptions::fixed_terms)
//            and only the candidate's parameters are fitted: the right choice when the model is
//            right where it has terms and misses one effect;
//   refitted the model's stationary term types and the candidate are all fitted together: when
//            the missing effect also biased what the old terms stand for.
// With a nonstationary term in the model, the fit works on the stationary equivalent
// (diagnose/effective_model.hpp) and the fitted coefficients are scaled back by 1 / sqrt(w), so
// that the nonstationary segments scale the new term like the others.

#include <optional>
#include <string>
#include <vector>

#include "stochnav/fit/fit_data.hpp"
#include "stochnav/model/noise_model.hpp"

namespace stochnav {

struct CandidateFit {
  NoiseModel model;  ///< the current model with the candidate (and refitted terms)
  NoiseTerm term;    ///< the candidate term as fitted (natural units)
  bool refitted = false;
  /// Parameters the fit left on a search bound ("gauss_markov.tau_c"): limits, not estimates.
  std::vector<std::string> at_bound;
};

/// The fit of one variant; nullopt when Ceres finds no usable solution or the fit rejects the
/// data (too few points for the parameters). `type` must not be kNonstationary.
/// duration_s: the record's duration (for the stationary equivalent).
std::optional<CandidateFit> fit_candidate(const NoiseModel& model, const FitData& data,
                                          TermType type, bool refit, double duration_s);

/// All stationary terms of `model` refitted together (the same term types, repeats kept; a
/// nonstationary term is kept as it is and the fit works on the stationary equivalent, as
/// above): the joint refit at the end of the workflow, after terms were added one at a time with
/// the others held. A term left on a search bound is held at its value in `model` and the rest
/// refitted once more. nullopt when Ceres finds no usable solution, a parameter still ends on a
/// bound, the type `must_fit` (a term whose value in `model` is a placeholder) ends on one, or
/// the model has no stationary term. `term` of the result is unused.
std::optional<CandidateFit> refit_jointly(const NoiseModel& model, const FitData& data,
                                          double duration_s,
                                          std::optional<TermType> must_fit = std::nullopt);

}  // namespace stochnav
