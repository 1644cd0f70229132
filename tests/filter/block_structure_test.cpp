// Block detection on known patterns: diagonal runs, 2 x 2 and companion blocks, the dense fallback.

#include "stochnav/filter/block_structure.hpp"

#include <gtest/gtest.h>

#include <random>
#include "random_matrix.hpp"

namespace stochnav {
namespace {

using Block = BlockDiagonalStructure::Block;

using stochnav::testing::random_matrix;

TEST(BlockDiagonalStructure, ADiagonalPatternIsOneDiagonalRun) {
  Eigen::MatrixXd phi = Eigen::MatrixXd::Zero(5, 5);
  phi.diagonal() << 0.9, 0.8, 0.7, 0.6, 0.5;
  BlockDiagonalStructure structure(5);
  structure.cover(phi);
  EXPECT_EQ(structure.blocks(), (std::vector<Block>{{0, 5, true}}));
  EXPECT_EQ(structure.max_block_size(), 1);
  EXPECT_TRUE(structure.covers(phi));
  EXPECT_FALSE(structure.is_dense());
}

TEST(BlockDiagonalStructure, TwoByTwoBlocksBetweenDiagonalRuns) {
  // A shaping filter's axis: two first-order states, a ramp (2 x 2), an oscillator (2 x 2),
  // then the next axis' first-order state.
  Eigen::MatrixXd phi = Eigen::MatrixXd::Identity(7, 7);
  phi(2, 3) = 0.1;                    // ramp: upper-triangular
  phi(4, 5) = -0.2, phi(5, 4) = 0.2;  // oscillator
  Eigen::MatrixXd q = Eigen::MatrixXd::Identity(7, 7);
  const auto structure = BlockDiagonalStructure(7).cover(phi).cover(q);
  EXPECT_EQ(structure.blocks(),
            (std::vector<Block>{{0, 2, true}, {2, 2, false}, {4, 2, false}, {6, 1, true}}));
  EXPECT_EQ(structure.max_block_size(), 2);
  EXPECT_TRUE(structure.covers(phi));
  EXPECT_TRUE(structure.covers(q));
  // A coupling across two blocks is not covered; covering it merges them and what lies between.
  Eigen::MatrixXd coupled = q;
  coupled(6, 3) = 1e-300;
  EXPECT_FALSE(structure.covers(coupled));
  auto merged = structure;
  merged.cover(coupled);
  EXPECT_EQ(merged.blocks(), (std::vector<Block>{{0, 2, true}, {2, 5, false}}));
}

TEST(BlockDiagonalStructure, QdCouplingsCountLikeTransitionCouplings) {
  // AR(2) companion form in Phi, its noise only in the first state; Q couples 3 and 4.
  Eigen::MatrixXd phi = Eigen::MatrixXd::Identity(5, 5);
  phi(0, 1) = 0.3, phi(1, 0) = 1.0;
  Eigen::MatrixXd q = Eigen::MatrixXd::Identity(5, 5);
  q(3, 4) = q(4, 3) = 0.1;
  const auto structure = BlockDiagonalStructure(5).cover(phi).cover(q);
  EXPECT_EQ(structure.blocks(), (std::vector<Block>{{0, 2, false}, {2, 1, true}, {3, 2, false}}));
}

TEST(BlockDiagonalStructure, NoBlockStructureFallsBackToOneDenseBlock) {
  std::mt19937_64 engine(3);
  const Eigen::MatrixXd dense = random_matrix(6, 6, engine);
  const auto structure = BlockDiagonalStructure(6).cover(dense);
  EXPECT_TRUE(structure.is_dense());
  EXPECT_EQ(structure, BlockDiagonalStructure::dense(6));
  // A single far coupling (first with last state) also spans everything.
  Eigen::MatrixXd corner = Eigen::MatrixXd::Identity(6, 6);
  corner(0, 5) = 1.0;
  EXPECT_TRUE(BlockDiagonalStructure(6).cover(corner).is_dense());
  // A NaN couples: it must not be dropped as if it were zero.
  Eigen::MatrixXd nan = Eigen::MatrixXd::Identity(6, 6);
  nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(BlockDiagonalStructure(6).covers(nan));
}

TEST(BlockDiagonalStructure, EmptyStructure) {
  const BlockDiagonalStructure structure(0);
  EXPECT_TRUE(structure.blocks().empty());
  EXPECT_EQ(structure.max_block_size(), 0);
  EXPECT_TRUE(structure.covers(Eigen::MatrixXd(0, 0)));
}

}  // namespace
}  // namespace stochnav
