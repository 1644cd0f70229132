#pragma once
// The covariance bookkeeping of an error-state Kalman filter with closed-loop feedback: the
// error estimate is handed to the navigator (and so reset to zero) after every update, so only
// the covariance P is propagated. All covariance surgery lives here; the navigator owns the
// meaning of the states (plugin/state_layout.hpp).
//
// Numerical care: Joseph-form updates, P kept symmetric after every operation, innovation
// covariances factorised by Cholesky. Trouble (a non-positive-definite innovation covariance,
// a non-positive diagonal of P, a non-finite value) never throws: it is counted in
// FilterHealth, the update concerned is skipped, and P is repaired when it can be.
//
// Structure (the cost of augmented states): the error state is x = [head (D dense states: the
// core and any other states the aids and the INS errors couple densely), tail (n_a augmented
// states of the noise models)]. Its transition is
//   Phi = [[Phi_h, G], [0, Phi_t]],   Q_d = blockdiag(Q_h, Q_t),
// with Phi_t and Q_t block-diagonal (filter/block_diagonal_matrix.hpp) and G nonzero in a few head
// rows only (the augmented sensor errors drive the attitude or velocity rows: G = +-C_nb_dt M,
// M sparse, filter/sparse_map.hpp); measurements see the head only. propagate(const
// BlockTransition&) and update() exploit this: O(n^2 (b + c) + D^2 n) per propagation (b the
// largest tail block, c the coupled rows) and O(n^2 m) per update, instead of O(n^3) each. No
// allocation once the sizes have been met.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "stochnav/filter/block_diagonal_matrix.hpp"
#include "stochnav/filter/error_dynamics.hpp"
#include "stochnav/filter/sparse_map.hpp"

namespace stochnav {

/// Counters of numerical trouble since the filter started; all zero for a healthy run.
struct FilterHealth {
  std::uint64_t singular_innovations = 0;  ///< S = H P H^T + R not positive definite: skipped
  std::uint64_t repaired_diagonals = 0;    ///< diagonal entries of P found <= 0 and reset
  std::uint64_t non_finite = 0;            ///< NaN or infinity met in P (P reset to P0)
  bool ok() const {
    return singular_innovations == 0 && repaired_diagonals == 0 && non_finite == 0;
  }
};

/// Outcome of one measurement update.
struct UpdateOutcome {
  bool accepted = false;  ///< passed the gate and was applied
  bool singular = false;  ///< S was not positive definite (never applied)
  double nis = 0.0;       ///< z^T S^-1 z (NaN when singular)
  double log_det_s = 0.0; ///< ln det S (NaN when singular): with nis, the Gaussian likelihood
};

/// One group of augmented states in a BlockTransition: states [offset, offset + k) of the error
/// state, with their transition and noise, driving the c head rows [coupling_row,
/// coupling_row + c) through G = L M (Phi's entries in those rows and the segment's columns).
struct TailSegment {
  int offset = 0;                              ///< first state of the segment, >= D
  const BlockDiagonalMatrix& transition;       ///< Phi_t of the segment, k x k
  const BlockDiagonalMatrix& noise;            ///< Q_t of the segment, k x k
  int coupling_row = 0;                        ///< first head row driven by the segment
  Eigen::Ref<const Eigen::MatrixXd> coupling;  ///< L, c x r (c = 0: no coupling)
  const SparseMap& coupling_map;               ///< M, r x k (e.g. the sensor map, r = 3)
};

/// Phi and Q_d of one propagation by blocks (see the header comment). Entries of Phi not
/// described here are zero, and so are those of Q_d outside the head and the segments' blocks.
struct BlockTransition {
  Eigen::Ref<const Eigen::MatrixXd> head_transition;  ///< Phi_h, D x D
  Eigen::Ref<const Eigen::MatrixXd> head_noise;       ///< Q_h, D x D
  /// In order of offset, contiguous from D to n (segments of size 0 are allowed and skipped).
  std::span<const TailSegment> tail;
};

/// How update() applies the Joseph form (I - K H) P (I - K H)^T + K R K^T.
enum class JosephForm {
  /// P - K U^T - U K^T + K S K^T with U = P H^T, S = H P H^T + R: algebraically identical for
  /// any gain, O(n^2 m), symmetric by construction (one triangle computed, then mirrored).
  kExpanded,
  /// The textbook product with the n x n matrix I - K H, O(n^3): the reference.
  kProduct,
};

class ErrorStateFilter final {
 public:
  /// P0: n x n symmetric positive definite initial covariance of the error state.
  explicit ErrorStateFilter(Eigen::MatrixXd initial_covariance);

  int size() const { return static_cast<int>(covariance_.rows()); }
  const Eigen::MatrixXd& covariance() const { return covariance_; }
  const FilterHealth& health() const { return health_; }

  /// P <- Phi P Phi^T + Q_d (n x n each; Phi the discrete transition, Q_d the discrete noise),
  /// by dense products: O(n^3). The reference for propagate(const BlockTransition&). With the
  /// 15 core states alone and Phi of the core form [[A, B], [0, I]], the fixed-size kernel of
  /// filter/core_covariance.hpp (same result to rounding).
  void propagate(const Eigen::Ref<const Eigen::MatrixXd>& phi,
                 const Eigen::Ref<const Eigen::MatrixXd>& q_d);

