// The fixed-size core kernels (filter/core_covariance.hpp) against the dense products they
// replace, computed in long double: on random symmetric positive definite covariances and random
// transitions of the core form [[A, B], [0, I]], and of the wider form [[A, B], [0, D]] (D
// diagonal: scale-factor and first-order augmented states).

#include "stochnav/filter/core_covariance.hpp"

#include <gtest/gtest.h>

#include <random>

#include "stochnav/filter/error_state_filter.hpp"

namespace stochnav {
namespace {

using CoreMatrixL = Eigen::Matrix<long double, 15, 15>;

CoreMatrix random_core(std::mt19937_64& engine, double scale) {
  std::normal_distribution<double> normal(0.0, scale);
  CoreMatrix m;
  for (int j = 0; j < 15; ++j) {
    for (int i = 0; i < 15; ++i) m(i, j) = normal(engine);
  }
  return m;
}

CoreMatrix random_covariance(std::mt19937_64& engine) {
  const CoreMatrix a = random_core(engine, 1.0);
  Eigen::Matrix<double, 15, 1> scale;
  std::uniform_real_distribution<double> exponent(-6.0, 1.0);
  for (int i = 0; i < 15; ++i) scale(i) = std::pow(10.0, exponent(engine));
  const CoreMatrix spd = a * a.transpose() / 15.0 + 0.1 * CoreMatrix::Identity();
  const CoreMatrix p = scale.asDiagonal() * spd * scale.asDiagonal();
  return 0.5 * (p + p.transpose());  // exactly symmetric, as the kernel's precondition asks
}

// F with zero bias rows, as integrated_core_dynamics gives it.
CoreMatrix random_dynamics(std::mt19937_64& engine) {
  CoreMatrix f = random_core(engine, 0.05);
  f.bottomRows<6>().setZero();
  return f;
}

double max_relative_error(const CoreMatrix& value, const CoreMatrixL& reference) {
  const long double norm = reference.cwiseAbs().maxCoeff();
  return static_cast<double>((value.cast<long double>() - reference).cwiseAbs().maxCoeff() / norm);
}

TEST(CoreCovariance, MatchesTheDenseProductAndIsExactlySymmetric) {
  std::mt19937_64 engine(15);
  for (int trial = 0; trial < 200; ++trial) {
    const CoreMatrix f = random_dynamics(engine);
    CoreMatrix phi = f + 0.5 * f * f;
    phi.diagonal().array() += 1.0;
    ASSERT_TRUE(has_constant_bias_rows(phi));
    const CoreMatrix p0 = random_covariance(engine);
    const CoreMatrix q = random_covariance(engine) * 1e-3;
    const CoreMatrixL phi_l = phi.cast<long double>();
    const CoreMatrixL reference =
        phi_l * p0.cast<long double>() * phi_l.transpose() + q.cast<long double>();
    CoreMatrix p = p0;
    propagate_core_covariance(phi, q, p);
    EXPECT_LT(max_relative_error(p, reference), 1e-14) << "trial " << trial;
    EXPECT_TRUE(p == p.transpose()) << "trial " << trial;
  }
}

TEST(CoreCovariance, SecondOrderIncrementIsFPlusHalfFSquared) {
  std::mt19937_64 engine(9);
  for (int trial = 0; trial < 50; ++trial) {
    const CoreMatrix f = random_dynamics(engine);
    const CoreMatrixL f_l = f.cast<long double>();
    const CoreMatrixL reference = f_l + 0.5L * f_l * f_l;
    EXPECT_LT(max_relative_error(second_order_transition_increment(f), reference), 1e-15);
  }
}

TEST(CoreCovariance, RecognisesOnlyConstantBiasRows) {
  CoreMatrix phi = CoreMatrix::Identity();
  phi.topRows<9>().setConstant(0.3);
  EXPECT_TRUE(has_constant_bias_rows(phi));
  CoreMatrix coupled = phi;
  coupled(12, 4) = 1e-300;  // any nonzero below the head breaks the form
  EXPECT_FALSE(has_constant_bias_rows(coupled));
  CoreMatrix scaled = phi;
  scaled(14, 14) = 1.0 + 1e-15;
  EXPECT_FALSE(has_constant_bias_rows(scaled));
}

TEST(CoreCovariance, ZeroIntervalLeavesPPlusQ) {
  // dt == 0: F = 0, Phi = I, so P' = P + Q exactly.
  std::mt19937_64 engine(3);
  const CoreMatrix p0 = random_covariance(engine);
  const CoreMatrix q = random_covariance(engine);
  CoreMatrix phi = second_order_transition_increment(CoreMatrix::Zero());
  phi.diagonal().array() += 1.0;
  CoreMatrix p = p0;
  propagate_core_covariance(phi, q, p);
  const CoreMatrix expected = p0 + q;
  for (int j = 0; j < 15; ++j) {
    for (int i = j; i < 15; ++i) EXPECT_DOUBLE_EQ(p(i, j), expected(i, j));
  }
}

TEST(CoreCovariance, FilterPropagateCoreEqualsPropagate) {
  std::mt19937_64 engine(21);
  const CoreMatrix p0 = random_covariance(engine);
  ErrorStateFilter checked(p0);
  ErrorStateFilter direct(p0);
  for (int step = 0; step < 20; ++step) {
    const CoreMatrix f = random_dynamics(engine);
    CoreMatrix phi = second_order_transition_increment(f);
    phi.diagonal().array() += 1.0;
    const CoreMatrix q = random_covariance(engine) * 1e-4;
    checked.propagate(phi, q);
    direct.propagate_core(phi, q);
  }
  EXPECT_TRUE(checked.covariance() == direct.covariance());
  EXPECT_TRUE(direct.health().ok());
}

template <int N>
using SquareL = Eigen::Matrix<long double, N, N>;

template <int N>
NavDiagonalMatrix<N> random_square(std::mt19937_64& engine, double scale) {
  std::normal_distribution<double> normal(0.0, scale);
  NavDiagonalMatrix<N> m;
  for (int j = 0; j < N; ++j) {
    for (int i = 0; i < N; ++i) m(i, j) = normal(engine);
  }
  return m;
}

template <int N>
NavDiagonalMatrix<N> random_square_covariance(std::mt19937_64& engine) {
  const NavDiagonalMatrix<N> a = random_square<N>(engine, 1.0);
  Eigen::Matrix<double, N, 1> scale;
  std::uniform_real_distribution<double> exponent(-6.0, 1.0);
  for (int i = 0; i < N; ++i) scale(i) = std::pow(10.0, exponent(engine));
  const NavDiagonalMatrix<N> spd =
      a * a.transpose() / double{N} + 0.1 * NavDiagonalMatrix<N>::Identity();
  const NavDiagonalMatrix<N> p = scale.asDiagonal() * spd * scale.asDiagonal();
  return 0.5 * (p + p.transpose());
}

// F with zero rows after the 9 navigation states (the scale-factor columns of the navigation
// rows nonzero, as the navigator builds F with scale-factor states).
template <int N>
NavDiagonalMatrix<N> random_wide_dynamics(std::mt19937_64& engine) {
  NavDiagonalMatrix<N> f = random_square<N>(engine, 0.05);
  f.template bottomRows<N - 9>().setZero();
  return f;
}

// Phi = I + F + F^2 / 2 with the last `first_order` states given a decay (exp(-T / tau)) on
// the diagonal: the form of scale-factor states followed by first-order augmented states.
template <int N>
NavDiagonalMatrix<N> random_wide_transition(std::mt19937_64& engine, int first_order) {
  const NavDiagonalMatrix<N> f = random_wide_dynamics<N>(engine);
  NavDiagonalMatrix<N> phi = second_order_transition_increment<N>(f);
  phi.diagonal().array() += 1.0;
  std::uniform_real_distribution<double> decay(0.5, 1.0);
  for (int i = N - first_order; i < N; ++i) phi(i, i) = decay(engine);
  return phi;
}

template <int N>
void expect_wide_kernel_matches_dense_product(int first_order, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  for (int trial = 0; trial < 100; ++trial) {
    const NavDiagonalMatrix<N> phi = random_wide_transition<N>(engine, first_order);
    ASSERT_TRUE(has_diagonal_trailing_rows<N>(phi));
    const NavDiagonalMatrix<N> p0 = random_square_covariance<N>(engine);
    const NavDiagonalMatrix<N> q = random_square_covariance<N>(engine) * 1e-3;
    const SquareL<N> phi_l = phi.template cast<long double>();
    const SquareL<N> reference = phi_l * p0.template cast<long double>() * phi_l.transpose() +
                                 q.template cast<long double>();
    NavDiagonalMatrix<N> p = p0;
    propagate_nav_diagonal_covariance<N>(phi, q, p);
    const long double norm = reference.cwiseAbs().maxCoeff();
    const double error = static_cast<double>(
        (p.template cast<long double>() - reference).cwiseAbs().maxCoeff() / norm);
    EXPECT_LT(error, 1e-14) << "N = " << N << ", trial " << trial;
    EXPECT_TRUE(p == p.transpose()) << "N = " << N << ", trial " << trial;
  }
}

// The kernel's arithmetic written out one entry at a time, each sum in k order from zero:
// T = [A B] P (9 x N), P'_nn = T [A B]^T + Q_nn, P'_bn = D T_b^T + Q_bn, P'_bb = D P_bb D + Q_bb,
// lower triangles mirrored. However the kernel groups its columns into registers, it must add
// the same products in the same order: the same bits.
template <int N>
NavDiagonalMatrix<N> summed_in_order(const NavDiagonalMatrix<N>& phi,
                                     const NavDiagonalMatrix<N>& q,
                                     const NavDiagonalMatrix<N>& p) {
  Eigen::Matrix<double, 9, N> t;
  for (int j = 0; j < N; ++j) {
    for (int i = 0; i < 9; ++i) {
      double sum = 0.0;
      for (int k = 0; k < N; ++k) sum += phi(i, k) * p(k, j);
      t(i, j) = sum;
    }
  }
  NavDiagonalMatrix<N> out;
  for (int j = 0; j < N; ++j) {
    for (int i = j; i < N; ++i) {
      double value = 0.0;
      if (i < 9) {
        for (int k = 0; k < N; ++k) value += t(i, k) * phi(j, k);
        value += q(i, j);
      } else if (j < 9) {
        value = phi(i, i) * t(j, i) + q(i, j);
      } else {
        value = phi(i, i) * p(i, j) * phi(j, j) + q(i, j);
      }
      out(i, j) = out(j, i) = value;
    }
  }
  return out;
}

template <int N>
void expect_kernel_sums_in_order(int first_order, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  for (int trial = 0; trial < 100; ++trial) {
    const NavDiagonalMatrix<N> phi = random_wide_transition<N>(engine, first_order);
    const NavDiagonalMatrix<N> p0 = random_square_covariance<N>(engine);
    const NavDiagonalMatrix<N> q = random_square_covariance<N>(engine) * 1e-3;
    NavDiagonalMatrix<N> p = p0;
    propagate_nav_diagonal_covariance<N>(phi, q, p);
    EXPECT_TRUE(p == summed_in_order<N>(phi, q, p0)) << "N = " << N << ", trial " << trial;
  }
}

TEST(NavDiagonalCovariance, EveryEntryIsSummedInOrderBitForBit) {
  expect_kernel_sums_in_order<15>(0, 115);
  expect_kernel_sums_in_order<21>(0, 121);
  expect_kernel_sums_in_order<21>(6, 126);
  expect_kernel_sums_in_order<27>(6, 127);
}

TEST(NavDiagonalCovariance, MatchesTheDenseProductWithScaleFactorStates) {
  expect_wide_kernel_matches_dense_product<18>(0, 18);
  expect_wide_kernel_matches_dense_product<21>(0, 21);
}

TEST(NavDiagonalCovariance, MatchesTheDenseProductWithFirstOrderStates) {
  expect_wide_kernel_matches_dense_product<21>(6, 6);   // the core and 6 Gauss-Markov states
  expect_wide_kernel_matches_dense_product<27>(6, 27);  // scale factors, then Gauss-Markov
  expect_wide_kernel_matches_dense_product<24>(3, 24);
}

TEST(NavDiagonalCovariance, SecondOrderIncrementIsFPlusHalfFSquared) {
  std::mt19937_64 engine(12);
  for (int trial = 0; trial < 50; ++trial) {
    const NavDiagonalMatrix<21> f = random_wide_dynamics<21>(engine);
    const SquareL<21> f_l = f.cast<long double>();
    const SquareL<21> reference = f_l + 0.5L * f_l * f_l;
    const SquareL<21> increment = second_order_transition_increment<21>(f).cast<long double>();
    EXPECT_LT(static_cast<double>((increment - reference).cwiseAbs().maxCoeff() /
                                  reference.cwiseAbs().maxCoeff()),
              1e-15);
  }
}

TEST(NavDiagonalCovariance, RecognisesOnlyDiagonalTrailingRows) {
  NavDiagonalMatrix<21> phi = NavDiagonalMatrix<21>::Identity();
  phi.topRows<9>().setConstant(0.3);
  phi(20, 20) = 0.9;  // a decay is allowed
  EXPECT_TRUE(has_diagonal_trailing_rows<21>(phi));
  NavDiagonalMatrix<21> coupled = phi;
  coupled(17, 19) = 1e-300;  // trailing states coupled to each other
  EXPECT_FALSE(has_diagonal_trailing_rows<21>(coupled));
  NavDiagonalMatrix<21> driven = phi;
  driven(15, 3) = 1e-300;  // a trailing state driven by a navigation state
  EXPECT_FALSE(has_diagonal_trailing_rows<21>(driven));
}

TEST(NavDiagonalCovariance, FifteenStatesAreTheCoreKernelBitForBit) {
  std::mt19937_64 engine(33);
  for (int trial = 0; trial < 20; ++trial) {
    const CoreMatrix f = random_dynamics(engine);
    CoreMatrix phi = second_order_transition_increment(f);
    phi.diagonal().array() += 1.0;
    const CoreMatrix p0 = random_covariance(engine);
    const CoreMatrix q = random_covariance(engine) * 1e-4;
    CoreMatrix core = p0;
    propagate_core_covariance(phi, q, core);
    CoreMatrix wide = p0;
    propagate_nav_diagonal_covariance<15>(phi, q, wide);
    EXPECT_TRUE(core == wide) << "trial " << trial;
  }
}

TEST(NavDiagonalCovariance, FilterPropagateNavDiagonalEqualsDensePropagateToRounding) {
  std::mt19937_64 engine(42);
  const NavDiagonalMatrix<21> p0 = random_square_covariance<21>(engine);
  ErrorStateFilter dense{Eigen::MatrixXd(p0)};
  ErrorStateFilter fixed{Eigen::MatrixXd(p0)};
  for (int step = 0; step < 20; ++step) {
    const NavDiagonalMatrix<21> phi = random_wide_transition<21>(engine, 6);
    const NavDiagonalMatrix<21> q = random_square_covariance<21>(engine) * 1e-4;
    dense.propagate(phi, q);
    fixed.propagate_nav_diagonal<21>(phi, q);
  }
  const Eigen::MatrixXd difference = fixed.covariance() - dense.covariance();
  EXPECT_LT(difference.cwiseAbs().maxCoeff() / dense.covariance().cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_TRUE(fixed.health().ok());
}

}  // namespace
}  // namespace stochnav
