#pragma once
// The navigation state shared by the scenario simulator, the strapdown INS, the filter and the
// aiding plugins, and the frames it is written in.
//
// Frames:
//   n  local-level navigation frame ENU: x East, y North, z Up, at the current position.
//   b  tool (body) frame of the MWD tool: z along the tool axis, pointing down the hole (towards
//      the bit); x towards the tool's reference mark (toolface zero); y = z x x (right-handed).
//   e  Earth-centred Earth-fixed (WGS-84), i inertial.
// Rotations: C_nb maps a vector from b to n (v_n = C_nb v_b); q_nb is the same rotation as a
// unit quaternion (Eigen's Hamilton convention).
// MWD attitude (ins/mwd_attitude.hpp): inclination is the angle between the tool axis z_b and
// the local vertical down (0 vertical, pi/2 horizontal); azimuth is the direction of the tool
// axis' horizontal projection, clockwise from North towards East; toolface is the high-side
// toolface, the angle about the tool axis from the high side to x_b.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace stochnav {

struct NavState {
  double t_s = 0.0;             ///< time (s)
  double latitude_rad = 0.0;    ///< geodetic latitude, WGS-84 (rad)
  double longitude_rad = 0.0;   ///< longitude, WGS-84 (rad)
  double height_m = 0.0;        ///< height above the WGS-84 ellipsoid (m)
  Eigen::Vector3d v_n = Eigen::Vector3d::Zero();  ///< velocity relative to Earth, ENU (m/s)
  Eigen::Quaterniond q_nb = Eigen::Quaterniond::Identity();  ///< attitude, body to ENU
};

}  // namespace stochnav
