#include "stochnav/fit/fit_noise_terms.hpp"

#include <fmt/format.h>

#include <boost/math/distributions/chi_squared.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "log_avar_fit.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/fit/oadev_covariance.hpp"
#include "stochnav/model/allan_variance.hpp"

namespace stochnav {
namespace {

using fit_detail::LogAvarFit;
using fit_detail::Solution;
using fit_detail::TermParameters;

double criterion_of(const Solution& solution, std::size_t points, InformationCriterion kind) {
  const double p = static_cast<double>(solution.parameter_count);
  const double penalty = kind == InformationCriterion::kAic
                             ? 2.0 * p
                             : p * std::log(static_cast<double>(points));
  return 2.0 * solution.cost + penalty;
}

// Best solution over the starts of `added` (FitOptions::terms[slot], or kNoSlot) appended to
// `base` (jointly refitted).
Solution best_with(const LogAvarFit& fit, const std::vector<TermParameters>& base, TermType added,
                   std::size_t slot = fit_detail::kNoSlot) {
  Solution best;
  best.cost = std::numeric_limits<double>::infinity();
  for (const auto& start : fit.starts(added, slot)) {
    auto terms = base;
    terms.push_back({added, start, slot});
    Solution solution = fit.solve(std::move(terms));
    if (solution.usable && solution.cost < best.cost) best = std::move(solution);
  }
  return best;
}

// In TermType order; repeated types in the order of FitOptions::terms.
std::vector<TermParameters> canonical_order(std::vector<TermParameters> terms) {
  std::stable_sort(terms.begin(), terms.end(),
                   [](const TermParameters& a, const TermParameters& b) {
                     return a.type != b.type ? a.type < b.type : a.slot < b.slot;
                   });
  return terms;
}

std::vector<TermType> types_of(const std::vector<TermParameters>& terms) {
  std::vector<TermType> types;
  for (const auto& term : terms) types.push_back(term.type);
  return types;
}

// A parameter left on the edge of its search range: the data do not determine it.
bool any_at_bound(const LogAvarFit& fit, const Solution& solution) {
  for (const auto& term : solution.terms) {
    for (std::size_t k = 0; k < term.log_values.size(); ++k) {
      if (fit.at_bound(term, k)) return true;
    }
  }
  return false;
}

[[noreturn]] void fail(const std::string& problem) {
  throw ConfigError("noise-term fit: " + problem);
}

Solution fit_explicit(const LogAvarFit& fit, const std::vector<TermType>& terms) {
  // Easy terms first (power laws), then the ones with a shape parameter.
  std::vector<std::size_t> order(terms.size());
  for (std::size_t slot = 0; slot < order.size(); ++slot) order[slot] = slot;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return terms[a] < terms[b]; });
  std::vector<TermParameters> current;
  Solution solution;
  for (std::size_t slot : order) {
    const TermType type = terms[slot];
    solution = best_with(fit, current, type, slot);
    if (!solution.usable) {
      fail(fmt::format("no usable solution when adding {}", term_type_name(type)));
    }
    current = solution.terms;
  }
  return fit.solve(canonical_order(current));
}

Solution fit_automatic(const LogAvarFit& fit, const FitOptions& options,
                       std::vector<SelectionStep>& history) {
  const std::size_t points = fit.point_count();
  std::vector<TermParameters> current;
  double current_criterion = std::numeric_limits<double>::infinity();
  Solution current_solution;
  while (true) {
    Solution best;
    double best_criterion = std::numeric_limits<double>::infinity();
    std::size_t best_step = 0;
    for (TermType candidate : options.candidates) {
      const bool present = std::any_of(current.begin(), current.end(),
                                        [&](const auto& t) { return t.type == candidate; });
      if (present) continue;
      std::size_t parameters = fit_detail::parameter_count(candidate);
      for (const auto& term : current) parameters += term.log_values.size();
      if (parameters >= points) continue;
      Solution solution = best_with(fit, current, candidate);
      // A term the data leave on its search bound (a rate ramp of e^-14 times its read-off on
      // white noise) is not a better description, only a failed one: never select it.
      if (!solution.usable || any_at_bound(fit, solution)) continue;
      const double criterion = criterion_of(solution, points, options.criterion);
      auto terms = types_of(canonical_order(solution.terms));
      history.push_back({std::move(terms), criterion, false});
      if (criterion < best_criterion) {
        best_criterion = criterion;
        best = std::move(solution);
        best_step = history.size() - 1;
      }
    }
    if (!best.usable) break;
    if (!(best_criterion < current_criterion - options.min_criterion_improvement)) break;
    history[best_step].accepted = true;
    current = best.terms;
    current_criterion = best_criterion;
    current_solution = std::move(best);
  }
  // Backward pass: drop a term whenever keeping it is not worth the margin a term needs.
  bool dropped = true;
  while (dropped && current.size() > 1) {
    dropped = false;
    for (std::size_t j = 0; j < current.size(); ++j) {
      auto reduced = current;
      reduced.erase(reduced.begin() + static_cast<std::ptrdiff_t>(j));
      Solution solution = fit.solve(reduced);
      if (!solution.usable || any_at_bound(fit, solution)) continue;
      const double criterion = criterion_of(solution, points, options.criterion);
      if (criterion < current_criterion + options.min_criterion_improvement) {
        history.push_back({types_of(canonical_order(solution.terms)), criterion, true});
        current = solution.terms;
        current_criterion = criterion;
        current_solution = std::move(solution);
        dropped = true;
        break;
      }
    }
  }
  if (current.empty()) fail("no candidate term could be fitted to the data");
  return fit.solve(canonical_order(current));
}

}  // namespace

