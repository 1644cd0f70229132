#include "stochnav/filter/block_diagonal_matrix.hpp"

#include <cassert>

namespace stochnav {
namespace {

using Block = BlockDiagonalStructure::Block;
using ConstMap = Eigen::Map<const Eigen::MatrixXd>;

// Dense blocks up to this size are multiplied coefficient-wise (no packing); larger ones (the
// dense fallback) through Eigen's blocked product, which is faster there.
constexpr int kLazyProductMaxBlock = 8;

}  // namespace

void BlockDiagonalMatrix::assign(const BlockDiagonalStructure& structure,
                                 const Eigen::Ref<const Eigen::MatrixXd>& dense) {
  assert(dense.rows() == structure.size() && dense.cols() == structure.size());
  structure_ = structure;
  Eigen::Index dense_size = 0;
  for (const Block& block : structure_.blocks()) {
    if (!block.diagonal) dense_size += block.size * block.size;
  }
  // resize() keeps the storage when the size is unchanged: no allocation at a repeated assign.
  diagonal_.resize(structure_.size());
  dense_.resize(dense_size);
  Eigen::Index next = 0;
  for (const Block& block : structure_.blocks()) {
    const int o = block.offset, s = block.size;
    if (block.diagonal) {
      diagonal_.segment(o, s) = dense.diagonal().segment(o, s);
    } else {
      Eigen::Map<Eigen::MatrixXd>(dense_.data() + next, s, s) = dense.block(o, o, s, s);
      next += s * s;
    }
  }
}

void BlockDiagonalMatrix::multiply(const Eigen::Ref<const Eigen::MatrixXd>& src,
                                   Eigen::Ref<Eigen::MatrixXd> dst) const {
  assert(src.rows() == size() && dst.rows() == size() && dst.cols() == src.cols());
  const double* next = dense_.data();
  for (const Block& block : structure_.blocks()) {
    const int o = block.offset, s = block.size;
    if (block.diagonal) {
      dst.middleRows(o, s) = diagonal_.segment(o, s).asDiagonal() * src.middleRows(o, s);
      continue;
    }
    if (s == 2) {
      dst.middleRows(o, 2).noalias() =
          Eigen::Map<const Eigen::Matrix2d>(next).lazyProduct(src.middleRows(o, 2));
    } else if (s <= kLazyProductMaxBlock) {
      dst.middleRows(o, s).noalias() = ConstMap(next, s, s).lazyProduct(src.middleRows(o, s));
    } else {
      dst.middleRows(o, s).noalias() = ConstMap(next, s, s) * src.middleRows(o, s);
    }
    next += s * s;
  }
}

void BlockDiagonalMatrix::multiply_transpose_from_right(
    const Eigen::Ref<const Eigen::MatrixXd>& src, Eigen::Ref<Eigen::MatrixXd> dst) const {
  assert(src.cols() == size() && dst.cols() == size() && dst.rows() == src.rows());
  const double* next = dense_.data();
  for (const Block& block : structure_.blocks()) {
    const int o = block.offset, s = block.size;
    if (block.diagonal) {
      dst.middleCols(o, s) = src.middleCols(o, s) * diagonal_.segment(o, s).asDiagonal();
      continue;
    }
    if (s == 2) {
      dst.middleCols(o, 2).noalias() =
          src.middleCols(o, 2).lazyProduct(Eigen::Map<const Eigen::Matrix2d>(next).transpose());
    } else if (s <= kLazyProductMaxBlock) {
      dst.middleCols(o, s).noalias() =
          src.middleCols(o, s).lazyProduct(ConstMap(next, s, s).transpose());
    } else {
      dst.middleCols(o, s).noalias() = src.middleCols(o, s) * ConstMap(next, s, s).transpose();
    }
    next += s * s;
  }
}

void BlockDiagonalMatrix::multiply_lower(const Eigen::Ref<const Eigen::MatrixXd>& src,
                                         Eigen::Ref<Eigen::MatrixXd> dst, int offset) const {
  assert(src.rows() == size() && dst.rows() == size() && dst.cols() == src.cols());
  assert(offset + size() <= src.cols());
  const double* next = dense_.data();
  for (const Block& block : structure_.blocks()) {
    const int o = block.offset, s = block.size;
    const int columns = offset + o + s;
    if (block.diagonal) {
      dst.block(o, 0, s, columns) =
          diagonal_.segment(o, s).asDiagonal() * src.block(o, 0, s, columns);
      continue;
    }
    if (s == 2) {
      dst.block(o, 0, 2, columns).noalias() =
          Eigen::Map<const Eigen::Matrix2d>(next).lazyProduct(src.block(o, 0, 2, columns));
    } else if (s <= kLazyProductMaxBlock) {
      dst.block(o, 0, s, columns).noalias() =
          ConstMap(next, s, s).lazyProduct(src.block(o, 0, s, columns));
    } else {
      dst.block(o, 0, s, columns).noalias() = ConstMap(next, s, s) * src.block(o, 0, s, columns);
    }
    next += s * s;
  }
}

void BlockDiagonalMatrix::multiply_transpose_from_right_lower(
    const Eigen::Ref<const Eigen::MatrixXd>& src, Eigen::Ref<Eigen::MatrixXd> dst,
    int offset) const {
  assert(src.cols() == size() && dst.cols() == size() && dst.rows() == src.rows());
  assert(offset + size() <= src.rows());
  const double* next = dense_.data();
  for (const Block& block : structure_.blocks()) {
    const int o = block.offset, s = block.size;
    const int first = offset + o;
    const int rows = static_cast<int>(src.rows()) - first;
    if (block.diagonal) {
      dst.block(first, o, rows, s) =
          src.block(first, o, rows, s) * diagonal_.segment(o, s).asDiagonal();
      continue;
    }
    if (s == 2) {
      dst.block(first, o, rows, 2).noalias() =
          src.block(first, o, rows, 2)
              .lazyProduct(Eigen::Map<const Eigen::Matrix2d>(next).transpose());
    } else if (s <= kLazyProductMaxBlock) {
      dst.block(first, o, rows, s).noalias() =
          src.block(first, o, rows, s).lazyProduct(ConstMap(next, s, s).transpose());
    } else {
      dst.block(first, o, rows, s).noalias() =
          src.block(first, o, rows, s) * ConstMap(next, s, s).transpose();
    }
    next += s * s;
  }
}

void BlockDiagonalMatrix::add_to(Eigen::Ref<Eigen::MatrixXd> dst) const {
  assert(dst.rows() == size() && dst.cols() == size());
  const double* next = dense_.data();
  for (const Block& block : structure_.blocks()) {
    const int o = block.offset, s = block.size;
    if (block.diagonal) {
      dst.diagonal().segment(o, s) += diagonal_.segment(o, s);
    } else {
      dst.block(o, o, s, s) += ConstMap(next, s, s);
      next += s * s;
    }
  }
}

Eigen::MatrixXd BlockDiagonalMatrix::to_dense() const {
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(size(), size());
  add_to(dense);
  return dense;
}

}  // namespace stochnav
