#pragma once
// The attitude error beyond first order while the heading is uncertain by degrees.
//
// With C_nb_est = (I - [phi x]) C_nb_true (filter/error_dynamics.hpp) and E = C_nb_est C_nb_true^T,
// the computed frame's rotation about the navigation frame is exactly
//   dE/dt = [((E - I) omega_in_n) x] E,
// so the tilt the accelerometers see (the rotation of the computed frame's vertical) changes at
//   d phi/dt = -omega_in_n x phi - 1/2 [phi x]^2 omega_in_n + O(phi^3).
// The filter keeps the first term. The second is a product of errors: with the heading 6 deg off
// (0.1 rad) at 60 N it is a north tilt rate of 1/2 psi^2 Omega cos(lat) = 0.04 deg/h, as large as
// the along-hole gyro bias's share of the tilt (psi times the bias) through which the filter
// separates the bias from the heading in an east-west hole. Left out, the filter "learns" the
// heading from a tilt drift it does not model (docs/drilling-envelope.md, section 4).
//
// For a zero-mean Gaussian phi with covariance P (what the error-state filter holds after every
// feedback), each component m_i = phi^T A_i phi of m = -1/2 [phi x]^2 omega is a quadratic form:
// its mean is E[m] = -1/2 (P - tr(P) I) omega (with psi alone, a north tilt rate of
// 1/2 sigma_psi^2 Omega cos(lat): the tilt every heading error drives, whatever its sign), and by
// Isserlis' theorem Cov(m_i, m_l) = 2 tr(A_i P A_l P). The mean is the second-order filter's
// correction of the predicted error (its E[f(x)] = f(x_hat) + 1/2 tr(f'' P)): the navigator
// feeds it back every covariance interval. Without it, the filter read that average tilt as
// information on the heading and the gyro biases, linear in the error it does not know. The term depends on the heading
// error itself, which changes slowly; the filter adds it as a white process noise of the same
// variance over a correlation time tau (power spectral density 2 Cov(m) tau), the first-order
// Gauss-Markov equivalent. It vanishes as P shrinks (as P^2): it costs nothing once the heading
// is known to a fraction of a degree.

#include <Eigen/Core>

namespace stochnav {

/// E[m] (rad/s) of the second-order attitude-error rate m = -1/2 [phi x]^2 omega_in_n for
/// phi ~ N(0, p_attitude) (rad^2, ENU), omega_in_n (rad/s, ENU).
Eigen::Vector3d second_order_attitude_rate_mean(const Eigen::Matrix3d& p_attitude,
                                                const Eigen::Vector3d& omega_in_n);

/// Cov(m) (rad^2/s^2) of the second-order attitude-error rate m = -1/2 [phi x]^2 omega_in_n for
/// phi ~ N(0, p_attitude) (rad^2, ENU), omega_in_n (rad/s, ENU) the navigation frame's rate.
Eigen::Matrix3d second_order_attitude_rate_covariance(const Eigen::Matrix3d& p_attitude,
                                                      const Eigen::Vector3d& omega_in_n);

/// The process noise (rad^2) this term adds to phi over an interval of interval_s seconds when
/// it is treated as Gauss-Markov noise with correlation time correlation_s (0: none).
Eigen::Matrix3d second_order_attitude_noise(const Eigen::Matrix3d& p_attitude,
                                            const Eigen::Vector3d& omega_in_n, double interval_s,
                                            double correlation_s);

}  // namespace stochnav
