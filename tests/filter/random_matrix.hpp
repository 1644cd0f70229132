#pragma once
// Random test matrices for the covariance-structure tests.

#include <Eigen/Core>
#include <random>

namespace stochnav::testing {

/// rows x cols matrix of independent standard normal entries drawn from `engine`.
inline Eigen::MatrixXd random_matrix(int rows, int cols, std::mt19937_64& engine) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd m(rows, cols);
  for (int j = 0; j < cols; ++j) {
    for (int i = 0; i < rows; ++i) m(i, j) = normal(engine);
  }
  return m;
}

}  // namespace stochnav::testing
