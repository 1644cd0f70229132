#include "stochnav/plugin/param_unit.hpp"

#include "stochnav/model/reporting_units.hpp"

namespace stochnav::plugin {

ParamUnit ParamUnit::of(ParameterDimension dimension) {
  ParamUnit unit;
  unit.dimension_ = dimension;
  return unit;
}

ParamUnit ParamUnit::fixed(std::string_view name) {
  ParamUnit unit;
  unit.fixed_name_ = name;
  return unit;
}

std::string ParamUnit::name(Quantity quantity) const {
  return dimension_ ? reported_unit_name(quantity, *dimension_) : std::string(fixed_name_);
}

double ParamUnit::to_natural(Quantity quantity, double reported) const {
  return dimension_ ? stochnav::to_natural(quantity, *dimension_, reported) : reported;
}

double ParamUnit::to_reported(Quantity quantity, double natural) const {
  return dimension_ ? stochnav::to_reported(quantity, *dimension_, natural) : natural;
}

}  // namespace stochnav::plugin
