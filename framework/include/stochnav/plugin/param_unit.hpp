#pragma once
// The unit of one plugin parameter: what its JSON value is written in (the reporting unit) and
// how it becomes the natural SI value a model computes with.

#include <optional>
#include <string>
#include <string_view>

#include "stochnav/core/units.hpp"
#include "stochnav/model/noise_term.hpp"

namespace stochnav::plugin {

class ParamUnit {
 public:
  /// A noise-term dimension: reported in the IEEE 952 unit of the sensor's quantity
  /// (model/reporting_units.hpp: N of a gyro in deg/sqrt(h), natural rad/sqrt(s)).
  static ParamUnit of(ParameterDimension dimension);
  /// A unit that JSON and the model share, no conversion: "s", "Hz", "m", "m/s", "" for a pure
  /// number. `name` must outlive the unit (a string literal).
  static ParamUnit fixed(std::string_view name);

  /// The reporting unit's name for a sensor measuring `quantity`, e.g. "deg/h", "s", "".
  std::string name(Quantity quantity) const;
  double to_natural(Quantity quantity, double reported) const;
  double to_reported(Quantity quantity, double natural) const;

 private:
  std::optional<ParameterDimension> dimension_;
  std::string_view fixed_name_;
};

}  // namespace stochnav::plugin
