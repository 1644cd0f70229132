// BlockDiagonalMatrix: its products equal the dense products on mixed blocks (diagonal runs,
// 2 x 2, 3 x 3 and a large dense block), whatever lies outside the blocks of the source matrix.

#include "stochnav/filter/block_diagonal_matrix.hpp"

#include <gtest/gtest.h>

#include <random>
#include "random_matrix.hpp"

namespace stochnav {
namespace {

using stochnav::testing::random_matrix;

TEST(BlockDiagonalMatrix, ProductsEqualDenseProducts) {
  std::mt19937_64 engine(11);
  constexpr int k = 26;
  Eigen::MatrixXd pattern = Eigen::MatrixXd::Identity(k, k);
  pattern.block(3, 3, 3, 3).setOnes();      // 3 x 3
  pattern.block(7, 7, 2, 2).setOnes();      // 2 x 2
  pattern.block(12, 12, 10, 10).setOnes();  // larger than the coefficient-wise limit
  const auto structure = BlockDiagonalStructure(k).cover(pattern);
  ASSERT_EQ(structure.blocks().size(), 7u);
  const Eigen::MatrixXd full = random_matrix(k, k, engine);  // nonzero outside the blocks too
  const Eigen::MatrixXd b = full.cwiseProduct(pattern);
  BlockDiagonalMatrix matrix;
  matrix.assign(structure, full);
  EXPECT_EQ(matrix.to_dense(), b);

  const Eigen::MatrixXd src = random_matrix(k, 7, engine);
  Eigen::MatrixXd left(k, 7), right(7, k);
  matrix.multiply(src, left);
  matrix.multiply_transpose_from_right(src.transpose(), right);
  EXPECT_LE((left - b * src).norm(), 1e-14 * (b * src).norm());
  EXPECT_LE((right - src.transpose() * b.transpose()).norm(), 1e-14 * (b * src).norm());
  Eigen::MatrixXd sum = Eigen::MatrixXd::Ones(k, k);
  matrix.add_to(sum);
  EXPECT_EQ(sum, b + Eigen::MatrixXd::Ones(k, k));

  // Reassigning a structure of the same size reuses the storage and gives the new values.
  matrix.assign(BlockDiagonalStructure::dense(k), full);
  EXPECT_EQ(matrix.to_dense(), full);
}

}  // namespace
}  // namespace stochnav
