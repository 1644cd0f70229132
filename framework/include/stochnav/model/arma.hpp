#pragma once
// Autoregressive moving-average models of a zero-mean stationary series y_k (k = 0, 1, ...):
//
//   y_k = sum_{i=1..p} phi_i y_{k-i} + e_k + sum_{j=1..q} theta_j e_{k-j},   e_k ~ N(0, sigma^2)
//
// estimated from data (Burg or Yule-Walker for AR(p); conditional sum of squares with Ceres for
// ARMA(p, q)), orders chosen by an information criterion, and written in state-space form for a
// Kalman filter. The series has one unit throughout (the "signal" unit: sigma and y share it);
// k counts samples of the series (blocks of length T when the series is a block average).
//
// References: Burg's method and Levinson-Durbin as in Brockwell & Davis, "Introduction to Time
// Series and Forecasting" (2016), sections 5.1.1-5.1.2; the conditional sum of squares and the
// Hannan-Rissanen start, ibid. 5.1.4 and 5.2; the state-space form of Harvey, "Forecasting,
// Structural Time Series Models and the Kalman Filter" (1989), section 3.1.

#include <Eigen/Core>
#include <span>
#include <vector>

namespace stochnav {

/// An ARMA(p, q) model: p = ar.size(), q = ma.size().
struct ArmaModel {
  std::vector<double> ar;  ///< phi_1 .. phi_p
  std::vector<double> ma;  ///< theta_1 .. theta_q
  double sigma = 0.0;      ///< innovation standard deviation, signal unit, >= 0
};

/// True when 1 - sum phi_i z^i has all its roots strictly outside the unit circle (the AR part
/// is causal and stationary). An empty polynomial is stationary.
bool is_stationary(std::span<const double> ar);
/// True when 1 + sum theta_j z^j has all its roots strictly outside the unit circle.
bool is_invertible(std::span<const double> ma);

/// How an order is chosen: both are n log(sigma_hat^2) + penalty, smaller is better.
enum class InformationCriterion {
  kAic,  ///< penalty 2 m
  kBic,  ///< penalty m log(n)
};

/// The criterion of a fit with `parameters` coefficients (m) and innovation variance estimate
/// `innovation_variance` (> 0) on `n` observations.
double information_criterion(InformationCriterion criterion, double innovation_variance, int n,
                             int parameters);

/// Estimator of AR coefficients.
enum class ArMethod {
  kBurg,        ///< Burg: reflection coefficients minimising forward + backward errors
  kYuleWalker,  ///< Yule-Walker: Levinson-Durbin on the biased sample autocovariance
};

/// One fitted model with the criterion value it was chosen by.
struct ArmaFit {
  ArmaModel model;
  double criterion = 0.0;  ///< value of the information criterion (smaller is better)
  int observations = 0;    ///< n used by the criterion
};

/// AR(p) fits for every p in [0, max_order] in one recursion (both methods are order-recursive):
/// element p is the AR(p) model and its innovation variance estimate. Both methods give
/// stationary models. `y` is used as is (remove its mean first). Throws std::invalid_argument
/// when max_order < 0 or y.size() <= max_order + 1, or y has zero variance.
std::vector<ArmaModel> fit_ar_all_orders(std::span<const double> y, int max_order, ArMethod method);

/// The AR(p), 1 <= p <= max_order, that minimises the criterion (ties: the smaller order).
ArmaFit select_ar(std::span<const double> y, int max_order, ArMethod method,
                  InformationCriterion criterion);

/// Asymptotic standard errors of AR(p) coefficient estimates from n observations:
/// sqrt(diag(sigma^2 Gamma_p^-1) / n), Gamma_p the p x p autocovariance matrix of the model.
std::vector<double> ar_standard_errors(const ArmaModel& model, int n);

/// ARMA(p, q) by conditional least squares: minimises sum_{k >= condition_on} e_k^2 with the
/// residuals e_k = y_k - sum phi_i y_{k-i} - sum theta_j e_{k-j} computed from e_k = 0 for
/// k < condition_on (condition_on >= p; the Gaussian conditional likelihood is maximal there).
/// Solved with Ceres (automatic derivatives) from a Hannan-Rissanen start (a long AR fit gives
/// innovations, then a linear regression gives phi, theta). The coefficients are parametrised by
/// partial autocorrelations tanh(u) in (-1, 1) (Jones 1980), so the result is always stationary
/// and invertible. sigma^2 = the mean squared residual. Throws std::invalid_argument when
/// p < 0, q < 0, condition_on < p, or too few observations (< condition_on + 10 (p + q + 1)).
ArmaFit fit_arma_css(std::span<const double> y, int p, int q, int condition_on,
                     InformationCriterion criterion);

/// The ARMA(p, q), 0 <= p <= max_p, 0 <= q <= max_q, p + q >= 1, minimising the criterion;
/// every candidate conditions on the first max_p observations so criteria compare on equal n.
ArmaFit select_arma(std::span<const double> y, int max_p, int max_q,
                    InformationCriterion criterion);

/// State-space (Harvey) form of an ARMA(p, q), dimension r = max(p, q + 1):
///   x_{k+1} = A x_k + g e_{k+1},   y_k = x_k(0),   var(e) = sigma^2,
/// A (r x r) with first column phi_1..phi_r (phi_i = 0 for i > p) and ones on the
/// superdiagonal, g = (1, theta_1, .., theta_{r-1}) (theta_j = 0 for j > q). For an AR(p) it is
/// a companion form. The first state is the series itself.
struct ArmaStateSpace {
  Eigen::MatrixXd a;   ///< A, r x r
  Eigen::VectorXd g;   ///< g, r
  double sigma = 0.0;  ///< innovation standard deviation, signal unit
  int size() const { return static_cast<int>(g.size()); }
};
ArmaStateSpace state_space(const ArmaModel& model);

/// The largest state dimension the k-step transition handles without heap allocation.
inline constexpr int kMaxArmaStateSize = 24;

/// Stationary covariance P = A P A^T + sigma^2 g g^T (discrete Lyapunov equation, solved
/// through (I - A (x) A) vec P = vec(sigma^2 g g^T)), r x r, signal unit^2. Throws
/// std::invalid_argument when the AR part is not stationary.
Eigen::MatrixXd stationary_covariance(const ArmaStateSpace& model);

/// Autocovariances gamma(0..max_lag) of the series: gamma(h) = e_0^T A^h P e_0.
std::vector<double> autocovariance(const ArmaModel& model, int max_lag);

/// Transition and noise over k >= 0 steps: phi = A^k, q = sum_{j<k} A^j g g^T A^jT sigma^2
/// (k = 0: I and 0). phi, q are r x r, sized by the caller; no heap allocation when
/// r <= kMaxArmaStateSize.
void k_step_transition(const ArmaStateSpace& model, int k, Eigen::Ref<Eigen::MatrixXd> phi,
                       Eigen::Ref<Eigen::MatrixXd> q);

/// Means of consecutive blocks of `block` samples (a trailing partial block is dropped).
std::vector<double> block_means(std::span<const double> x, int block);

/// x minus its mean.
std::vector<double> demeaned(std::span<const double> x);

}  // namespace stochnav
