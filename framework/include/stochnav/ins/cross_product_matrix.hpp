#pragma once
// The cross-product (skew-symmetric) matrix: skew(a) b = a x b, for any frame.

#include <Eigen/Core>

namespace stochnav {

inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

}  // namespace stochnav
