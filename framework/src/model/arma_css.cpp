// ARMA(p, q) by conditional sum of squares (the conditional Gaussian likelihood), minimised
// with Ceres from a Hannan-Rissanen start; coefficients parametrised by partial
// autocorrelations tanh(u) so every iterate is stationary and invertible.

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "arma_polynomials.hpp"
#include "stochnav/model/arma.hpp"

namespace stochnav {
namespace {

// Partial autocorrelations kept this far inside (-1, 1) at the start: atanh stays finite.
constexpr double kStartReflectionLimit = 0.98;

// Residuals e_k, k >= condition_on, of the series for the unconstrained parameters
// u = (u_ar (p), u_ma (q)): phi from tanh(u_ar), theta = -(coefficients from tanh(u_ma)).
struct ConditionalResiduals {
  std::span<const double> y;
  int p;
  int q;
  int condition_on;

  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    using std::tanh;
    std::vector<T> reflections(p + q);
    for (int i = 0; i < p + q; ++i) reflections[i] = tanh(parameters[0][i]);
    const std::vector<T> phi =
        arma_detail::coefficients_from_reflections<T>(std::span<const T>(reflections).first(p));
    std::vector<T> theta =
        arma_detail::coefficients_from_reflections<T>(std::span<const T>(reflections).last(q));
    for (T& value : theta) value = -value;
    std::vector<T> e(y.size(), T(0.0));
    for (std::size_t k = condition_on; k < y.size(); ++k) {
      T value(y[k]);
      for (int i = 0; i < p; ++i) value -= phi[i] * y[k - 1 - i];
      for (int j = 0; j < q && static_cast<int>(k) - 1 - j >= 0; ++j)
        value -= theta[j] * e[k - 1 - j];
      e[k] = value;
      residuals[k - condition_on] = value;
    }
    return true;
  }
};

// Unconstrained parameter of a coefficient polynomial: atanh of its partial autocorrelations,
// each pulled inside (-limit, limit); zeros when the polynomial is not stationary.
std::vector<double> unconstrained(std::span<const double> coefficients) {
  const auto reflections = arma_detail::partial_autocorrelations(coefficients);
  std::vector<double> u(coefficients.size(), 0.0);
  if (!reflections) return u;
  for (std::size_t i = 0; i < u.size(); ++i) {
    u[i] = std::atanh(std::clamp((*reflections)[i], -kStartReflectionLimit, kStartReflectionLimit));
  }
  return u;
}

// Hannan-Rissanen: innovations from a long AR (Burg), then y_k regressed on its p lags and the
// q lags of the innovations. Returns (phi, theta).
std::pair<std::vector<double>, std::vector<double>> hannan_rissanen(std::span<const double> y,
                                                                    int p, int q) {
  const int n = static_cast<int>(y.size());
  if (q == 0 && p == 0) return {};
  const int long_order = std::min(std::max(10, 2 * (p + q)), n / 10);
  std::vector<double> innovations(n, 0.0);
  if (q > 0 && long_order >= 1) {
    const ArmaModel long_ar = fit_ar_all_orders(y, long_order, ArMethod::kBurg)[long_order];
    for (int k = long_order; k < n; ++k) {
      double value = y[k];
      for (int i = 0; i < long_order; ++i) value -= long_ar.ar[i] * y[k - 1 - i];
      innovations[k] = value;
    }
  }
  const int first = std::max(p, long_order + q);
  const int rows = n - first;
  Eigen::MatrixXd design(rows, p + q);
  Eigen::VectorXd target(rows);
  for (int row = 0; row < rows; ++row) {
    const int k = first + row;
    target(row) = y[k];
    for (int i = 0; i < p; ++i) design(row, i) = y[k - 1 - i];
    for (int j = 0; j < q; ++j) design(row, p + j) = innovations[k - 1 - j];
  }
  const Eigen::VectorXd beta = design.colPivHouseholderQr().solve(target);
  return {std::vector<double>(beta.data(), beta.data() + p),
          std::vector<double>(beta.data() + p, beta.data() + p + q)};
}

}  // namespace

ArmaFit fit_arma_css(std::span<const double> y, int p, int q, int condition_on,
                     InformationCriterion criterion) {
  const int n = static_cast<int>(y.size());
  if (p < 0 || q < 0 || condition_on < p || n < condition_on + 10 * (p + q + 1)) {
    throw std::invalid_argument("fit_arma_css: need p, q >= 0, condition_on >= p and at least " +
                                std::to_string(condition_on + 10 * (p + q + 1)) +
                                " observations; got p = " + std::to_string(p) + ", q = " +
                                std::to_string(q) + ", " + std::to_string(n) + " observations");
  }
  // Fit a unit-variance copy: tolerances then mean the same at any signal scale.
  double scale = 0.0;
  for (double v : y) scale += v * v;
  scale = std::sqrt(scale / n);
  if (!(scale > 0.0)) throw std::invalid_argument("fit_arma_css: the series has zero variance");
  std::vector<double> scaled(y.begin(), y.end());
  for (double& v : scaled) v /= scale;

  const auto [phi_start, theta_start] = hannan_rissanen(scaled, p, q);
  std::vector<double> u = unconstrained(phi_start);
  std::vector<double> negated_theta(theta_start);
  for (double& value : negated_theta) value = -value;
  const std::vector<double> u_ma = unconstrained(negated_theta);
  u.insert(u.end(), u_ma.begin(), u_ma.end());

  ConditionalResiduals functor{scaled, p, q, condition_on};
  const int residual_count = n - condition_on;
  if (p + q > 0) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<ConditionalResiduals, 4>(
        new ConditionalResiduals(functor));
    cost->AddParameterBlock(p + q);
    cost->SetNumResiduals(residual_count);
    ceres::Problem problem;
    problem.AddResidualBlock(cost, nullptr, u.data());
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.logging_type = ceres::SILENT;
    options.max_num_iterations = 200;
    options.function_tolerance = 1e-12;
    options.parameter_tolerance = 1e-12;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
  }

  std::vector<double> residuals(residual_count);
  const double* parameters[] = {u.data()};
  functor(parameters, residuals.data());
  double sum = 0.0;
  for (double e : residuals) sum += e * e;
  const double variance = sum / residual_count;

  std::vector<double> reflections(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) reflections[i] = std::tanh(u[i]);
  ArmaFit fit;
  fit.model.ar = arma_detail::coefficients_from_reflections<double>(
      std::span<const double>(reflections).first(p));
  fit.model.ma = arma_detail::coefficients_from_reflections<double>(
      std::span<const double>(reflections).last(q));
  for (double& theta : fit.model.ma) theta = -theta;
  fit.model.sigma = std::sqrt(variance) * scale;
  fit.observations = residual_count;
  fit.criterion = information_criterion(criterion, variance * scale * scale, residual_count, p + q);
  return fit;
}

ArmaFit select_arma(std::span<const double> y, int max_p, int max_q,
                    InformationCriterion criterion) {
  if (max_p < 0 || max_q < 0 || max_p + max_q < 1) {
    throw std::invalid_argument("select_arma: need max_p, max_q >= 0 and max_p + max_q >= 1");
  }
  ArmaFit best;
  best.criterion = std::numeric_limits<double>::infinity();
  for (int p = 0; p <= max_p; ++p) {
    for (int q = 0; q <= max_q; ++q) {
      if (p + q == 0) continue;
      ArmaFit fit = fit_arma_css(y, p, q, max_p, criterion);
      if (fit.criterion < best.criterion) best = std::move(fit);
    }
  }
  return best;
}

}  // namespace stochnav
