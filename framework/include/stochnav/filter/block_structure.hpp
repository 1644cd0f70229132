#pragma once
// The block-diagonal structure of the augmented states' transition and noise (the tail of the
// error state, plugin/noise_model_plugin.hpp): first-order shaping states give a diagonal,
// ramps and oscillators 2 x 2 blocks, AR / ARMA companion forms a small dense block per axis.
// Knowing it, the filter multiplies by Phi_t in O(k b) per column instead of O(k^2)
// (filter/block_diagonal_matrix.hpp; filter/error_state_filter.hpp, BlockTransition).
//
// Blocks are contiguous ranges of states. A structure is detected from nonzero patterns: two
// states belong to one block when some pattern couples them, and a block is widened to the
// contiguous range it spans (states 0 and 5 coupled make one block 0..5). A pattern with no
// block structure therefore ends as one dense block: the dense fallback, still exact.

#include <Eigen/Core>
#include <vector>

namespace stochnav {

class BlockDiagonalStructure final {
 public:
  /// Rows and columns [offset, offset + size) of the described k x k matrices.
  struct Block {
    int offset = 0;
    int size = 0;
    /// True: the block is itself diagonal (a run of `size` mutually independent states, stored
    /// as one block so that they are scaled together); false: a dense size x size block.
    bool diagonal = false;
    bool operator==(const Block&) const = default;
  };

  /// The finest structure of size k >= 0: every state independent (one diagonal run).
  explicit BlockDiagonalStructure(int size = 0);

  /// One dense block of size k: what any k x k matrix fits.
  static BlockDiagonalStructure dense(int size);

  int size() const { return size_; }
  /// In order of offset, covering [0, size) without gaps; consecutive diagonal runs are merged.
  const std::vector<Block>& blocks() const { return blocks_; }
  /// The size of the largest dense block (1 when every block is a diagonal run, 0 when empty).
  int max_block_size() const;
  /// A single dense block over all states (nothing to exploit).
  bool is_dense() const { return blocks_.size() == 1 && !blocks_[0].diagonal; }
  /// Every state independent (one diagonal run, or no states): a diagonal matrix.
  bool is_diagonal() const {
    return blocks_.empty() || (blocks_.size() == 1 && blocks_[0].diagonal);
  }

  /// True when every nonzero of `matrix` (size x size) lies inside a block (inside a diagonal
  /// run: on the diagonal). O(k^2), no allocation.
  bool covers(const Eigen::Ref<const Eigen::MatrixXd>& matrix) const;

  /// Coarsens this structure as little as possible so that it covers `pattern` too: the
  /// structure of the nonzeros of `pattern` (size x size) united with the current blocks.
  /// O(k^2); allocates. Detect a structure with BlockDiagonalStructure(k).cover(a).cover(b).
  BlockDiagonalStructure& cover(const Eigen::Ref<const Eigen::MatrixXd>& pattern);

  bool operator==(const BlockDiagonalStructure&) const = default;

 private:
  // Rebuilds blocks_ from reach[i] = the last state that state i is coupled with (>= i).
  void rebuild(const std::vector<int>& reach);

  int size_ = 0;
  std::vector<Block> blocks_;
};

}  // namespace stochnav
