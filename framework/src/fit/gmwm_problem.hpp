#pragma once
// The GMWM objective as plain numbers, shared by the starting-value search (gmwm_starts.cpp)
// and the Ceres fit (gmwm_fit.cpp). Parameters form one flat vector: per term, in
// parameter_specs order, the natural log of each coefficient (Q | N | B | K | |R| | sigma,
// tau_c; natural units).

#include <optional>
#include <vector>

#include "stochnav/fit/gmwm_fit.hpp"
#include "stochnav/fit/implied_wavelet_variance.hpp"

namespace stochnav::gmwm_detail {

struct GmwmProblem {
  std::vector<TermType> terms;
  std::vector<std::size_t> offset;  ///< first flat index of each term
  std::size_t parameter_count = 0;
  std::vector<double> scale_s;      ///< tau_j (s)
  std::vector<double> wv;           ///< nu_hat_j (natural units^2)
  std::vector<double> sqrt_weight;  ///< sqrt(Omega_jj) = 1 / sd(nu_hat_j)
  std::vector<double> lower_log;    ///< per flat parameter
  std::vector<double> upper_log;
  std::vector<bool> lower_given;  ///< lower_log is a bound the user gave (controls)
  std::vector<bool> upper_given;
  std::vector<std::optional<double>> fixed_log;  ///< held values
  std::vector<std::optional<double>> fixed;      ///< held values as given (natural units)
  std::vector<std::optional<double>> start_log;  ///< given starts
  double tau0_s = 0.0;
  GaussMarkovSampling sampling = GaussMarkovSampling::kIntervalMean;

  /// The implied wavelet variance at scale j of the terms with natural parameters `natural`.
  template <typename T>
  T model_wavelet_variance(const T* natural, std::size_t j) const {
    T sum(0.0);
    for (std::size_t t = 0; t < terms.size(); ++t) {
      sum += term_wavelet_variance(terms[t], natural + offset[t], scale_s[j], tau0_s, sampling);
    }
    return sum;
  }

  /// Flat parameters that are fitted (not fixed).
  std::size_t free_count() const;
};

/// Omega, bounds and controls of `options` on `data` (both validated by the caller).
GmwmProblem make_gmwm_problem(const GmwmData& data, const GmwmOptions& options);

/// sum_j Omega_jj (nu_hat_j - nu_j(theta))^2 for flat natural-log parameters.
double gmwm_objective(const GmwmProblem& problem, const std::vector<double>& log_parameters);

/// Natural-log starting vectors, best first (at most `count`; see gmwm_fit.hpp).
std::vector<std::vector<double>> gmwm_starting_points(const GmwmProblem& problem,
                                                      std::size_t count);

}  // namespace stochnav::gmwm_detail