  /// P <- Phi P Phi^T + Q_d for a filter of the 15 core states alone, Phi of the core form
  /// [[A, B], [0, I]] (filter/core_covariance.hpp; checked in debug builds), Q_d symmetric: the
  /// fixed-size kernel without propagate()'s checks and copies. Same result as propagate().
  void propagate_core(const CoreMatrix& phi, const CoreMatrix& q_d);

  /// P <- Phi P Phi^T + Q_d for a filter of N states whose transition has the fixed-size form
  /// of filter/core_covariance.hpp (the 9 navigation states, then N - 9 states with diagonal
  /// transition rows: biases, scale factors, first-order augmented states;
  /// kHasNavDiagonalKernel<N>; the form is checked in debug builds), Q_d symmetric: no
  /// dynamic-size product, no allocation. The same result as propagate() to rounding; at N = 15
  /// identical to propagate_core().
  template <int N>
  void propagate_nav_diagonal(const Eigen::Matrix<double, N, N>& phi,
                              const Eigen::Matrix<double, N, N>& q_d);

  /// P <- Phi P Phi^T + Q_d with Phi and Q_d given by blocks (BlockTransition): the same
  /// result as the dense propagate to rounding, in O(n^2 (b + c) + D^2 n). Precondition:
  /// D + the segments' sizes = n, segments contiguous, coupling rows inside the head.
  void propagate(const BlockTransition& transition);

  /// Measurement z = H dx + v, v ~ N(0, R): z (m), H (m x k) the first k <= n columns of the
  /// Jacobian (the others zero: aids see the head states only), R (m x m). When accepted
  /// (NIS <= gate_threshold and S positive definite) writes the error estimate K z into
  /// `correction` (n) and updates P in Joseph form (`form`); otherwise leaves both unchanged.
  UpdateOutcome update(const Eigen::Ref<const Eigen::VectorXd>& z,
                       const Eigen::Ref<const Eigen::MatrixXd>& h,
                       const Eigen::Ref<const Eigen::MatrixXd>& r, double gate_threshold,
                       Eigen::Ref<Eigen::VectorXd> correction,
                       JosephForm form = JosephForm::kExpanded);

  /// Replaces P (n x n, symmetric positive definite; the size must not change): a filter split
  /// from another (MwdNavigator::split). Throws std::invalid_argument for another size.
  void replace_covariance(const Eigen::Ref<const Eigen::MatrixXd>& covariance);

  /// Makes state `index` a consider state (Schmidt-Kalman): update() never corrects its
  /// estimate (its row of K is zero), while P keeps its uncertainty and its correlations with
  /// the other states, whose gains are the optimal ones (the Joseph form holds for any gain).
  void consider(Eigen::Index index);
  /// Makes a consider state an estimated one again (no-op for an estimated state).
  void release(Eigen::Index index) { std::erase(considered_, index); }
  /// Whether state `index` is a consider state.
  bool considered(Eigen::Index index) const {
    return std::find(considered_.begin(), considered_.end(), index) != considered_.end();
  }

  /// S = H P H^T + R of the last update attempt (m x m) and its gain K (n x m; zero if
  /// rejected): for innovation records and adaptive noise models.
  const Eigen::MatrixXd& last_innovation_covariance() const { return innovation_covariance_; }
  const Eigen::MatrixXd& last_gain() const { return gain_; }

 private:
  // Makes P exactly symmetric (kAverage: the mean of P and P^T; kMirrorLower: the lower
  // triangle copied over the upper one; kNone: P is symmetric already), then repairs it
  // (FilterHealth).
  enum class Symmetrize { kAverage, kMirrorLower, kNone };
  void keep_healthy(Symmetrize how);
  static constexpr int kCoreSize = 15;

  Eigen::MatrixXd covariance_;
  Eigen::MatrixXd initial_covariance_;
  Eigen::MatrixXd innovation_covariance_;
  Eigen::MatrixXd gain_;
  Eigen::LLT<Eigen::MatrixXd> innovation_factor_;
  Eigen::VectorXd whitened_innovation_;  // L^-1 z, m
  Eigen::MatrixXd scratch_;              // n x n
  Eigen::MatrixXd p_ht_;                 // U = P H^T, n x m
  Eigen::MatrixXd joseph_term_;          // K S / 2 - U, n x m
  Eigen::MatrixXd h_full_;               // H padded to m x n (JosephForm::kProduct)
  std::vector<Eigen::Index> considered_;  // consider states: rows of K kept zero
  // propagate(const BlockTransition&): Y = P_th Phi_h^T + P_tt G^T (n_a x D),
  // Z = P_hh Phi_h^T + P_ht G^T (D x D), X = P_tt Phi_t^T (n_a x n_a), and the products with
  // the coupling maps P_tt M^T (n_a x r), P_ht M^T (D x r), M Y (r x D).
  Eigen::MatrixXd tail_head_, head_head_, tail_tail_;
  Eigen::MatrixXd tail_map_, head_map_, map_head_;
  FilterHealth health_;
};

}  // namespace stochnav
