#pragma once
// Covariance of the overlapping Allan-variance estimates of one record of a noise model, across
// averaging factors: the uncertainties and correlations the fit needs (the estimates at
// neighbouring taus share data and are strongly correlated, about 0.5 at octave spacing).
//
// Method (Gaussian noise, exact for a finite record, no asymptotics): the estimate at factor m is
//   A(m) = sum_{i<n} d_i(m)^2 / (2 tau^2 n),  d_i(m) = x[i+2m] - 2 x[i+m] + x[i],  n = N - 2m,
// over N phase points x. For zero-mean Gaussian d, Cov(d^2, d'^2) = 2 Cov(d, d')^2, and
//   Cov(d_i(m1), d_j(m2)) = C12(i - j) = sum_{p,q in 0..2} a_p a_q G((i - j + p m1 - q m2) tau0),
// with a = (1, -2, 1) and G the generalized covariance of the phase, which second differences
// turn into true covariances (constants and linear terms of G cancel). Per term, h in s:
//   quantization       G = Q^2 at h = 0, else 0 (white angle noise)
//   angle_random_walk  G = -N^2 |h| / 2
//   bias_instability   G = B^2 h^2 ln|h| / (2 pi)    (ideal flicker rate noise)
//   rate_random_walk   G = K^2 |h|^3 / 12
//   gauss_markov       G = -s^2 T^2 (|h|/T + e^(-|h|/T))
// and Cov(A(m1), A(m2)) = [2 sum_l c(l) C12(l)^2 + 4 r1 r2 sum_l c(l) C12(l)] / (4 tau1^2 tau2^2 n1 n2)
// where c(l) counts the index pairs at lag l and r = R tau^2 is a rate ramp's (constant) second
// difference. The lag sums run exactly over short stretches and by adaptive Gauss-Legendre
// quadrature between the kinks of C12 over long ones; the tails of flicker and Gauss-Markov
// terms are summed out to 64 (m1 + m2) lags and 40 tau_c respectively.
// Not modelled: sinusoids (deterministic), nonstationary segments.

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "stochnav/model/noise_model.hpp"

namespace stochnav {

/// M x M covariance of the overlapping AVAR estimates at `m_values` (each >= 1 with
/// 2 m < phase_count) of a record of `phase_count` phase points every tau0_s seconds of
/// `model`, in natural units^4.
Eigen::MatrixXd oadev_estimate_covariance(const NoiseModel& model, double tau0_s,
                                          std::size_t phase_count,
                                          std::span<const std::size_t> m_values);

}  // namespace stochnav
