#include "stochnav/fit/gmwm_fit.hpp"

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "gmwm_problem.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/fit/implied_wavelet_variance.hpp"

namespace stochnav {
namespace {

using gmwm_detail::GmwmProblem;

/// Whitened residuals sqrt(Omega_jj) (nu_hat_j - nu_j(exp(p))) of one flat log-parameter block.
struct WhitenedWaveletResiduals {
  const GmwmProblem* problem;

  template <typename T>
  bool operator()(T const* const* blocks, T* residuals) const {
    const GmwmProblem& p = *problem;
    std::vector<T> natural(p.parameter_count);
    for (std::size_t k = 0; k < p.parameter_count; ++k) natural[k] = exp(blocks[0][k]);
    for (std::size_t j = 0; j < p.scale_s.size(); ++j) {
      residuals[j] = (T(p.wv[j]) - p.model_wavelet_variance(natural.data(), j)) * p.sqrt_weight[j];
    }
    return true;
  }
};

ceres::CostFunction* make_cost(const GmwmProblem& problem) {
  auto* cost = new ceres::DynamicAutoDiffCostFunction<WhitenedWaveletResiduals, 8>(
      new WhitenedWaveletResiduals{&problem});
  cost->AddParameterBlock(static_cast<int>(problem.parameter_count));
  cost->SetNumResiduals(static_cast<int>(problem.scale_s.size()));
  return cost;
}

struct GmwmSolution {
  std::vector<double> log_parameters;
  double objective = std::numeric_limits<double>::infinity();
  int iterations = 0;
  bool converged = false;
};

GmwmSolution solve_from(const GmwmProblem& problem, std::vector<double> start, int max_iterations) {
  ceres::Problem ceres_problem;
  double* block = start.data();
  ceres_problem.AddResidualBlock(make_cost(problem), nullptr, block);
  std::vector<int> fixed;
  for (std::size_t k = 0; k < problem.parameter_count; ++k) {
    if (problem.fixed_log[k]) {
      fixed.push_back(static_cast<int>(k));
      continue;
    }
    ceres_problem.SetParameterLowerBound(block, static_cast<int>(k), problem.lower_log[k]);
    ceres_problem.SetParameterUpperBound(block, static_cast<int>(k), problem.upper_log[k]);
  }
  if (fixed.size() == problem.parameter_count) {
    ceres_problem.SetParameterBlockConstant(block);
  } else if (!fixed.empty()) {
    ceres_problem.SetManifold(
        block, new ceres::SubsetManifold(static_cast<int>(problem.parameter_count), fixed));
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-12;
  options.parameter_tolerance = 1e-10;
  options.gradient_tolerance = 1e-14;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &ceres_problem, &summary);
  GmwmSolution solution;
  solution.objective = 2.0 * summary.final_cost;
  solution.iterations = static_cast<int>(summary.iterations.size());
  solution.converged = summary.termination_type == ceres::CONVERGENCE;
  solution.log_parameters = std::move(start);
  return solution;
}

/// A = d(whitened residual) / d(log parameter) at `log_parameters`, all parameters.
Eigen::MatrixXd whitened_jacobian(const GmwmProblem& problem, std::vector<double> log_parameters) {
  ceres::Problem ceres_problem;
  ceres_problem.AddResidualBlock(make_cost(problem), nullptr, log_parameters.data());
  ceres::CRSMatrix crs;
  ceres_problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, nullptr, nullptr, &crs);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r) {
    for (int i = crs.rows[r]; i < crs.rows[r + 1]; ++i) a(r, crs.cols[i]) = crs.values[i];
  }
  return a;
}

std::string check_fit_size(const GmwmData& data, const GmwmOptions& options,
                           const GmwmProblem& problem) {
  const std::size_t scales = data.scale_s.size();
  const std::size_t free = problem.free_count();
  if (scales < free + 1) {
    return fmt::format(
        "{}: {} scales for {} free parameters; GMWM needs at least one scale more "
        "than parameters: use a longer record or fewer --terms",
        data.source, scales, free);
  }
  const bool ramp = std::find(options.terms.begin(), options.terms.end(), TermType::kRateRamp) !=
                    options.terms.end();
  if (ramp && scales < kGmwmRampMinScales) {
    return fmt::format(
        "{}: a rate_ramp (drift) needs at least {} wavelet-variance scales (a "
        "record of {} samples) to be told from a random walk; the record gives {}: "
        "drop rate_ramp or use a longer record",
        data.source, kGmwmRampMinScales, std::size_t{2} << kGmwmRampMinScales, scales);
  }
  return {};
}

