#pragma once
// The Levinson recursion between AR coefficients phi_1..phi_p and partial autocorrelations
// r_1..r_p (reflection coefficients): phi_{m,m} = r_m, phi_{m,i} = phi_{m-1,i} - r_m
// phi_{m-1,m-i}. The polynomial 1 - sum phi_i z^i has all roots outside the unit circle exactly
// when every |r_m| < 1 (Schur-Cohn), which makes this the test of stationarity and the
// unconstrained parametrisation of the CSS fit (Jones 1980).

#include <cmath>
#include <optional>
#include <span>
#include <vector>

namespace stochnav::arma_detail {

/// Order m coefficients from order m - 1 ones and the new reflection coefficient r_m.
template <typename T>
std::vector<T> levinson_step(const std::vector<T>& previous, const T& r) {
  const std::size_t m = previous.size() + 1;
  std::vector<T> next(m);
  for (std::size_t i = 0; i + 1 < m; ++i) next[i] = previous[i] - r * previous[m - 2 - i];
  next[m - 1] = r;
  return next;
}

/// Coefficients phi_1..phi_p from reflection coefficients r_1..r_p.
template <typename T>
std::vector<T> coefficients_from_reflections(std::span<const T> reflections) {
  std::vector<T> phi;
  for (const T& r : reflections) phi = levinson_step(phi, r);
  return phi;
}

/// Reflection coefficients of phi by the step-down recursion, or nullopt when some |r_m| >= 1
/// (the polynomial has a root on or inside the unit circle).
inline std::optional<std::vector<double>> partial_autocorrelations(std::span<const double> ar) {
  std::vector<double> a(ar.begin(), ar.end());
  std::vector<double> reflections(a.size());
  for (std::size_t m = a.size(); m >= 1; --m) {
    const double r = a[m - 1];
    if (!(std::abs(r) < 1.0)) return std::nullopt;
    reflections[m - 1] = r;
    std::vector<double> lower(m - 1);
    for (std::size_t i = 0; i + 1 < m; ++i) {
      lower[i] = (a[i] + r * a[m - 2 - i]) / (1.0 - r * r);
    }
    a = std::move(lower);
  }
  return reflections;
}

}  // namespace stochnav::arma_detail
