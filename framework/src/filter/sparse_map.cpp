#include "stochnav/filter/sparse_map.hpp"

#include <cassert>

namespace stochnav {

SparseMap::SparseMap(const Eigen::Ref<const Eigen::MatrixXd>& dense)
    : rows_(static_cast<int>(dense.rows())), cols_(static_cast<int>(dense.cols())) {
  for (int j = 0; j < cols_; ++j) {
    for (int i = 0; i < rows_; ++i) {
      if (dense(i, j) != 0.0) entries_.push_back({.row = i, .col = j, .value = dense(i, j)});
    }
  }
}

void SparseMap::add_product_transpose_from_right(const Eigen::Ref<const Eigen::MatrixXd>& src,
                                                 Eigen::Ref<Eigen::MatrixXd> dst) const {
  assert(src.cols() == cols_ && dst.cols() == rows_ && dst.rows() == src.rows());
  // Column by column: contiguous axpys.
  for (const Entry& entry : entries_) dst.col(entry.row) += entry.value * src.col(entry.col);
}

void SparseMap::add_product(const Eigen::Ref<const Eigen::MatrixXd>& src,
                            Eigen::Ref<Eigen::MatrixXd> dst) const {
  assert(src.rows() == cols_ && dst.rows() == rows_ && dst.cols() == src.cols());
  for (const Entry& entry : entries_) dst.row(entry.row) += entry.value * src.row(entry.col);
}

}  // namespace stochnav
