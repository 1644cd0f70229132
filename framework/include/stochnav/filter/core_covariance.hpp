#pragma once
// Covariance propagation of the core error states (plugin/state_layout.hpp, core_state), and of
// the core followed by states with a diagonal transition (scale factors, first-order
// Gauss-Markov sensor errors), by fixed-size kernels that use the block structure of their
// transition.
//
// The core error dynamics (filter/error_dynamics.hpp) leave the bias rows of F zero (the biases
// are random walks), so the second-order transition over a covariance interval,
// Phi = I + F_bar T + (F_bar T)^2 / 2, has the form
//   Phi = [[A, B], [0, I]],   A 9 x 9 (position, velocity, attitude rows and columns),
//                             B 9 x 6 (their accelerometer and gyro bias columns),
// I the 6 x 6 identity of the bias rows. With P = [[P_nn, P_nb], [P_bn, P_bb]] and
// T = A [P_nn P_nb] + B [P_bn P_bb] (9 x 15; T_n, T_b its first 9 and last 6 columns):
//   P'_nn = T_n A^T + T_b B^T + Q_nn,   P'_bn = T_b^T + Q_bn,   P'_bb = P_bb + Q_bb:
// 9 x 15 x 24 multiply-adds instead of the 2 x 15^3 of the dense Phi P Phi^T. P' is written from
// the lower triangles (of P'_nn, Q) and mirrored: exactly symmetric. No allocation. On x86-64
// the kernel runs 4 doubles per instruction where the CPU has AVX2, with results bit-identical
// to the baseline code (no fused multiply-add, the same order of sums).
//
// The same form holds with N - 9 trailing states whose transition rows are diagonal, D =
// diag(d): scale-factor states (random constants, d = 1, their columns of B the integrated
// C_nb diag(omega) or -C_nb diag(f): filter/error_dynamics.hpp) and first-order augmented states
// (d = exp(-T / tau), their columns of B the coupling +-C_nb_dt M). Then
//   P'_bn = D T_b^T + Q_bn,   P'_bb = D P_bb D + Q_bb
// (d = 1 multiplies exactly: the 15-state results are those of the core kernel above).
// 9 x N x (N + 9) multiply-adds: at N = 21 (the core and both scale-factor blocks, KF-GINS's
// state) 5,700 instead of the 18,500 of the dense product, and no dynamic-size matrix.

#include <Eigen/Core>

#include "stochnav/filter/error_dynamics.hpp"

namespace stochnav {

/// An N x N matrix of a fixed-size error state: the 9 navigation states (position, velocity,
/// attitude: plugin::core_state) first, then N - 9 states with diagonal transition rows.
template <int N>
using NavDiagonalMatrix = Eigen::Matrix<double, N, N>;

/// The sizes with a fixed-size kernel: 15 (the core), 18 and 21 (with one or both scale-factor
/// blocks, or 3 or 6 first-order augmented states), 24 and 27 (both).
template <int N>
inline constexpr bool kHasNavDiagonalKernel = N == 15 || N == 18 || N == 21 || N == 24 || N == 27;

/// True when the last 6 rows of `phi` (15 x 15) are [0 I]: the bias rows of the core transition.
bool has_constant_bias_rows(const Eigen::Ref<const CoreMatrix>& phi);

/// True when rows 9..N-1 of `phi` (N x N) are zero off the diagonal: the form the kernel needs.
template <int N>
bool has_diagonal_trailing_rows(const NavDiagonalMatrix<N>& phi);

/// P <- Phi P Phi^T + Q_d for the 15 core states (each 15 x 15; Phi dimensionless, P and Q_d in
/// the core states' units). Preconditions: has_constant_bias_rows(phi); P and Q_d symmetric.
/// The same result as the dense product to rounding, exactly symmetric.
void propagate_core_covariance(const CoreMatrix& phi, const CoreMatrix& q_d,
                               Eigen::Ref<CoreMatrix> p);

/// P <- Phi P Phi^T + Q_d for an N-state error state of the NavDiagonalMatrix form (each N x N;
/// kHasNavDiagonalKernel<N>). Preconditions: has_diagonal_trailing_rows(phi); P and Q_d
/// symmetric. The same result as the dense product to rounding, exactly symmetric; at N = 15
/// bit-identical to propagate_core_covariance.
template <int N>
void propagate_nav_diagonal_covariance(const NavDiagonalMatrix<N>& phi,
                                       const NavDiagonalMatrix<N>& q_d,
                                       Eigen::Ref<NavDiagonalMatrix<N>> p);

/// F + F^2 / 2 for the integrated core dynamics F = F_bar T (15 x 15, dimensionless; its last 6
/// rows zero, as integrated_core_dynamics gives it): only the first 9 rows of F^2 are formed.
/// Plus the identity, it is the second-order transition Phi of the interval.
CoreMatrix second_order_transition_increment(const CoreMatrix& f);

/// The same for N x N integrated dynamics whose rows 9..N-1 are zero (the core's, widened by
/// the scale-factor columns; kHasNavDiagonalKernel<N>).
template <int N>
NavDiagonalMatrix<N> second_order_transition_increment(const NavDiagonalMatrix<N>& f);

}  // namespace stochnav