/// The model, uncertainties and diagnostics of the best solution.
FitResult make_result(const GmwmData& data, const GmwmProblem& problem, const GmwmSolution& best) {
  FitResult result;
  result.model.unit = data.unit;
  result.model.rate_hz = data.rate_hz;
  std::vector<std::size_t> free;
  for (std::size_t k = 0; k < problem.parameter_count; ++k) {
    if (!problem.fixed_log[k]) free.push_back(k);
  }
  const Eigen::MatrixXd a_all = whitened_jacobian(problem, best.log_parameters);
  Eigen::MatrixXd a(a_all.rows(), static_cast<Eigen::Index>(free.size()));
  for (std::size_t i = 0; i < free.size(); ++i) {
    a.col(static_cast<Eigen::Index>(i)) = a_all.col(static_cast<Eigen::Index>(free[i]));
  }
  const Eigen::MatrixXd information = a.transpose() * a;
  // Pseudo-inverse: a direction the data do not determine (a singular value below 1e-12 of the
  // largest) leaves the parameters with a share of it undetermined (NaN), the others keep theirs.
  // With every parameter held there would be nothing to decompose (Eigen's SVD of an empty
  // matrix crashes); check_parameter_controls refuses that, the guard stays.
  const auto p = static_cast<Eigen::Index>(problem.parameter_count);
  result.log_covariance = Eigen::MatrixXd::Zero(p, p);
  std::vector<bool> undetermined(problem.parameter_count, false);
  if (!free.empty()) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(information,
                                                Eigen::ComputeFullU | Eigen::ComputeFullV);
    const auto& singular = svd.singularValues();
    const double threshold = 1e-12 * singular.maxCoeff();
    Eigen::MatrixXd inverse = Eigen::MatrixXd::Zero(information.rows(), information.cols());
    for (Eigen::Index i = 0; i < singular.size(); ++i) {
      const auto v = svd.matrixV().col(i);
      if (singular[i] > threshold) {
        inverse += v * v.transpose() / singular[i];
        continue;
      }
      for (Eigen::Index m = 0; m < v.size(); ++m) {
        if (std::abs(v[m]) > 0.1) undetermined[free[static_cast<std::size_t>(m)]] = true;
      }
    }
    for (std::size_t i = 0; i < free.size(); ++i) {
      for (std::size_t m = 0; m < free.size(); ++m) {
        result.log_covariance(static_cast<Eigen::Index>(free[i]),
                              static_cast<Eigen::Index>(free[m])) =
            inverse(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(m));
      }
    }
  }
  FitDiagnostics& d = result.diagnostics;
  for (std::size_t t = 0; t < problem.terms.size(); ++t) {
    const TermType type = problem.terms[t];
    NoiseTerm term = make_term(type);
    NoiseTerm sigma = make_term(type);
    for (std::size_t i = 0; i < parameter_specs(type).size(); ++i) {
      const std::size_t k = problem.offset[t] + i;
      // A held parameter exactly as given (exp(log v) may differ from v in the last bit).
      const double value = problem.fixed[k] ? *problem.fixed[k] : std::exp(best.log_parameters[k]);
      set_parameter_value(term, i, value);
      const auto kk = static_cast<Eigen::Index>(k);
      const bool held = problem.fixed_log[k].has_value();
      const double sd = held              ? 0.0
                        : undetermined[k] ? std::nan("")
                                          : value * std::sqrt(result.log_covariance(kk, kk));
      set_parameter_value(sigma, i, sd);
      if (held) continue;
      const double margin = 1e-6 * (problem.upper_log[k] - problem.lower_log[k]);
      const bool on_lower = best.log_parameters[k] <= problem.lower_log[k] + margin;
      const bool on_upper = best.log_parameters[k] >= problem.upper_log[k] - margin;
      if ((on_lower && problem.lower_given[k]) || (on_upper && problem.upper_given[k])) {
        // The user's constraint, not a failed parameter (fit/parameter_control.hpp).
        d.warnings.push_back(on_bound_given_warning(parameter_label(problem.terms, t, i)));
      } else if (on_lower || on_upper) {
        d.at_bound.push_back(parameter_label(problem.terms, t, i));
      } else if (!std::isfinite(sd)) {
        d.undetermined.push_back(parameter_label(problem.terms, t, i));
      }
    }
    result.model.terms.push_back(term);
    result.sigma.push_back(sigma);
  }
  d.method = FitMethod::kGmwm;
  d.gauss_markov_sampling = problem.sampling;
  d.cost = best.objective;
  d.chi_square = best.objective;
  d.points = data.scale_s.size();
  d.parameters = free.size();
  d.criterion_value = best.objective + 2.0 * static_cast<double>(free.size());
  d.loss = RobustLoss::kNone;
  d.loss_scale = 0.0;
  d.iterations = best.iterations;
  d.converged = best.converged;
  d.chosen_terms = problem.terms;
  if (!best.converged) d.warnings.push_back("the best start did not meet a Ceres tolerance");
  return result;
}

}  // namespace

