#include "stochnav/filter/error_state_filter.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "stochnav/filter/core_covariance.hpp"

namespace stochnav {

// The innovation factor starts factorised (of a 1 x 1 identity): an LLT never computed holds an
// indeterminate status, which a copy of the filter (MwdNavigator::split) would read.
ErrorStateFilter::ErrorStateFilter(Eigen::MatrixXd initial_covariance)
    : covariance_(std::move(initial_covariance)),
      initial_covariance_(covariance_),
      innovation_factor_(Eigen::MatrixXd::Identity(1, 1)) {}

void ErrorStateFilter::propagate(const Eigen::Ref<const Eigen::MatrixXd>& phi,
                                 const Eigen::Ref<const Eigen::MatrixXd>& q_d) {
  if (size() == kCoreSize) {
    // The common case (no augmented states): fixed-size kernels, unrolled and vectorised.
    const CoreMatrix phi_fixed = phi;
    const CoreMatrix q_fixed = q_d;
    Eigen::Map<CoreMatrix> p(covariance_.data());
    if (has_constant_bias_rows(phi_fixed)) {
      propagate_core_covariance(phi_fixed, q_fixed, p);  // exactly symmetric
      keep_healthy(Symmetrize::kNone);
      return;
    }
    const CoreMatrix phi_p = phi_fixed.lazyProduct(p);
    p.noalias() = phi_p.lazyProduct(phi_fixed.transpose());
  } else {
    // Small matrices: coefficient-wise products beat the blocked GEMM path and its packing.
    scratch_.noalias() = phi.lazyProduct(covariance_);
    covariance_.noalias() = scratch_.lazyProduct(phi.transpose());
  }
  covariance_ += q_d;
  keep_healthy(Symmetrize::kAverage);
}

void ErrorStateFilter::propagate_core(const CoreMatrix& phi, const CoreMatrix& q_d) {
  assert(size() == kCoreSize && has_constant_bias_rows(phi));
  propagate_core_covariance(phi, q_d, Eigen::Map<CoreMatrix>(covariance_.data()));
  keep_healthy(Symmetrize::kNone);  // the kernel's P is exactly symmetric
}

template <int N>
void ErrorStateFilter::propagate_nav_diagonal(const Eigen::Matrix<double, N, N>& phi,
                                              const Eigen::Matrix<double, N, N>& q_d) {
  assert(size() == N && has_diagonal_trailing_rows<N>(phi));
  propagate_nav_diagonal_covariance<N>(phi, q_d,
                                       Eigen::Map<Eigen::Matrix<double, N, N>>(covariance_.data()));
  keep_healthy(Symmetrize::kNone);  // the kernel's P is exactly symmetric
}

template void ErrorStateFilter::propagate_nav_diagonal<15>(const Eigen::Matrix<double, 15, 15>&,
                                                           const Eigen::Matrix<double, 15, 15>&);
template void ErrorStateFilter::propagate_nav_diagonal<18>(const Eigen::Matrix<double, 18, 18>&,
                                                           const Eigen::Matrix<double, 18, 18>&);
template void ErrorStateFilter::propagate_nav_diagonal<21>(const Eigen::Matrix<double, 21, 21>&,
                                                           const Eigen::Matrix<double, 21, 21>&);
template void ErrorStateFilter::propagate_nav_diagonal<24>(const Eigen::Matrix<double, 24, 24>&,
                                                           const Eigen::Matrix<double, 24, 24>&);
template void ErrorStateFilter::propagate_nav_diagonal<27>(const Eigen::Matrix<double, 27, 27>&,
                                                           const Eigen::Matrix<double, 27, 27>&);

void ErrorStateFilter::propagate(const BlockTransition& transition) {
  const Eigen::Index n = size();
  const Eigen::Index d = transition.head_transition.rows();
  const Eigen::Index n_a = n - d;
  if (n_a == 0) {
    propagate(transition.head_transition, transition.head_noise);
    return;
  }
  // P = [[P_hh, P_ht], [P_th, P_tt]], Phi = [[F_h, G], [0, F_t]]:
  //   P'_hh = F_h Z + G Y + Q_h,  Z = P_hh F_h^T + P_ht G^T
  //   P'_th = F_t Y,              Y = P_th F_h^T + P_tt G^T
  //   P'_tt = F_t X + Q_t,        X = P_tt F_t^T
  // G is nonzero only in each segment's coupling rows (G = L M, M sparse) and F_t, Q_t are
  // block-diagonal, so every product touches nonzero blocks only. P'_tt is computed on and
  // below the diagonal (by blocks) and mirrored, P'_ht is P'_th^T and P'_hh is averaged with
  // its transpose: P' is exactly symmetric.
  const auto& phi_h = transition.head_transition;
  const auto p_hh = covariance_.topLeftCorner(d, d);
  const auto p_ht = covariance_.topRightCorner(d, n_a);
  const auto p_th = covariance_.bottomLeftCorner(n_a, d);
  const auto p_tt = covariance_.bottomRightCorner(n_a, n_a);
  tail_head_.resize(n_a, d);
  head_head_.resize(d, d);
  tail_tail_.resize(n_a, n_a);
  scratch_.resize(n, n);

  tail_head_.noalias() = p_th * phi_h.transpose();
  head_head_.noalias() = p_hh * phi_h.transpose();
  for (const TailSegment& segment : transition.tail) {
    const int k = segment.transition.size();
    if (k == 0) continue;
    assert(segment.offset >= d && segment.offset + k <= n && segment.noise.size() == k);
    const int local = segment.offset - static_cast<int>(d);
    const Eigen::Index c = segment.coupling.rows();
    if (c > 0) {
      assert(segment.coupling_map.cols() == k &&
             segment.coupling_map.rows() == segment.coupling.cols());
      const Eigen::Index r = segment.coupling.cols();
      tail_map_.setZero(n_a, r);
      segment.coupling_map.add_product_transpose_from_right(p_tt.middleCols(local, k), tail_map_);
      tail_head_.middleCols(segment.coupling_row, c).noalias() +=
          tail_map_ * segment.coupling.transpose();
      head_map_.setZero(d, r);
      segment.coupling_map.add_product_transpose_from_right(p_ht.middleCols(local, k), head_map_);
      head_head_.middleCols(segment.coupling_row, c).noalias() +=
          head_map_ * segment.coupling.transpose();
    }
    segment.transition.multiply_transpose_from_right_lower(p_tt.middleCols(local, k),
                                                           tail_tail_.middleCols(local, k), local);
  }

  auto next_hh = scratch_.topLeftCorner(d, d);
  next_hh.noalias() = phi_h * head_head_;
  for (const TailSegment& segment : transition.tail) {
    const int k = segment.transition.size();
    if (k == 0) continue;
    const int local = segment.offset - static_cast<int>(d);
    const Eigen::Index c = segment.coupling.rows();
    if (c > 0) {
      map_head_.setZero(segment.coupling.cols(), d);
      segment.coupling_map.add_product(tail_head_.middleRows(local, k), map_head_);
      next_hh.middleRows(segment.coupling_row, c).noalias() += segment.coupling * map_head_;
    }
    segment.transition.multiply(tail_head_.middleRows(local, k),
                                scratch_.block(segment.offset, 0, k, d));
    auto next_tt = scratch_.block(segment.offset, d, k, n_a);
    segment.transition.multiply_lower(tail_tail_.middleRows(local, k), next_tt, local);
    segment.noise.add_to(next_tt.middleCols(local, k));
  }
  for (Eigen::Index j = 0; j < d; ++j) {
    for (Eigen::Index i = j; i < d; ++i) {
      const double value = 0.5 * (next_hh(i, j) + next_hh(j, i)) + transition.head_noise(i, j);
      next_hh(i, j) = next_hh(j, i) = value;
    }
  }
  scratch_.topRightCorner(d, n_a) = scratch_.bottomLeftCorner(n_a, d).transpose();
  auto next_tt = scratch_.bottomRightCorner(n_a, n_a);
  for (Eigen::Index j = 0; j < n_a; ++j) {
    for (Eigen::Index i = j + 1; i < n_a; ++i) next_tt(j, i) = next_tt(i, j);
  }
  covariance_.swap(scratch_);
  keep_healthy(Symmetrize::kNone);
}

UpdateOutcome ErrorStateFilter::update(const Eigen::Ref<const Eigen::VectorXd>& z,
                                       const Eigen::Ref<const Eigen::MatrixXd>& h,
                                       const Eigen::Ref<const Eigen::MatrixXd>& r,
                                       double gate_threshold,
                                       Eigen::Ref<Eigen::VectorXd> correction, JosephForm form) {
  UpdateOutcome outcome;
  const Eigen::Index n = size();
  const Eigen::Index m = z.size();
  const Eigen::Index k = h.cols();  // H's columns beyond k are zero
  assert(k <= n && h.rows() == m);
  p_ht_.resize(n, m);
  p_ht_.noalias() = covariance_.leftCols(k) * h.transpose();  // U = P H^T
  innovation_covariance_.resize(m, m);
  innovation_covariance_.noalias() = h * p_ht_.topRows(k);
  innovation_covariance_ += r;
  for (Eigen::Index j = 0; j < m; ++j) {
    for (Eigen::Index i = j + 1; i < m; ++i) {
      const double mean = 0.5 * (innovation_covariance_(i, j) + innovation_covariance_(j, i));
      innovation_covariance_(i, j) = innovation_covariance_(j, i) = mean;
    }
  }
  gain_.setZero(n, m);
  innovation_factor_.compute(innovation_covariance_);
  if (innovation_factor_.info() != Eigen::Success || !z.allFinite()) {
    ++health_.singular_innovations;
    outcome.singular = true;
    outcome.nis = std::numeric_limits<double>::quiet_NaN();
    outcome.log_det_s = outcome.nis;
    return outcome;
  }
  // NIS = |L^-1 z|^2 with S = L L^T.
  whitened_innovation_ = z;
  innovation_factor_.matrixL().solveInPlace(whitened_innovation_);
  outcome.nis = whitened_innovation_.squaredNorm();
  outcome.log_det_s = 2.0 * innovation_factor_.matrixLLT().diagonal().array().log().sum();
  if (!(outcome.nis <= gate_threshold)) return outcome;

  // K = U S^-1 = U L^-T L^-1.
  gain_ = p_ht_;
  innovation_factor_.matrixU().solveInPlace<Eigen::OnTheRight>(gain_);
  innovation_factor_.matrixL().solveInPlace<Eigen::OnTheRight>(gain_);
  for (const Eigen::Index state : considered_) gain_.row(state).setZero();
  correction.noalias() = gain_ * z;
  if (form == JosephForm::kExpanded) {
    // P - K U^T - U K^T + K S K^T = P + E K^T + K E^T with E = K S / 2 - U.
    joseph_term_.resize(n, m);
    joseph_term_.noalias() = gain_ * innovation_covariance_;
    joseph_term_ *= 0.5;
    joseph_term_ -= p_ht_;
    covariance_.triangularView<Eigen::Lower>() += joseph_term_ * gain_.transpose();
    covariance_.triangularView<Eigen::Lower>() += gain_ * joseph_term_.transpose();
    keep_healthy(Symmetrize::kMirrorLower);
  } else {
    h_full_.setZero(m, n);
    h_full_.leftCols(k) = h;
    Eigen::MatrixXd i_kh = -gain_ * h_full_;
    i_kh.diagonal().array() += 1.0;
    scratch_.noalias() = i_kh * covariance_;
    covariance_.noalias() = scratch_ * i_kh.transpose();
    covariance_.noalias() += gain_ * r * gain_.transpose();
    keep_healthy(Symmetrize::kAverage);
  }
  outcome.accepted = true;
  return outcome;
}

void ErrorStateFilter::replace_covariance(const Eigen::Ref<const Eigen::MatrixXd>& covariance) {
  if (covariance.rows() != size() || covariance.cols() != size()) {
    throw std::invalid_argument("ErrorStateFilter::replace_covariance: " +
                                std::to_string(covariance.rows()) + " x " +
                                std::to_string(covariance.cols()) + " for a filter of " +
                                std::to_string(size()) + " states");
  }
  covariance_ = covariance;
}

void ErrorStateFilter::consider(Eigen::Index index) {
  assert(index >= 0 && index < size());
  if (std::find(considered_.begin(), considered_.end(), index) == considered_.end()) {
    considered_.push_back(index);
  }
}

void ErrorStateFilter::keep_healthy(Symmetrize how) {
  if (how != Symmetrize::kNone) {
    for (Eigen::Index j = 0; j < covariance_.cols(); ++j) {
      for (Eigen::Index i = j + 1; i < covariance_.rows(); ++i) {
        const double value = how == Symmetrize::kAverage
                                 ? 0.5 * (covariance_(i, j) + covariance_(j, i))
                                 : covariance_(i, j);
        covariance_(i, j) = covariance_(j, i) = value;
      }
    }
  }
  // 0 x is 0 for every finite x and NaN otherwise: one vectorised sum instead of allFinite()'s
  // coefficient-wise test (which cost as much as a whole structured propagation).
  if (!((covariance_.array() * 0.0).sum() == 0.0)) {
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
