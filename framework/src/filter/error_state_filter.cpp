#include "stochnav/filter/error_state_filter.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <utility>

namespace stochnav {

ErrorStateFilter::ErrorStateFilter(Eigen::MatrixXd initial_covariance)
    : covariance_(std::move(initial_covariance)), initial_covariance_(covariance_) {}

void ErrorStateFilter::propagate(const Eigen::MatrixXd& phi, const Eigen::MatrixXd& q_d) {
  if (size() == kCoreSize) {
    // The common case (no augmented states): fixed-size products, unrolled and vectorised.
    using Fixed = Eigen::Matrix<double, kCoreSize, kCoreSize>;
    const Eigen::Map<const Fixed> phi_fixed(phi.data());
    Eigen::Map<Fixed> p(covariance_.data());
    const Fixed phi_p = phi_fixed * p;
    p.noalias() = phi_p * phi_fixed.transpose();
  } else {
    // Small matrices: coefficient-wise products beat the blocked GEMM path and its packing.
    scratch_.noalias() = phi.lazyProduct(covariance_);
    covariance_.noalias() = scratch_.lazyProduct(phi.transpose());
  }
  covariance_ += q_d;
  keep_healthy();
}

UpdateOutcome ErrorStateFilter::update(const Eigen::Ref<const Eigen::VectorXd>& z,
                                       const Eigen::Ref<const Eigen::MatrixXd>& h,
                                       const Eigen::Ref<const Eigen::MatrixXd>& r,
                                       double gate_threshold,
                                       Eigen::Ref<Eigen::VectorXd> correction) {
  UpdateOutcome outcome;
  const Eigen::MatrixXd p_ht = covariance_ * h.transpose();
  innovation_covariance_.noalias() = h * p_ht;
  innovation_covariance_ += r;
  innovation_covariance_ = 0.5 * (innovation_covariance_ + innovation_covariance_.transpose()).eval();
  gain_.setZero(size(), z.size());
  const Eigen::LLT<Eigen::MatrixXd> factor(innovation_covariance_);
  if (factor.info() != Eigen::Success || !z.allFinite()) {
    ++health_.singular_innovations;
    outcome.singular = true;
    outcome.nis = std::numeric_limits<double>::quiet_NaN();
    return outcome;
  }
  outcome.nis = z.dot(factor.solve(z));
  if (!(outcome.nis <= gate_threshold)) return outcome;

  gain_ = factor.solve(p_ht.transpose()).transpose();  // K = P H^T S^-1
  correction.noalias() = gain_ * z;
  // Joseph form: (I - K H) P (I - K H)^T + K R K^T.
  Eigen::MatrixXd i_kh = -gain_ * h;
  i_kh.diagonal().array() += 1.0;
  scratch_.noalias() = i_kh * covariance_;
  covariance_.noalias() = scratch_ * i_kh.transpose();
  covariance_.noalias() += gain_ * r * gain_.transpose();
  keep_healthy();
  outcome.accepted = true;
  return outcome;
}

void ErrorStateFilter::keep_healthy() {
  for (Eigen::Index j = 0; j < covariance_.cols(); ++j) {
    for (Eigen::Index i = j + 1; i < covariance_.rows(); ++i) {
      const double mean = 0.5 * (covariance_(i, j) + covariance_(j, i));
      covariance_(i, j) = covariance_(j, i) = mean;
    }
  }
  if (!covariance_.allFinite()) {
    ++health_.non_finite;
    covariance_ = initial_covariance_;
    return;
  }
  for (Eigen::Index i = 0; i < covariance_.rows(); ++i) {
    if (!(covariance_(i, i) > 0.0)) {
      ++health_.repaired_diagonals;
      covariance_.row(i).setZero();
      covariance_.col(i).setZero();
      covariance_(i, i) = initial_covariance_(i, i);
    }
  }
}

}  // namespace stochnav
