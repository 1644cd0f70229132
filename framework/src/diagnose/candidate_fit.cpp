#include "stochnav/diagnose/candidate_fit.hpp"

#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/effective_model.hpp"
#include "stochnav/fit/fit_noise_terms.hpp"

namespace stochnav {

std::optional<CandidateFit> fit_candidate(const NoiseModel& model, const FitData& data,
                                          TermType type, bool refit, double duration_s) {
  const StationaryEquivalent equivalent = stationary_equivalent(model, duration_s);
  FitOptions options;
  options.terms = {type};
  if (refit) {
    for (const NoiseTerm& term : equivalent.model.terms) options.terms.push_back(term_type(term));
  } else {
    options.fixed_terms = equivalent.model.terms;
  }
  FitResult fitted;
  try {
    fitted = fit_noise_terms(data, options);
  } catch (const ConfigError&) {
    return std::nullopt;  // too few points for the parameters, or no usable solution
  }
  const double back = 1.0 / std::sqrt(equivalent.variance_factor);
  CandidateFit result;
  result.refitted = refit;
  result.at_bound = fitted.diagnostics.at_bound;
  result.model = NoiseModel{model.unit, model.rate_hz, {}};
  const NonstationaryTerm* nonstationary = find_nonstationary(model);
  if (!refit) {
    for (const NoiseTerm& term : model.terms) {
      if (term_type(term) != TermType::kNonstationary) result.model.terms.push_back(term);
    }
  }
  bool candidate_seen = false;
  for (const NoiseTerm& term : fitted.model.terms) {
    NoiseTerm natural = scale_amplitude(term, back);
    // The candidate is the fitted term of its type that is not one of the refitted old ones:
    // with repeats (a second Gauss-Markov), the last of that type.
    if (term_type(natural) == type) {
      result.term = natural;
      candidate_seen = true;
    }
    result.model.terms.push_back(std::move(natural));
  }
  if (!candidate_seen) return std::nullopt;
  if (nonstationary != nullptr) result.model.terms.push_back(*nonstationary);
  return result;
}

std::optional<CandidateFit> refit_jointly(const NoiseModel& model, const FitData& data,
                                          double duration_s, std::optional<TermType> must_fit) {
  const StationaryEquivalent equivalent = stationary_equivalent(model, duration_s);
  std::vector<NoiseTerm> stationary;
  for (const NoiseTerm& term : equivalent.model.terms) {
    if (term_type(term) != TermType::kNonstationary) stationary.push_back(term);
  }
  if (stationary.empty()) return std::nullopt;
  // First every term free; a term the joint fit leaves on a search bound is then held at its
  // value (the data cannot set it beside the others) and the rest refitted once more.
  std::vector<bool> held(stationary.size(), false);
  FitResult fitted;
  for (int attempt = 0; attempt < 2; ++attempt) {
    FitOptions options;
    for (std::size_t i = 0; i < stationary.size(); ++i) {
      if (held[i]) {
        options.fixed_terms.push_back(stationary[i]);
      } else {
        options.terms.push_back(term_type(stationary[i]));
      }
    }
    if (options.terms.empty()) return std::nullopt;
    try {
      fitted = fit_noise_terms(data, options);
    } catch (const ConfigError&) {
      return std::nullopt;
    }
    if (fitted.model.terms.size() != options.terms.size()) return std::nullopt;
    if (fitted.diagnostics.at_bound.empty()) break;
    if (attempt == 1) return std::nullopt;
    bool any = false;
    for (const std::string& name : fitted.diagnostics.at_bound) {
      const std::string type_name = name.substr(0, name.find('.'));
      if (must_fit && type_name == term_type_name(*must_fit)) return std::nullopt;
      for (std::size_t i = 0; i < stationary.size(); ++i) {
        if (term_type_name(term_type(stationary[i])) == type_name) held[i] = any = true;
      }
    }
    if (!any) return std::nullopt;
  }
  const double back = 1.0 / std::sqrt(equivalent.variance_factor);
  CandidateFit result;
  result.refitted = true;
  result.model = NoiseModel{model.unit, model.rate_hz, {}};
  for (std::size_t i = 0; i < stationary.size(); ++i) {
    if (held[i]) result.model.terms.push_back(scale_amplitude(stationary[i], back));
  }
  for (const NoiseTerm& term : fitted.model.terms) {
    result.model.terms.push_back(scale_amplitude(term, back));
  }
  if (const NonstationaryTerm* nonstationary = find_nonstationary(model)) {
    result.model.terms.push_back(*nonstationary);
  }
  return result;
}

}  // namespace stochnav
