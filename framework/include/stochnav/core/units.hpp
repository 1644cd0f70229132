#pragma once
// Units of a rate signal and the conversions between them.
//
// Internally stochnav works in SI: a gyro signal in rad/s, an accelerometer signal in m/s^2.
// Plain (dimensionless) data, such as fractional frequency of a clock, is left as it is.
// Noise-term coefficients are reported in the IEEE 952 units of DESIGN.md: for angular rates
// (Q arcsec, N deg/sqrt(h), B deg/h, K deg/h/sqrt(h), R deg/h^2); for specific force the same
// pattern with m/s in place of deg; for plain data the natural units of the signal (Q in
// signal*s, N in signal*sqrt(s), B in signal, K in signal/sqrt(s), R in signal/s).

#include <string>
#include <string_view>

namespace stochnav {

enum class Unit {
  kDegPerHour,    ///< deg/h (gyro, IEEE 952 reporting unit)
  kDegPerSecond,  ///< deg/s
  kRadPerSecond,  ///< rad/s (SI)
  kMeterPerSecondSquared,  ///< m/s^2 (SI specific force)
  kStandardGravity,        ///< g = 9.80665 m/s^2
  kPlain,                  ///< dimensionless or unknown: no conversion
};

enum class Quantity { kAngularRate, kSpecificForce, kPlain };

/// Parses "deg/h", "deg/s", "rad/s", "m/s^2", "g" or "plain". Throws ConfigError otherwise.
Unit parse_unit(std::string_view text);

/// The spelling parse_unit accepts for `unit`.
std::string unit_name(Unit unit);

/// What the unit measures.
Quantity quantity_of(Unit unit);

/// Factor f such that value_si = f * value_in_unit (SI: rad/s, m/s^2; plain: 1).
double si_per_unit(Unit unit);

}  // namespace stochnav
