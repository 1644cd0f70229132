#include "stochnav/filter/block_structure.hpp"

#include <algorithm>
#include <cassert>

namespace stochnav {
BlockDiagonalStructure::BlockDiagonalStructure(int size) : size_(std::max(size, 0)) {
  if (size_ > 0) blocks_.push_back({.offset = 0, .size = size_, .diagonal = true});
}

BlockDiagonalStructure BlockDiagonalStructure::dense(int size) {
  BlockDiagonalStructure structure(size);
  if (!structure.blocks_.empty()) structure.blocks_[0].diagonal = false;
  return structure;
}

int BlockDiagonalStructure::max_block_size() const {
  int largest = 0;
  for (const Block& block : blocks_) largest = std::max(largest, block.diagonal ? 1 : block.size);
  return largest;
}

bool BlockDiagonalStructure::covers(const Eigen::Ref<const Eigen::MatrixXd>& matrix) const {
  assert(matrix.rows() == size_ && matrix.cols() == size_);
  for (const Block& block : blocks_) {
    for (int j = block.offset; j < block.offset + block.size; ++j) {
      // Inside a dense block only the rows outside it must be zero; in a run, all but (j, j).
      const int inside_begin = block.diagonal ? j : block.offset;
      const int inside_end = block.diagonal ? j + 1 : block.offset + block.size;
      // A sum of magnitudes is 0 only when every entry is (no underflow: nothing is squared;
      // a NaN or an overflow makes it NaN or infinite), and it vectorises.
      if (!(matrix.col(j).head(inside_begin).cwiseAbs().sum() == 0.0)) return false;
      if (!(matrix.col(j).tail(size_ - inside_end).cwiseAbs().sum() == 0.0)) return false;
    }
  }
  return true;
}

BlockDiagonalStructure& BlockDiagonalStructure::cover(
    const Eigen::Ref<const Eigen::MatrixXd>& pattern) {
  assert(pattern.rows() == size_ && pattern.cols() == size_);
  std::vector<int> reach(static_cast<std::size_t>(size_));
  for (int i = 0; i < size_; ++i) reach[static_cast<std::size_t>(i)] = i;
  for (const Block& block : blocks_) {
    if (block.diagonal) continue;
    reach[static_cast<std::size_t>(block.offset)] = block.offset + block.size - 1;
  }
  for (int j = 0; j < size_; ++j) {
    for (int i = 0; i < size_; ++i) {
      // Anything but an exact zero couples (a NaN too: it must not be dropped silently).
      if (i == j || pattern(i, j) == 0.0) continue;
      int& r = reach[static_cast<std::size_t>(std::min(i, j))];
      r = std::max(r, std::max(i, j));
    }
  }
  rebuild(reach);
  return *this;
}

void BlockDiagonalStructure::rebuild(const std::vector<int>& reach) {
  blocks_.clear();
  int start = 0;
  while (start < size_) {
    // Merge the overlapping coupling ranges [i, reach[i]] that start inside the current block.
    int end = start;
    for (int i = start; i <= end; ++i) end = std::max(end, reach[static_cast<std::size_t>(i)]);
    const int size = end - start + 1;
    if (size == 1 && !blocks_.empty() && blocks_.back().diagonal) {
      ++blocks_.back().size;
    } else {
      blocks_.push_back({.offset = start, .size = size, .diagonal = size == 1});
    }
    start = end + 1;
  }
}

}  // namespace stochnav
