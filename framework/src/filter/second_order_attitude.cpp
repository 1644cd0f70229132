#include "stochnav/filter/second_order_attitude.hpp"

#include <array>

namespace stochnav {

Eigen::Vector3d second_order_attitude_rate_mean(const Eigen::Matrix3d& p_attitude,
                                                const Eigen::Vector3d& omega_in_n) {
  // E[phi phi^T] = P, E[|phi|^2] = tr(P).
  return -0.5 * (p_attitude * omega_in_n - p_attitude.trace() * omega_in_n);
}

Eigen::Matrix3d second_order_attitude_rate_covariance(const Eigen::Matrix3d& p_attitude,
                                                      const Eigen::Vector3d& omega_in_n) {
  // [phi x]^2 w = phi (phi . w) - |phi|^2 w, so m_i = -1/2 (phi_i (phi . w) - |phi|^2 w_i)
  // = phi^T A_i phi with A_i = -1/2 (sym(e_i w^T) - w_i I), sym(M) = (M + M^T) / 2.
  std::array<Eigen::Matrix3d, 3> forms;
  for (int i = 0; i < 3; ++i) {
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
    outer.row(i) = omega_in_n.transpose();
    forms[i] = -0.5 * (0.5 * (outer + outer.transpose()) -
                       omega_in_n(i) * Eigen::Matrix3d::Identity());
  }
  std::array<Eigen::Matrix3d, 3> form_times_p;
  for (int i = 0; i < 3; ++i) form_times_p[i] = forms[i] * p_attitude;
  Eigen::Matrix3d covariance;
  for (int i = 0; i < 3; ++i) {
    for (int l = i; l < 3; ++l) {
      covariance(i, l) = 2.0 * (form_times_p[i] * form_times_p[l]).trace();
      covariance(l, i) = covariance(i, l);
    }
  }
  return covariance;
}

Eigen::Matrix3d second_order_attitude_noise(const Eigen::Matrix3d& p_attitude,
                                            const Eigen::Vector3d& omega_in_n, double interval_s,
                                            double correlation_s) {
  if (!(correlation_s > 0.0)) return Eigen::Matrix3d::Zero();
  return second_order_attitude_rate_covariance(p_attitude, omega_in_n) *
         (2.0 * correlation_s * interval_s);
}

}  // namespace stochnav
