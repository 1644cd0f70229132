#include "stochnav/core/units.hpp"

#include <array>
#include <numbers>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

struct UnitEntry {
  Unit unit;
  std::string_view name;
  Quantity quantity;
  double si_per_unit;
};

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr std::array<UnitEntry, 6> kUnits{{
    {Unit::kDegPerHour, "deg/h", Quantity::kAngularRate, kDeg / 3600.0},
    {Unit::kDegPerSecond, "deg/s", Quantity::kAngularRate, kDeg},
    {Unit::kRadPerSecond, "rad/s", Quantity::kAngularRate, 1.0},
    {Unit::kMeterPerSecondSquared, "m/s^2", Quantity::kSpecificForce, 1.0},
    {Unit::kStandardGravity, "g", Quantity::kSpecificForce, 9.80665},
    {Unit::kPlain, "plain", Quantity::kPlain, 1.0},
}};

const UnitEntry& entry(Unit unit) {
  for (const auto& e : kUnits) {
    if (e.unit == unit) return e;
  }
  return kUnits.back();
}

}  // namespace

Unit parse_unit(std::string_view text) {
  for (const auto& e : kUnits) {
    if (e.name == text) return e.unit;
  }
  throw ConfigError("unknown unit '" + std::string(text) +
                    "': use one of deg/h, deg/s, rad/s, m/s^2, g, plain");
}

std::string unit_name(Unit unit) { return std::string(entry(unit).name); }
Quantity quantity_of(Unit unit) { return entry(unit).quantity; }
double si_per_unit(Unit unit) { return entry(unit).si_per_unit; }

}  // namespace stochnav
