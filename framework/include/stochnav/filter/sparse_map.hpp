#pragma once
// A sparse r x k matrix kept as its nonzeros: the augmented sensor map M of a noise model
// (3 x n_aug, plugin/noise_model_plugin.hpp), where each state drives one axis. The filter
// couples augmented states into the head through G = L M (L = +-C_nb_dt, 3 x 3,
// filter/error_state_filter.hpp, TailSegment), so products with G cost O(k) per column of the
// other factor, not O(3 k).

#include <Eigen/Core>
#include <vector>

namespace stochnav {

class SparseMap final {
 public:
  /// The empty 0 x 0 map.
  SparseMap() = default;
  /// The exact nonzeros of `dense` (r x k), by column. Allocates.
  explicit SparseMap(const Eigen::Ref<const Eigen::MatrixXd>& dense);

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  /// Number of stored nonzeros.
  int nonzeros() const { return static_cast<int>(entries_.size()); }

  /// dst += src M^T: src c x k, dst c x r. No allocation.
  void add_product_transpose_from_right(const Eigen::Ref<const Eigen::MatrixXd>& src,
                                        Eigen::Ref<Eigen::MatrixXd> dst) const;
  /// dst += M src: src k x c, dst r x c. No allocation.
  void add_product(const Eigen::Ref<const Eigen::MatrixXd>& src,
                   Eigen::Ref<Eigen::MatrixXd> dst) const;

 private:
  struct Entry {
    int row = 0;
    int col = 0;
    double value = 0.0;
  };
  std::vector<Entry> entries_;  // in order of column
  int rows_ = 0;
  int cols_ = 0;
};

}  // namespace stochnav
