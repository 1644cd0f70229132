// The fixed-size core kernels (filter/core_covariance.hpp) against the dense products they
// replace, computed in long double: on random symmetric positive definite covariances and random
// transitions of the core form [[A, B], [0, I]].

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

}  // namespace
}  // namespace stochnav