std::string FitOptions::validate() const {
  for (const auto* list : {&terms, &candidates}) {
    for (TermType type : *list) {
      if (type == TermType::kNonstationary) {
        return std::string(list == &terms ? "terms" : "candidates") +
               ": nonstationary terms have no Allan-variance signature to fit; expected "
               "stationary term types";
      }
    }
  }
  for (const NoiseTerm& term : fixed_terms) {
    if (term_type(term) == TermType::kNonstationary) {
      return "fixed_terms: a nonstationary term has no Allan variance to hold; expected "
             "stationary terms";
    }
  }
  if (terms.empty() && candidates.empty()) return "candidates: empty; expected at least one term";
  if (!controls.empty() && terms.empty()) {
    return "controls: the automatic term selection cannot be steered; name the terms";
  }
  if (const auto issue = check_parameter_controls(terms, controls)) return issue->message();
  if (!(loss_scale > 0.0) || !std::isfinite(loss_scale)) {
    return fmt::format("loss_scale: {}; expected a number > 0", loss_scale);
  }
  if (!(min_criterion_improvement >= 0.0) || !std::isfinite(min_criterion_improvement)) {
    return fmt::format("min_criterion_improvement: {}; expected a number >= 0",
                       min_criterion_improvement);
  }
  if (max_iterations < 1) return fmt::format("max_iterations: {}; expected >= 1", max_iterations);
  return {};
}

namespace {

// The input EDF, made non-increasing in tau: more averaging never adds degrees of freedom, and
// noise misidentification at long tau can report EDFs far too large for a point.
std::vector<double> monotone_edf(const FitData& data) {
  std::vector<std::size_t> order(data.tau_s.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return data.tau_s[a] < data.tau_s[b]; });
  std::vector<double> edf = data.edf;
  double cap = std::numeric_limits<double>::infinity();
  for (std::size_t i : order) {
    edf[i] = std::min(edf[i], cap);
    cap = edf[i];
  }
  return edf;
}

struct Weighting {
  std::vector<double> edf;
  Eigen::MatrixXd correlation;  // empty: independent points
};

// The fitted terms plus the held ones: the model the points are weighted by.
NoiseModel model_of(const Solution& solution, const FitData& data,
                    const std::vector<NoiseTerm>& fixed_terms) {
  NoiseModel model{data.unit, data.rate_hz, fixed_terms};
  for (const auto& term : solution.terms) {
    NoiseTerm value = make_term(term.type);
    for (std::size_t k = 0; k < term.log_values.size(); ++k) {
      set_parameter_value(value, k, std::exp(term.log_values[k]));
    }
    model.terms.push_back(std::move(value));
  }
  return model;
}

// EDFs and correlations of the points under `model`; nullopt when the data do not allow it
// (taus not integer multiples of tau0, or a degenerate model).
std::optional<Weighting> model_weighting(const FitData& data, const NoiseModel& model) {
  if (data.phase_count == 0) return std::nullopt;
  std::vector<std::size_t> m_values;
  for (double tau : data.tau_s) {
    const double m = std::round(tau * data.rate_hz);
    if (m < 1.0 || std::abs(m - tau * data.rate_hz) > 1e-6 * m ||
        2.0 * m >= static_cast<double>(data.phase_count)) {
      return std::nullopt;
    }
    m_values.push_back(static_cast<std::size_t>(m));
  }
  const Eigen::MatrixXd covariance =
      oadev_estimate_covariance(model, 1.0 / data.rate_hz, data.phase_count, m_values);
  Weighting weighting;
  const auto n = static_cast<Eigen::Index>(m_values.size());
  Eigen::VectorXd scale(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double avar = allan_variance(model, data.tau_s[static_cast<std::size_t>(i)]);
    const double variance = covariance(i, i);
    if (!(variance > 0.0) || !std::isfinite(variance) || !(avar > 0.0)) return std::nullopt;
    weighting.edf.push_back(2.0 * avar * avar / variance);
    scale[i] = 1.0 / std::sqrt(variance);
  }
  weighting.correlation = scale.asDiagonal() * covariance * scale.asDiagonal();
  if (!weighting.correlation.allFinite()) return std::nullopt;
  return weighting;
}

}  // namespace

