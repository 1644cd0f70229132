#pragma once
// Covariance propagation of the 15 core error states (plugin/state_layout.hpp, core_state) by
// fixed-size kernels that use the block structure of their transition.
//
// The core error dynamics (filter/error_dynamics.hpp) leave the bias rows of F zero (the biases
// are random walks), so the second-order transition over a covariance interval,
// Phi = I + F_bar T + (F_bar T)^2 / 2, has the form
//   Phi = [[A, B], [0, I]],   A 9 x 9 (position, velocity, attitude rows and columns),
//                             B 9 x 6 (their accelerometer and gyro bias columns),
// I the 6 x 6 identity of the bias rows. With P = [[P_nn, P_nb], [P_bn, P_bb]] and
// T = A [P_nn P_nb] + B [P_bn P_bb] (9 x 15; T_n, T_b its first 9 and last 6 columns):
//   P'_nn = T_n A^T + T_b B^T + Q_nn,   P'_nb = T_b + Q_nb,   P'_bb = P_bb + Q_bb:
// 9 x 15 x 24 multiply-adds instead of the 2 x 15^3 of the dense Phi P Phi^T. P' is written from
// the lower triangles (of P'_nn, Q) and mirrored: exactly symmetric. No allocation. On x86-64
// the kernel runs 4 doubles per instruction where the CPU has AVX2, with results bit-identical
// to the baseline code (no fused multiply-add, the same order of sums).

#include <Eigen/Core>

#include "stochnav/filter/error_dynamics.hpp"

namespace stochnav {

/// True when the last 6 rows of `phi` (15 x 15) are [0 I]: the bias rows of the core transition.
bool has_constant_bias_rows(const Eigen::Ref<const CoreMatrix>& phi);

/// P <- Phi P Phi^T + Q_d for the 15 core states (each 15 x 15; Phi dimensionless, P and Q_d in
/// the core states' units). Preconditions: has_constant_bias_rows(phi); P and Q_d symmetric.
/// The same result as the dense product to rounding, exactly symmetric.
void propagate_core_covariance(const CoreMatrix& phi, const CoreMatrix& q_d,
                               Eigen::Ref<CoreMatrix> p);

/// F + F^2 / 2 for the integrated core dynamics F = F_bar T (15 x 15, dimensionless; its last 6
/// rows zero, as integrated_core_dynamics gives it): only the first 9 rows of F^2 are formed.
/// Plus the identity, it is the second-order transition Phi of the interval.
CoreMatrix second_order_transition_increment(const CoreMatrix& f);

}  // namespace stochnav
