#pragma once
// Minimum curvature, the industry's standard well-path method, shared by the survey listing
// (experiment/survey.hpp) and the ISCWSA error model (survey_error/). Between stations with hole
// directions t1, t2 (unit vectors) and a measured-depth step dMD, the path is the circular arc
// tangent to both: its displacement is dMD / 2 (t1 + t2) RF, with the dogleg
// beta = angle(t1, t2) and the ratio factor RF = (2 / beta) tan(beta / 2) (1 at beta = 0).
// Frames: the directions and the step share one frame; hole_direction_nev gives (north, east,
// vertical down).

#include <Eigen/Core>
#include <cmath>

namespace stochnav {

/// Unit vector along the hole (towards the bit) in (north, east, down); angles in rad.
inline Eigen::Vector3d hole_direction_nev(double inclination_rad, double azimuth_rad) {
  return {std::sin(inclination_rad) * std::cos(azimuth_rad),
          std::sin(inclination_rad) * std::sin(azimuth_rad), std::cos(inclination_rad)};
}

/// The dogleg angle between two unit directions (rad): 2 atan2(|t2 - t1|, |t2 + t1|), equal to
/// acos(t1 . t2) but at full precision for tiny doglegs (where acos of a number close to 1 loses
/// half the digits) and never outside acos' domain through rounding.
inline double dogleg_rad(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  return 2.0 * std::atan2((to - from).norm(), (to + from).norm());
}

/// RF = (2 / beta) tan(beta / 2): the ratio of the arc to the two straight tangent halves.
inline double ratio_factor(double dogleg) {
  // 0 / 0 at beta = 0; the series 1 + beta^2 / 12 is exact to rounding below 1e-9.
  if (dogleg < 1e-9) return 1.0 + dogleg * dogleg / 12.0;
  return 2.0 / dogleg * std::tan(dogleg / 2.0);
}

/// The displacement (m, the directions' frame) from a station with direction `from` to the next,
/// `md_step_m` further along the hole, with direction `to`.
inline Eigen::Vector3d minimum_curvature_step(const Eigen::Vector3d& from,
                                              const Eigen::Vector3d& to, double md_step_m) {
  return md_step_m / 2.0 * (from + to) * ratio_factor(dogleg_rad(from, to));
}

}  // namespace stochnav
