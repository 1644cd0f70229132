#include "stochnav/model/reporting_units.hpp"

#include <cmath>

#include "stochnav/core/angles.hpp"

namespace stochnav {
namespace {

constexpr double kSecondsPerHour = 3600.0;
constexpr double kRootSecondsPerHour = 60.0;  // sqrt(3600 s)

// The reporting "angle" unit in natural units: deg -> rad for gyros, m/s for accelerometers.
double angle_unit(Quantity quantity) {
  switch (quantity) {
    case Quantity::kAngularRate:
      return kRadPerDeg;
    case Quantity::kSpecificForce:
    case Quantity::kPlain:
      return 1.0;
  }
  return 1.0;
}

}  // namespace

double natural_per_reported(Quantity quantity, ParameterDimension dimension) {
  switch (dimension) {
    case ParameterDimension::kTime:
    case ParameterDimension::kFrequency:
    case ParameterDimension::kPhase:
    case ParameterDimension::kChannel:
      return 1.0;
    default:
      break;
  }
  if (quantity == Quantity::kPlain) return 1.0;
  const double angle = angle_unit(quantity);
  switch (dimension) {
    case ParameterDimension::kAngle:  // arcsec -> rad; m/s -> m/s
      return quantity == Quantity::kAngularRate ? angle / kSecondsPerHour : angle;
    case ParameterDimension::kAnglePerRootTime:  // deg/sqrt(h) -> rad/sqrt(s)
      return angle / kRootSecondsPerHour;
    case ParameterDimension::kRate:  // deg/h -> rad/s
      return angle / kSecondsPerHour;
    case ParameterDimension::kRatePerRootTime:  // deg/h/sqrt(h) -> rad/s/sqrt(s)
      return angle / (kSecondsPerHour * kRootSecondsPerHour);
    case ParameterDimension::kRatePerTime:  // deg/h^2 -> rad/s^2
      return angle / (kSecondsPerHour * kSecondsPerHour);
    default:
      return 1.0;
  }
}

std::string reported_unit_name(Quantity quantity, ParameterDimension dimension) {
  switch (dimension) {
    case ParameterDimension::kTime:
      return "s";
    case ParameterDimension::kFrequency:
      return "Hz";
    case ParameterDimension::kPhase:
      return "rad";
    case ParameterDimension::kChannel:
      return "channel unit";
    default:
      break;
  }
  if (quantity == Quantity::kPlain) {
    switch (dimension) {
      case ParameterDimension::kAngle:
        return "signal*s";
      case ParameterDimension::kAnglePerRootTime:
        return "signal*sqrt(s)";
      case ParameterDimension::kRate:
        return "signal";
      case ParameterDimension::kRatePerRootTime:
        return "signal/sqrt(s)";
      default:
        return "signal/s";
    }
  }
  const bool gyro = quantity == Quantity::kAngularRate;
  const std::string angle = gyro ? "deg" : "m/s";
  switch (dimension) {
    case ParameterDimension::kAngle:
      return gyro ? "arcsec" : "m/s";
    case ParameterDimension::kAnglePerRootTime:
      return angle + "/sqrt(h)";
    case ParameterDimension::kRate:
      return angle + "/h";
    case ParameterDimension::kRatePerRootTime:
      return angle + "/h/sqrt(h)";
    default:
      return angle + "/h^2";
  }
}

double to_reported(Quantity quantity, ParameterDimension dimension, double value_natural) {
  return value_natural / natural_per_reported(quantity, dimension);
}

double to_natural(Quantity quantity, ParameterDimension dimension, double value_reported) {
  return value_reported * natural_per_reported(quantity, dimension);
}

}  // namespace stochnav
