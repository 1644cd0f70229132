// AR estimators (Burg, Yule-Walker), order selection, and the state-space form of ARMA models.
// The conditional-least-squares ARMA fit is in arma_css.cpp.

#include "stochnav/model/arma.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "arma_polynomials.hpp"

namespace stochnav {
namespace {

void check_series(std::span<const double> y, int max_order, const char* who) {
  if (max_order < 0 || y.size() <= static_cast<std::size_t>(max_order) + 1) {
    throw std::invalid_argument(
        std::string(who) + ": need more than max_order + 1 = " + std::to_string(max_order + 1) +
        " observations, got " + std::to_string(y.size()));
  }
}

double mean_square(std::span<const double> y) {
  double sum = 0.0;
  for (double v : y) sum += v * v;
  return sum / static_cast<double>(y.size());
}

// Burg: each reflection coefficient minimises the summed forward and backward prediction
// errors of the current order; |r| < 1 by the Cauchy-Schwarz inequality, so every model is
// stationary. f[t] holds the forward error of order m at t, b[t] the backward error.
std::vector<ArmaModel> burg_all_orders(std::span<const double> y, int max_order) {
  const std::size_t n = y.size();
  std::vector<double> f(y.begin(), y.end()), b(y.begin(), y.end());
  std::vector<ArmaModel> fits(max_order + 1);
  double variance = mean_square(y);
  fits[0].sigma = std::sqrt(variance);
  std::vector<double> phi;
  for (int m = 1; m <= max_order; ++m) {
    double cross = 0.0, power = 0.0;
    for (std::size_t t = m; t < n; ++t) {
      cross += f[t] * b[t - 1];
      power += f[t] * f[t] + b[t - 1] * b[t - 1];
    }
    const double r = power > 0.0 ? 2.0 * cross / power : 0.0;
    // Descending t: b[t - 1] still holds order m - 1 when f[t] and b[t] are updated.
    for (std::size_t t = n - 1; t >= static_cast<std::size_t>(m); --t) {
      const double forward = f[t];
      f[t] = forward - r * b[t - 1];
      b[t] = b[t - 1] - r * forward;
    }
    phi = arma_detail::levinson_step(phi, r);
    variance *= 1.0 - r * r;
    fits[m].ar = phi;
    fits[m].sigma = std::sqrt(variance);
  }
  return fits;
}

// Yule-Walker: Levinson-Durbin on the biased (divide by n) sample autocovariance, which is
// positive definite, so every model is stationary.
std::vector<ArmaModel> yule_walker_all_orders(std::span<const double> y, int max_order) {
  const std::size_t n = y.size();
  std::vector<double> gamma(max_order + 1, 0.0);
  for (int h = 0; h <= max_order; ++h) {
    for (std::size_t t = h; t < n; ++t) gamma[h] += y[t] * y[t - h];
    gamma[h] /= static_cast<double>(n);
  }
  std::vector<ArmaModel> fits(max_order + 1);
  double variance = gamma[0];
  fits[0].sigma = std::sqrt(variance);
  std::vector<double> phi;
  for (int m = 1; m <= max_order; ++m) {
    double numerator = gamma[m];
    for (int i = 1; i < m; ++i) numerator -= phi[i - 1] * gamma[m - i];
    const double r = numerator / variance;
    phi = arma_detail::levinson_step(phi, r);
    variance *= 1.0 - r * r;
    fits[m].ar = phi;
    fits[m].sigma = std::sqrt(variance);
  }
  return fits;
}

// Sum_{j<k} A^j G A^jT and A^k by k steps of Q <- A Q A^T + G, with the matrix type chosen by
// the caller (a bounded stack type avoids heap allocation).
template <typename Matrix>
void iterate_transition(const ArmaStateSpace& model, int k, Eigen::Ref<Eigen::MatrixXd> phi,
                        Eigen::Ref<Eigen::MatrixXd> q) {
  const int r = model.size();
  const Matrix a = model.a;
  const Matrix noise = model.sigma * model.sigma * (model.g * model.g.transpose());
  Matrix power = Matrix::Identity(r, r), sum = Matrix::Zero(r, r), product(r, r);
  for (int j = 0; j < k; ++j) {
    product.noalias() = a * sum;
    sum.noalias() = product * a.transpose();
    sum += noise;
    product.noalias() = a * power;
    power = product;
  }
  phi = power;
  q = 0.5 * (sum + sum.transpose());
}

}  // namespace

bool is_stationary(std::span<const double> ar) {
  return arma_detail::partial_autocorrelations(ar).has_value();
}

bool is_invertible(std::span<const double> ma) {
  std::vector<double> negated(ma.begin(), ma.end());
  for (double& theta : negated) theta = -theta;
  return is_stationary(negated);
}

double information_criterion(InformationCriterion criterion, double innovation_variance, int n,
                             int parameters) {
  const double fit = n * std::log(innovation_variance);
  switch (criterion) {
    case InformationCriterion::kAic:
      return fit + 2.0 * parameters;
    case InformationCriterion::kBic:
      return fit + parameters * std::log(static_cast<double>(n));
  }
  return fit;
}

std::vector<ArmaModel> fit_ar_all_orders(std::span<const double> y, int max_order,
                                         ArMethod method) {
  check_series(y, max_order, "fit_ar_all_orders");
  if (!(mean_square(y) > 0.0)) {
    throw std::invalid_argument("fit_ar_all_orders: the series has zero variance");
  }
  return method == ArMethod::kBurg ? burg_all_orders(y, max_order)
                                   : yule_walker_all_orders(y, max_order);
}

ArmaFit select_ar(std::span<const double> y, int max_order, ArMethod method,
                  InformationCriterion criterion) {
  if (max_order < 1) throw std::invalid_argument("select_ar: max_order must be >= 1");
  const auto fits = fit_ar_all_orders(y, max_order, method);
  const int n = static_cast<int>(y.size());
  ArmaFit best;
  best.criterion = std::numeric_limits<double>::infinity();
  best.observations = n;
  for (int p = 1; p <= max_order; ++p) {
    const double variance = fits[p].sigma * fits[p].sigma;
    // A perfect fit (zero variance) wins outright at the smallest such order.
    const double value = variance > 0.0 ? information_criterion(criterion, variance, n, p)
                                        : -std::numeric_limits<double>::infinity();
    if (value < best.criterion) {
      best.model = fits[p];
      best.criterion = value;
    }
  }
  return best;
}

std::vector<double> ar_standard_errors(const ArmaModel& model, int n) {
  const int p = static_cast<int>(model.ar.size());
  const std::vector<double> gamma = autocovariance(ArmaModel{model.ar, {}, model.sigma}, p);
  Eigen::MatrixXd toeplitz(p, p);
  for (int i = 0; i < p; ++i) {
    for (int j = 0; j < p; ++j) toeplitz(i, j) = gamma[std::abs(i - j)];
  }
  const Eigen::MatrixXd inverse = toeplitz.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
  std::vector<double> errors(p);
  for (int i = 0; i < p; ++i) {
    errors[i] = std::sqrt(model.sigma * model.sigma * inverse(i, i) / n);
  }
  return errors;
}

ArmaStateSpace state_space(const ArmaModel& model) {
  const int p = static_cast<int>(model.ar.size());
  const int q = static_cast<int>(model.ma.size());
  const int r = std::max(p, q + 1);
  ArmaStateSpace space;
  space.a = Eigen::MatrixXd::Zero(r, r);
  space.g = Eigen::VectorXd::Zero(r);
  for (int i = 0; i < p; ++i) space.a(i, 0) = model.ar[i];
  for (int i = 0; i + 1 < r; ++i) space.a(i, i + 1) = 1.0;
  space.g(0) = 1.0;
  for (int j = 0; j < q; ++j) space.g(j + 1) = model.ma[j];
  space.sigma = model.sigma;
  return space;
}

Eigen::MatrixXd stationary_covariance(const ArmaStateSpace& model) {
  const int r = model.size();
  if (!is_stationary(std::vector<double>(model.a.col(0).data(), model.a.col(0).data() + r))) {
    throw std::invalid_argument("stationary_covariance: the AR part is not stationary");
  }
  // vec(A P A^T) = (A (x) A) vec(P) for column-major vec.
  Eigen::MatrixXd system = Eigen::MatrixXd::Identity(r * r, r * r);
  for (int i = 0; i < r; ++i) {
    for (int j = 0; j < r; ++j) system.block(i * r, j * r, r, r) -= model.a(i, j) * model.a;
  }
  const Eigen::MatrixXd noise = model.sigma * model.sigma * (model.g * model.g.transpose());
  const Eigen::VectorXd rhs = noise.reshaped();
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(system);
  Eigen::VectorXd solution = lu.solve(rhs);
  solution += lu.solve(rhs - system * solution);  // one step of iterative refinement
  Eigen::MatrixXd p = solution.reshaped(r, r);
  return 0.5 * (p + p.transpose());
}

std::vector<double> autocovariance(const ArmaModel& model, int max_lag) {
  const ArmaStateSpace space = state_space(model);
  const Eigen::MatrixXd p = stationary_covariance(space);
  Eigen::VectorXd column = p.col(0);
  std::vector<double> gamma(max_lag + 1);
  for (int h = 0; h <= max_lag; ++h) {
    gamma[h] = column(0);
    column = space.a * column;
  }
  return gamma;
}

void k_step_transition(const ArmaStateSpace& model, int k, Eigen::Ref<Eigen::MatrixXd> phi,
                       Eigen::Ref<Eigen::MatrixXd> q) {
  using Bounded = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                kMaxArmaStateSize, kMaxArmaStateSize>;
  if (model.size() <= kMaxArmaStateSize) {
    iterate_transition<Bounded>(model, k, phi, q);
  } else {
    iterate_transition<Eigen::MatrixXd>(model, k, phi, q);
  }
}

std::vector<double> block_means(std::span<const double> x, int block) {
  if (block < 1) throw std::invalid_argument("block_means: block must be >= 1");
  std::vector<double> means(x.size() / block);
  for (std::size_t k = 0; k < means.size(); ++k) {
    const auto first = x.begin() + static_cast<std::ptrdiff_t>(k * block);
    means[k] = std::accumulate(first, first + block, 0.0) / block;
  }
  return means;
}

std::vector<double> demeaned(std::span<const double> x) {
  if (x.empty()) return {};
  const double mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
  std::vector<double> out(x.begin(), x.end());
  for (double& v : out) v -= mean;
  return out;
}

}  // namespace stochnav
