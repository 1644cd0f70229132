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

#include <Eigen/Core>
#include <cstdint>

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
};

class ErrorStateFilter final {
 public:
  /// P0: n x n symmetric positive definite initial covariance of the error state.
  explicit ErrorStateFilter(Eigen::MatrixXd initial_covariance);

  int size() const { return static_cast<int>(covariance_.rows()); }
  const Eigen::MatrixXd& covariance() const { return covariance_; }
  const FilterHealth& health() const { return health_; }

  /// P <- Phi P Phi^T + Q_d (n x n each; Phi the discrete transition, Q_d the discrete noise).
  void propagate(const Eigen::MatrixXd& phi, const Eigen::MatrixXd& q_d);

  /// Measurement z = H dx + v, v ~ N(0, R): z (m), H (m x n), R (m x m). When accepted
  /// (NIS <= gate_threshold and S positive definite) writes the error estimate K z into
  /// `correction` (n) and updates P in Joseph form; otherwise leaves both unchanged.
  UpdateOutcome update(const Eigen::Ref<const Eigen::VectorXd>& z,
                       const Eigen::Ref<const Eigen::MatrixXd>& h,
                       const Eigen::Ref<const Eigen::MatrixXd>& r, double gate_threshold,
                       Eigen::Ref<Eigen::VectorXd> correction);

  /// S = H P H^T + R of the last update attempt (m x m) and its gain K (n x m; zero if
  /// rejected): for innovation records and adaptive noise models.
  const Eigen::MatrixXd& last_innovation_covariance() const { return innovation_covariance_; }
  const Eigen::MatrixXd& last_gain() const { return gain_; }

 private:
  void keep_healthy();
  static constexpr int kCoreSize = 15;

  Eigen::MatrixXd covariance_;
  Eigen::MatrixXd initial_covariance_;
  Eigen::MatrixXd innovation_covariance_;
  Eigen::MatrixXd gain_;
  Eigen::MatrixXd scratch_;
  FilterHealth health_;
};

}  // namespace stochnav
