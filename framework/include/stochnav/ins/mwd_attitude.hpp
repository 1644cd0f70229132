#pragma once
// MWD attitude angles (inclination, high-side toolface, azimuth) and the body-to-ENU rotation
// C_nb of ins/nav_state.hpp.
//
// Construction: C_nb = R_z(-azimuth) R_x(inclination) C_0 R_z(toolface), where R_axis(angle) is
// the right-handed rotation about that axis and C_0 = [x_b = North, y_b = East, z_b = Down] is
// the vertical tool with its reference mark to the north. Hence, in n = ENU:
//   tool axis    z_b = (sin I sin A, sin I cos A, -cos I)
//   high side    h   = (cos I sin A, cos I cos A, sin I)        (d z_b / dI: "up" across the axis)
//   mark         x_b = cos(TF) h + sin(TF) (z_b x h)            (TF right-handed about z_b, i.e.
//                                                              clockwise looking down the hole)
// Ranges: inclination in [0, pi], azimuth in [0, 2 pi) clockwise from North, toolface in
// [0, 2 pi).
//
// Near vertical (sin I < kNearVerticalSin) the azimuth and the high-side toolface are undefined:
// only their sum is. mwd_from_dcm then reports azimuth = 0 and puts the whole rotation about the
// tool axis into the toolface, which becomes the gyro ("north") toolface, the angle from North
// to x_b measured as above (exactly so at I = 0). The conversion back reproduces C_nb to within
// 2 sin I < 2e-7 rad there, and exactly (to rounding) everywhere else.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace stochnav {

struct MwdAttitude {
  double inclination_rad = 0.0;  ///< angle of the tool axis from vertical down, [0, pi]
  double toolface_rad = 0.0;     ///< high-side toolface (gyro toolface near vertical), [0, 2 pi)
  double azimuth_rad = 0.0;      ///< tool-axis direction clockwise from North, [0, 2 pi)
};

/// Below this sin(inclination) the high-side toolface is replaced by the gyro toolface.
inline constexpr double kNearVerticalSin = 1e-7;

/// C_nb (body to ENU) of an MWD attitude. Any angles are accepted (no wrapping needed).
Eigen::Matrix3d dcm_from_mwd(const MwdAttitude& attitude);

/// The MWD angles of a rotation matrix C_nb (assumed orthonormal), with the near-vertical rule
/// above; toolface and azimuth wrapped to [0, 2 pi).
MwdAttitude mwd_from_dcm(const Eigen::Matrix3d& C_nb);

/// Quaternion versions of the two functions above (q_nb, Hamilton, unit norm).
Eigen::Quaterniond quaternion_from_mwd(const MwdAttitude& attitude);
MwdAttitude mwd_from_quaternion(const Eigen::Quaterniond& q_nb);

/// Body angular velocity of the rotation of b relative to n (rad/s, in b) for MWD angles
/// changing at the given rates (rad/s): omega_nb_b such that dC_nb/dt = C_nb [omega_nb_b x].
Eigen::Vector3d mwd_angular_velocity_b(const MwdAttitude& attitude, double inclination_rate_radps,
                                       double toolface_rate_radps, double azimuth_rate_radps);

/// Wraps an angle to [0, 2 pi).
double wrap_two_pi(double angle_rad);

}  // namespace stochnav
