#include "stochnav/filter/core_covariance.hpp"

namespace stochnav {
namespace {

constexpr int kNav = 9;   // position, velocity, attitude
constexpr int kBias = 6;  // accelerometer and gyro biases

}  // namespace

bool has_constant_bias_rows(const Eigen::Ref<const CoreMatrix>& phi) {
  return phi.bottomLeftCorner<kBias, kNav>().cwiseAbs().sum() == 0.0 &&
         phi.bottomRightCorner<kBias, kBias>() == Eigen::Matrix<double, kBias, kBias>::Identity();
}

void propagate_core_covariance(const Eigen::Ref<const CoreMatrix>& phi,
                               const Eigen::Ref<const CoreMatrix>& q_d, Eigen::Ref<CoreMatrix> p) {
  const auto a = phi.topLeftCorner<kNav, kNav>();
  const auto b = phi.topRightCorner<kNav, kBias>();
  // lazyProduct: at these sizes the unrolled coefficient-wise product beats the blocked GEMM
  // path (its packing costs more than the arithmetic).
  Eigen::Matrix<double, kNav, 15> t;
  t.noalias() = a.lazyProduct(p.topRows<kNav>());
  t.noalias() += b.lazyProduct(p.bottomRows<kBias>());
  Eigen::Matrix<double, kNav, kNav> next_nn;
  next_nn.noalias() = t.leftCols<kNav>().lazyProduct(a.transpose());
  next_nn.noalias() += t.rightCols<kBias>().lazyProduct(b.transpose());

  for (int j = 0; j < kNav; ++j) {
    for (int i = j; i < kNav; ++i) p(i, j) = p(j, i) = next_nn(i, j) + q_d(i, j);
  }
  for (int j = 0; j < kNav; ++j) {
    for (int i = kNav; i < 15; ++i) p(i, j) = p(j, i) = t(j, i) + q_d(i, j);
  }
  for (int j = kNav; j < 15; ++j) {
    for (int i = j; i < 15; ++i) p(i, j) = p(j, i) = p(i, j) + q_d(i, j);
  }
}

CoreMatrix second_order_transition_increment(const CoreMatrix& f) {
  CoreMatrix increment = f;
  Eigen::Matrix<double, kNav, 15> f_squared;
  f_squared.noalias() = f.topLeftCorner<kNav, kNav>().lazyProduct(f.topRows<kNav>());
  increment.topRows<kNav>() += 0.5 * f_squared;
  return increment;
}

}  // namespace stochnav