namespace {

// "term_type.parameter", as parameter_label spells the given terms' ("gauss_markov#2.tau_c").
std::string parameter_name(const FitOptions& options, const TermParameters& term, std::size_t k) {
  if (term.slot != fit_detail::kNoSlot) return parameter_label(options.terms, term.slot, k);
  return fmt::format("{}.{}", term_type_name(term.type), parameter_specs(term.type)[k].name);
}

FitResult fit_noise_terms_once(const FitData& data, const FitOptions& options) {
  if (auto problem = validate(data); !problem.empty()) fail(problem);
  if (auto problem = options.validate(); !problem.empty()) fail(problem);
  std::size_t explicit_parameters = 0;
  for (TermType type : options.terms) explicit_parameters += fit_detail::parameter_count(type);
  for (const ParameterControl& control : options.controls)
    explicit_parameters -= control.fixed ? 1 : 0;
  if (explicit_parameters > data.tau_s.size()) {
    fail(fmt::format("{} parameters to fit from {} points; expected at least as many points "
                     "(use more taus, e.g. a dense tau set)",
                     explicit_parameters, data.tau_s.size()));
  }

  FitResult result;
  FitDiagnostics& diagnostics = result.diagnostics;
  diagnostics.automatic = options.terms.empty();
  const auto select = [&](const LogAvarFit& fit) {
    diagnostics.selection.clear();
    return diagnostics.automatic ? fit_automatic(fit, options, diagnostics.selection)
                                 : fit_explicit(fit, options.terms);
  };

  // Pilot fit with the input EDFs; then, when the record length is known, two passes weighted
  // by the covariance of the estimates under the current model (the first one repeats the term
  // selection with those weights).
  Weighting weighting{monotone_edf(data), {}};
  auto fit = std::make_unique<LogAvarFit>(data, options, weighting.edf);
  Solution solution = select(*fit);
  diagnostics.model_weighting = false;
  if (data.phase_count > 0) {
    for (int pass = 0; pass < 2; ++pass) {
      auto next = model_weighting(data, model_of(solution, data, options.fixed_terms));
      if (!next) {
        diagnostics.warnings.push_back(
            "points weighted by the input edf as independent: the taus are not integer "
            "multiples of 1 / rate_hz below phase_count / 2, or the model is degenerate");
        break;
      }
      weighting = std::move(*next);
      fit = std::make_unique<LogAvarFit>(data, options, weighting.edf, weighting.correlation);
      solution = pass == 0 ? select(*fit) : fit->solve(solution.terms);
      diagnostics.model_weighting = true;
    }
  }

  diagnostics.cost = solution.cost;
  diagnostics.chi_square = solution.chi_square;
  diagnostics.points = data.tau_s.size();
  diagnostics.parameters = solution.parameter_count;
  diagnostics.criterion = options.criterion;
  diagnostics.criterion_value = criterion_of(solution, data.tau_s.size(), options.criterion);
  diagnostics.loss = options.loss;
  diagnostics.loss_scale = options.loss_scale;
  diagnostics.iterations = solution.iterations;
  diagnostics.converged = solution.converged;
  diagnostics.readoffs = fit->readoffs();
  diagnostics.edf_used = weighting.edf;
  if (!solution.converged) {
    diagnostics.warnings.push_back(
        fmt::format("the final solve stopped without converging after {} iterations",
                    solution.iterations));
  }

  result.log_covariance = fit->covariance(solution);
  result.model.unit = data.unit;
  result.model.rate_hz = data.rate_hz;
  Eigen::Index offset = 0;
  for (const auto& term : solution.terms) {
    diagnostics.chosen_terms.push_back(term.type);
    NoiseTerm value = make_term(term.type);
    NoiseTerm sigma = make_term(term.type);
    for (std::size_t k = 0; k < term.log_values.size(); ++k, ++offset) {
      const double natural = std::exp(term.log_values[k]);
      const double log_variance = result.log_covariance(offset, offset);
      set_parameter_value(value, k, natural);
      if (fit->is_fixed(term, k)) {  // held: exactly as given, no uncertainty
        set_parameter_value(value, k, *fit->control(term, k)->fixed);
        set_parameter_value(sigma, k, 0.0);
        continue;
      }
      const double sigma_natural = natural * std::sqrt(log_variance);
      set_parameter_value(sigma, k, sigma_natural);
      const std::string label = parameter_name(options, term, k);
      if (fit->on_given_bound(term, k))
        diagnostics.warnings.push_back(on_bound_given_warning(label));
      if (!fit->at_bound(term, k) && !std::isfinite(sigma_natural)) {
        diagnostics.undetermined.push_back(label);
      }
      if (fit->at_bound(term, k)) {
        diagnostics.at_bound.push_back(label);
        diagnostics.warnings.push_back(fmt::format(
            "{} reached the edge of its search range: the data do not determine it", label));
      }
    }
    result.model.terms.push_back(std::move(value));
    result.sigma.push_back(std::move(sigma));
  }
  return result;
}

}  // namespace

