#pragma once
// Degrees and radians: the one definition of the conversion factors (configs and reports are in
// degrees, the maths in radians).

#include <numbers>

namespace stochnav {

inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;  ///< radians in one degree
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;  ///< degrees in one radian

}  // namespace stochnav
