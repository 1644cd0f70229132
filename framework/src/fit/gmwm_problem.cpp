#include "gmwm_problem.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>

#include "stochnav/fit/implied_wavelet_variance.hpp"

namespace stochnav::gmwm_detail {

std::size_t GmwmProblem::free_count() const {
  return static_cast<std::size_t>(
      std::count_if(fixed_log.begin(), fixed_log.end(), [](const auto& v) { return !v; }));
}

GmwmProblem make_gmwm_problem(const GmwmData& data, const GmwmOptions& options) {
  GmwmProblem problem;
  problem.terms = options.terms;
  problem.scale_s = data.scale_s;
  problem.wv = data.wv;
  problem.tau0_s = 1.0 / data.rate_hz;
  problem.sampling = options.gauss_markov_sampling;
  // V_jj from the 95 % interval's width, (hi - lo) = 2 z sd for a symmetric interval.
  const double z = boost::math::quantile(boost::math::normal(), 0.975);
  for (std::size_t j = 0; j < data.wv.size(); ++j) {
    problem.sqrt_weight.push_back(2.0 * z / (data.wv_hi[j] - data.wv_lo[j]));
  }
  const double wv_max = *std::max_element(data.wv.begin(), data.wv.end());
  const double wv_min = *std::min_element(data.wv.begin(), data.wv.end());
  for (TermType type : options.terms) {
    problem.offset.push_back(problem.parameter_count);
    if (type == TermType::kGaussMarkov) {
      problem.lower_log.push_back(0.5 * std::log(1e-12 * wv_min));
      problem.upper_log.push_back(0.5 * std::log(1e6 * wv_max));
      problem.lower_log.push_back(std::log(kGmwmMinCorrelationTimeSamples * problem.tau0_s));
      problem.upper_log.push_back(std::log(10.0 * data.scale_s.back()));
      problem.parameter_count += 2;
      continue;
    }
    // The coefficient whose term alone reaches the measured curve at some scale.
    double v_max = 0.0;
    const double unit = 1.0;
    for (std::size_t j = 0; j < data.wv.size(); ++j) {
      v_max = std::max(v_max, data.wv[j] / term_wavelet_variance(type, &unit, data.scale_s[j],
                                                                 problem.tau0_s, problem.sampling));
    }
    problem.lower_log.push_back(0.5 * std::log(1e-12 * v_max));
    problem.upper_log.push_back(0.5 * std::log(1e4 * v_max));
    problem.parameter_count += 1;
  }
  problem.fixed_log.assign(problem.parameter_count, std::nullopt);
  problem.fixed.assign(problem.parameter_count, std::nullopt);
  problem.start_log.assign(problem.parameter_count, std::nullopt);
  problem.lower_given.assign(problem.parameter_count, false);
  problem.upper_given.assign(problem.parameter_count, false);
  for (const auto& control : options.controls) {
    const std::size_t k = problem.offset[control.term] + control.parameter;
    if (control.lower) problem.lower_log[k] = std::log(*control.lower);
    if (control.upper) problem.upper_log[k] = std::log(*control.upper);
    problem.lower_given[k] = control.lower.has_value();
    problem.upper_given[k] = control.upper.has_value();
    if (control.fixed) problem.fixed_log[k] = std::log(*control.fixed);
    problem.fixed[k] = control.fixed;
    if (control.start) problem.start_log[k] = std::log(*control.start);
  }
  return problem;
}

double gmwm_objective(const GmwmProblem& problem, const std::vector<double>& log_parameters) {
  std::vector<double> natural(log_parameters.size());
  for (std::size_t k = 0; k < natural.size(); ++k) natural[k] = std::exp(log_parameters[k]);
  double sum = 0.0;
  for (std::size_t j = 0; j < problem.scale_s.size(); ++j) {
    const double r = (problem.wv[j] - problem.model_wavelet_variance(natural.data(), j)) *
                     problem.sqrt_weight[j];
    sum += r * r;
  }
  return sum;
}

}  // namespace stochnav::gmwm_detail