std::string GmwmOptions::validate() const {
  if (terms.empty())
    return "GMWM: no term given; name the terms (e.g. --terms "
           "angle_random_walk,gauss_markov,rate_random_walk)";
  for (TermType type : terms) {
    if (!has_wavelet_variance_form(type)) {
      return fmt::format(
          "GMWM: {} has no wavelet-variance form; use quantization, "
          "angle_random_walk, bias_instability, rate_random_walk, rate_ramp or "
          "gauss_markov",
          term_type_name(type));
    }
  }
  if (starts < 1 || max_iterations < 1) return "GMWM: starts and max_iterations must be >= 1";
  if (const auto issue = check_parameter_controls(terms, controls)) {
    return "GMWM: " + issue->message();
  }
  return {};
}

namespace {

/// One fit of options.terms; term_at_bound[t] names term t's parameters left on their search
/// bound (empty when none).
FitResult fit_gmwm_once(const GmwmData& data, const GmwmOptions& options,
                        std::vector<std::string>& term_at_bound) {
  const GmwmProblem problem = gmwm_detail::make_gmwm_problem(data, options);
  if (const auto reason = check_fit_size(data, options, problem); !reason.empty()) {
    throw ConfigError(reason);
  }
  GmwmSolution best;
  for (auto& start : gmwm_detail::gmwm_starting_points(problem, options.starts)) {
    GmwmSolution solution = solve_from(problem, std::move(start), options.max_iterations);
    if (solution.objective < best.objective) best = std::move(solution);
  }
  FitResult result = make_result(data, problem, best);
  term_at_bound.assign(problem.terms.size(), {});
  const auto& names = result.diagnostics.at_bound;
  for (std::size_t t = 0; t < problem.terms.size(); ++t) {
    for (std::size_t i = 0; i < parameter_specs(problem.terms[t]).size(); ++i) {
      const std::string label = parameter_label(problem.terms, t, i);
      if (std::find(names.begin(), names.end(), label) != names.end()) {
        term_at_bound[t] += (term_at_bound[t].empty() ? "" : ", ") + label;
      }
    }
  }
  return result;
}

}  // namespace

FitResult fit_gmwm(const GmwmData& data, const GmwmOptions& options) {
  if (const auto problem = validate(data); !problem.empty()) throw InputError(problem);
  if (const auto problem = options.validate(); !problem.empty()) throw ConfigError(problem);
  std::vector<std::string> at_bound;
  FitResult result = fit_gmwm_once(data, options, at_bound);
  if (!options.drop_terms_at_bound) return result;
  // As the Allan fit does (FitOptions::drop_terms_at_bound): every term with a parameter on its
  // bound is dropped and the rest refitted, until none is on a bound or none would be left; the
  // dropped terms are named in the diagnostics.
  const auto on_bound = [](const std::string& names) { return !names.empty(); };
  GmwmOptions current = options;
  std::vector<std::string> dropped;
  while (std::any_of(at_bound.begin(), at_bound.end(), on_bound) &&
         !std::all_of(at_bound.begin(), at_bound.end(), on_bound)) {
    std::vector<bool> drop(current.terms.size(), false);
    for (std::size_t t = 0; t < current.terms.size(); ++t) {
      if (!on_bound(at_bound[t])) continue;
      drop[t] = true;
      dropped.push_back(fmt::format("{} ({} on its search bound)", term_type_name(current.terms[t]),
                                    at_bound[t]));
    }
    SteeredTerms kept = without_terms(current.terms, current.controls, drop);
    GmwmOptions next = current;
    next.terms = std::move(kept.terms);
    next.controls = std::move(kept.controls);
    current = std::move(next);
    result = fit_gmwm_once(data, current, at_bound);
  }
  result.diagnostics.dropped_terms = dropped;
  for (const auto& term : dropped) {
    result.diagnostics.warnings.push_back("dropped " + term + " and refitted without it");
  }
  return result;
}

std::vector<FitResult> rank_gmwm_models(const GmwmData& data,
                                        std::span<const std::vector<TermType>> candidates,
                                        const GmwmOptions& common) {
  std::vector<FitResult> fits;
  std::vector<RankedModel> ranking;
  for (const auto& terms : candidates) {
    GmwmOptions options = common;
    options.terms = terms;
    options.controls.clear();
    fits.push_back(fit_gmwm(data, options));
    const FitDiagnostics& d = fits.back().diagnostics;
    ranking.push_back({terms, d.criterion_value, d.cost, d.dropped_terms, d.failed()});
  }
  std::vector<std::size_t> order(fits.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return ranking[a].wic < ranking[b].wic; });
  std::vector<FitResult> sorted;
  std::vector<RankedModel> sorted_ranking;
  for (std::size_t i : order) {
    sorted.push_back(std::move(fits[i]));
    sorted_ranking.push_back(std::move(ranking[i]));
  }
  if (!sorted.empty()) sorted.front().ranking = std::move(sorted_ranking);
  return sorted;
}

}  // namespace stochnav
