#pragma once
// A k x k block-diagonal matrix (the transition Phi_t or noise Q_t of augmented states) stored
// as its blocks on a BlockDiagonalStructure (filter/block_structure.hpp): the diagonal runs as
// one contiguous vector, each dense block as a small column-major matrix. Products cost
// O(k b) per column of the other factor (b the largest block) instead of O(k^2), and a
// diagonal run scales whole column segments at once.

#include <Eigen/Core>

#include "stochnav/filter/block_structure.hpp"

namespace stochnav {

class BlockDiagonalMatrix final {
 public:
  /// The empty 0 x 0 matrix.
  BlockDiagonalMatrix() = default;

  /// Takes the blocks of `dense` (k x k, k = structure.size()) on `structure`; entries outside
  /// the blocks are not read (they are taken as zero). Allocates only when the storage needed
  /// grows.
  void assign(const BlockDiagonalStructure& structure,
              const Eigen::Ref<const Eigen::MatrixXd>& dense);

  int size() const { return structure_.size(); }
  const BlockDiagonalStructure& structure() const { return structure_; }

  /// dst = B src; src and dst k x c, not aliased. No allocation.
  void multiply(const Eigen::Ref<const Eigen::MatrixXd>& src,
                Eigen::Ref<Eigen::MatrixXd> dst) const;
  /// dst = src B^T; src and dst c x k, not aliased. No allocation.
  void multiply_transpose_from_right(const Eigen::Ref<const Eigen::MatrixXd>& src,
                                     Eigen::Ref<Eigen::MatrixXd> dst) const;
  /// The lower triangles of the products above, for symmetric results (A a x a, a >= offset
  /// + k, of which this matrix's states occupy [offset, offset + k)):
  /// multiply_lower: src, dst the k rows [offset, offset + k) of A (k x a); dst = B src is
  /// computed in the columns up to each block's last state, which cover every entry of B A on
  /// or below A's diagonal; the others are left unchanged. No allocation.
  void multiply_lower(const Eigen::Ref<const Eigen::MatrixXd>& src, Eigen::Ref<Eigen::MatrixXd> dst,
                      int offset) const;
  /// multiply_transpose_from_right_lower: src, dst the k columns [offset, offset + k) of A
  /// (a x k); dst = src B^T is computed in the rows from each block's first state down. No
  /// allocation.
  void multiply_transpose_from_right_lower(const Eigen::Ref<const Eigen::MatrixXd>& src,
                                           Eigen::Ref<Eigen::MatrixXd> dst, int offset) const;

  /// dst += B; dst k x k, untouched outside the blocks. No allocation.
  void add_to(Eigen::Ref<Eigen::MatrixXd> dst) const;

  /// The k x k matrix (zeros outside the blocks); for tests and messages.
  Eigen::MatrixXd to_dense() const;

 private:
  BlockDiagonalStructure structure_;
  Eigen::VectorXd diagonal_;  // k: B(i, i) of the states in diagonal runs (others unused)
  Eigen::VectorXd dense_;     // the dense blocks one after the other, column-major each
};

}  // namespace stochnav
