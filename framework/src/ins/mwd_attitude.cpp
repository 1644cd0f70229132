#include "stochnav/ins/mwd_attitude.hpp"

#include <cmath>
#include <numbers>

namespace stochnav {
namespace {

Eigen::Matrix3d rotation_x(double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, c, -s, 0, s, c;
  return r;
}

Eigen::Matrix3d rotation_z(double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  Eigen::Matrix3d r;
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

// Vertical tool, mark to the north: columns x_b = N, y_b = E, z_b = Down (in ENU).
Eigen::Matrix3d vertical_reference() {
  Eigen::Matrix3d c0;
  c0 << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  return c0;
}

}  // namespace

double wrap_two_pi(double angle_rad) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  double wrapped = std::fmod(angle_rad, kTwoPi);
  if (wrapped < 0.0) wrapped += kTwoPi;
  if (wrapped >= kTwoPi) wrapped = 0.0;  // fmod of a tiny negative rounds up to 2 pi
  return wrapped + 0.0;                  // -0 becomes +0
}

Eigen::Matrix3d dcm_from_mwd(const MwdAttitude& attitude) {
  return rotation_z(-attitude.azimuth_rad) * rotation_x(attitude.inclination_rad) *
         vertical_reference() * rotation_z(attitude.toolface_rad);
}

MwdAttitude mwd_from_dcm(const Eigen::Matrix3d& C_nb) {
  MwdAttitude attitude;
  // Third column: the tool axis in ENU; third row: the Up components of the body axes.
  const double horizontal = std::hypot(C_nb(0, 2), C_nb(1, 2));
  attitude.inclination_rad = std::atan2(horizontal, -C_nb(2, 2));
  if (horizontal < kNearVerticalSin) {
    // x_b of dcm_from_mwd(I, TF, 0) is (sin TF, cos TF cos I, cos TF sin I).
    attitude.azimuth_rad = 0.0;
    const double sign = C_nb(2, 2) <= 0.0 ? 1.0 : -1.0;  // sign of cos I
    attitude.toolface_rad = wrap_two_pi(std::atan2(C_nb(0, 0), sign * C_nb(1, 0)));
    return attitude;
  }
  attitude.azimuth_rad = wrap_two_pi(std::atan2(C_nb(0, 2), C_nb(1, 2)));
  // x_b . Up = sin I cos TF, y_b . Up = -sin I sin TF.
  attitude.toolface_rad = wrap_two_pi(std::atan2(-C_nb(2, 1), C_nb(2, 0)));
  return attitude;
}

Eigen::Quaterniond quaternion_from_mwd(const MwdAttitude& attitude) {
  Eigen::Quaterniond q(dcm_from_mwd(attitude));
  q.normalize();
  return q;
}

MwdAttitude mwd_from_quaternion(const Eigen::Quaterniond& q_nb) {
  return mwd_from_dcm(q_nb.normalized().toRotationMatrix());
}

Eigen::Vector3d mwd_angular_velocity_b(const MwdAttitude& attitude, double inclination_rate_radps,
                                       double toolface_rate_radps, double azimuth_rate_radps) {
  // C = R_z(-A) R_x(I) C_0 R_z(TF): each factor's rate, carried into b by the factors after it.
  const Eigen::Matrix3d r_tf_t = rotation_z(attitude.toolface_rad).transpose();
  const Eigen::Matrix3d c0_t = vertical_reference().transpose();
  const Eigen::Matrix3d r_i_t = rotation_x(attitude.inclination_rad).transpose();
  return r_tf_t * c0_t *
             (r_i_t * Eigen::Vector3d::UnitZ() * (-azimuth_rate_radps) +
              Eigen::Vector3d::UnitX() * inclination_rate_radps) +
         Eigen::Vector3d::UnitZ() * toolface_rate_radps;
}

}  // namespace stochnav