FitResult fit_noise_terms(const FitData& data, const FitOptions& options) {
  FitResult result = fit_noise_terms_once(data, options);
  if (!options.drop_terms_at_bound || options.terms.empty()) return result;
  std::vector<std::string> dropped;
  FitOptions current = options;
  while (!result.diagnostics.at_bound.empty() && current.terms.size() > 1) {
    // Drop every term with a parameter on its bound; stop (the failure reported) when that
    // would leave none.
    std::vector<bool> drop(current.terms.size(), false);
    std::vector<std::string> on_bound_now;
    for (std::size_t slot = 0; slot < current.terms.size(); ++slot) {
      for (std::size_t k = 0; k < fit_detail::parameter_count(current.terms[slot]); ++k) {
        const std::string label = parameter_label(current.terms, slot, k);
        const auto& at_bound = result.diagnostics.at_bound;
        if (std::find(at_bound.begin(), at_bound.end(), label) == at_bound.end()) continue;
        drop[slot] = true;
        on_bound_now.push_back(fmt::format("{} (a parameter on its search bound)",
                                           term_type_name(current.terms[slot])));
        break;
      }
    }
    if (std::all_of(drop.begin(), drop.end(), [](bool d) { return d; }) ||
        std::none_of(drop.begin(), drop.end(), [](bool d) { return d; })) {
      break;
    }
    dropped.insert(dropped.end(), on_bound_now.begin(), on_bound_now.end());
    SteeredTerms kept = without_terms(current.terms, current.controls, drop);
    current.terms = std::move(kept.terms);
    current.controls = std::move(kept.controls);
    result = fit_noise_terms_once(data, current);
  }
  result.diagnostics.dropped_terms = dropped;
  for (const auto& term : dropped) {
    result.diagnostics.warnings.push_back("dropped " + term + " and refitted without it");
  }
  return result;
}

bool FitDiagnostics::failed() const { return !failure().empty(); }

std::string FitDiagnostics::failure() const {
  std::string reason;
  for (const auto& name : at_bound) {
    reason += (reason.empty() ? "" : "; ") + name + " on its search bound";
  }
  for (const auto& name : undetermined) {
    reason += (reason.empty() ? "" : "; ") + name +
              " has no uncertainty (NaN: the fit's covariance is singular there)";
  }
  const double p = chi_square_p_value();
  if (std::isfinite(p) && p < kFailedFitPValue) {
    reason += fmt::format("{}chi-square {:.4g} for {} dof (p = {:.2g} < {:g}): the terms do not "
                          "describe the record",
                          reason.empty() ? "" : "; ", chi_square, points - parameters, p,
                          kFailedFitPValue);
  }
  return reason;
}

double FitDiagnostics::reduced_chi_square() const {
  if (points <= parameters) return std::numeric_limits<double>::quiet_NaN();
  return chi_square / static_cast<double>(points - parameters);
}

double FitDiagnostics::chi_square_p_value() const {
  if (points <= parameters || !std::isfinite(chi_square)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const boost::math::chi_squared_distribution<double> distribution(
      static_cast<double>(points - parameters));
  return boost::math::cdf(boost::math::complement(distribution, std::max(chi_square, 0.0)));
}

std::string_view robust_loss_name(RobustLoss loss) {
  switch (loss) {
    case RobustLoss::kNone:
      return "none";
    case RobustLoss::kHuber:
      return "huber";
    case RobustLoss::kCauchy:
      return "cauchy";
  }
  return "none";
}

std::string_view criterion_name(InformationCriterion criterion) {
  return criterion == InformationCriterion::kAic ? "aic" : "bic";
}

std::string_view fit_method_name(FitMethod method) {
  return method == FitMethod::kGmwm ? "gmwm" : "avar";
}

}  // namespace stochnav
