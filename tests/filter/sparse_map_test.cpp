// SparseMap: its products equal the dense products with the map it was built from.

#include "stochnav/filter/sparse_map.hpp"

#include <gtest/gtest.h>

namespace stochnav {
namespace {

TEST(SparseMap, ProductsEqualDenseProducts) {
  // A sensor map: states of x, y, z each driving their axis, one state driving two axes.
  Eigen::MatrixXd map = Eigen::MatrixXd::Zero(3, 7);
  map(0, 0) = 1.0, map(0, 1) = 2.0, map(1, 2) = -1.5, map(1, 3) = 1.0, map(2, 4) = 0.5;
  map(2, 5) = 1.0, map(0, 5) = 0.25;  // column 6 stays zero
  const SparseMap sparse(map);
  EXPECT_EQ(sparse.rows(), 3);
  EXPECT_EQ(sparse.cols(), 7);
  EXPECT_EQ(sparse.nonzeros(), 7);

  const Eigen::MatrixXd src = Eigen::MatrixXd::Random(5, 7);
  Eigen::MatrixXd right = Eigen::MatrixXd::Ones(5, 3);
  sparse.add_product_transpose_from_right(src, right);
  EXPECT_LE((right - (Eigen::MatrixXd::Ones(5, 3) + src * map.transpose())).norm(), 1e-15);

  const Eigen::MatrixXd column_src = Eigen::MatrixXd::Random(7, 4);
  Eigen::MatrixXd left = Eigen::MatrixXd::Zero(3, 4);
  sparse.add_product(column_src, left);
  EXPECT_LE((left - map * column_src).norm(), 1e-15);
}

}  // namespace
}  // namespace stochnav
