#pragma once
// Closed-form Allan variances of the noise terms, as templates on the scalar type so the fit can
// differentiate them automatically (T = double or ceres::Jet). All in natural units: tau in s,
// coefficients as in model/noise_term.hpp, results in signal^2. tau must be > 0.
//
// Each form is the Allan variance of the continuous rate process averaged over tau, which is
// also what the overlapping estimator converges to on a record whose samples are averages of the
// rate over their sampling interval (as sim/ produces them).

#include <cmath>
#include <numbers>

namespace stochnav::closed_form {

/// 2 ln 2 / pi: AVAR of flicker rate noise per B^2 (deviation floor sqrt of it = 0.664 B).
inline constexpr double kFlickerFloorPerB2 = 2.0 * std::numbers::ln2 / std::numbers::pi;

/// g(h) = h - 3/2 + 2 e^-h - e^-2h / 2 = integral_0^h (1 - e^-s)^2 ds, accurate for all h >= 0.
/// g(h) ~ h^3/3 for small h (a Taylor series is used below h = 0.1, where the closed
/// expression cancels), g(h) ~ h - 3/2 for large h. For an Ornstein-Uhlenbeck process of
/// standard deviation s and correlation time T, the variance of its integral over a time t
/// (started in the stationary state) is 2 s^2 T^2 g(t / T).
template <typename T>
T ou_integral_shape(const T& h) {
  using std::exp;
  if (h < T(0.1)) {
    // sum_{n>=3} (-1)^n (2 - 2^(n-1)) / n! h^n; 12 terms leave < 1e-16 relative error at 0.1.
    T sum(0.0);
    T power = h * h;
    double factorial = 2.0;
    double two_pow = 2.0;  // 2^(n-1)
    for (int n = 3; n <= 14; ++n) {
      power = power * h;
      factorial *= n;
      two_pow *= 2.0;
      const double sign = (n % 2 == 0) ? 1.0 : -1.0;
      sum = sum + power * (sign * (2.0 - two_pow) / factorial);
    }
    return sum;
  }
  return h - T(1.5) + T(2.0) * exp(-h) - T(0.5) * exp(T(-2.0) * h);
}

/// 3 Q^2 / tau^2.
template <typename T>
T quantization_avar(const T& q, double tau) {
  return T(3.0) * q * q / (tau * tau);
}

/// N^2 / tau.
template <typename T>
T angle_random_walk_avar(const T& n, double tau) {
  return n * n / tau;
}

/// (2 ln 2 / pi) B^2, the same at every tau.
template <typename T>
T bias_instability_avar(const T& b) {
  return T(kFlickerFloorPerB2) * b * b;
}

/// K^2 tau / 3.
template <typename T>
T rate_random_walk_avar(const T& k, double tau) {
  return k * k * (tau / 3.0);
}

/// R^2 tau^2 / 2.
template <typename T>
T rate_ramp_avar(const T& r, double tau) {
  return r * r * (tau * tau / 2.0);
}

/// (2 s^2 T / tau)[1 - (T / 2 tau)(3 - 4 e^(-tau/T) + e^(-2 tau/T))] = 2 s^2 T^2 g(tau/T) / tau^2.
template <typename T>
T gauss_markov_avar(const T& sigma, const T& tau_c, double tau) {
  const T h = T(tau) / tau_c;
  return T(2.0) * sigma * sigma * tau_c * tau_c * ou_integral_shape(h) / (tau * tau);
}

/// A^2 sin^4(pi f tau) / (pi f tau)^2.
template <typename T>
T sinusoid_avar(const T& amplitude, const T& frequency_hz, double tau) {
  using std::sin;
  const T x = frequency_hz * (std::numbers::pi * tau);
  const T s = sin(x);
  return amplitude * amplitude * (s * s) * (s * s) / (x * x);
}

}  // namespace stochnav::closed_form
