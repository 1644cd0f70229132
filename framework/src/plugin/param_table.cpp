#include "stochnav/plugin/param_table.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "stochnav/plugin/noise_model_plugin.hpp"

namespace stochnav::plugin::param_table_detail {
namespace {

std::string with_unit(std::string text, const std::string& unit) {
  return unit.empty() ? text : text + " " + unit;
}

}  // namespace

double read_scalar(ParamReader& reader, std::string_view name, const ParamUnit& unit, Bound bound,
                   std::optional<double> fallback, Quantity quantity) {
  const std::string unit_name = unit.name(quantity);
  const double reported = fallback ? reader.number_or(name, *fallback, bound, unit_name)
                                   : reader.number(name, bound, unit_name);
  return unit.to_natural(quantity, reported);
}

Axes read_axes(ParamReader& reader, std::string_view name, const ParamUnit& unit, Bound bound,
               std::optional<double> fallback, Quantity quantity) {
  const std::string unit_name = unit.name(quantity);
  Axes values = fallback ? reader.axes_or(name, {*fallback, *fallback, *fallback}, bound, unit_name)
                         : reader.axes(name, bound, unit_name);
  for (double& value : values) value = unit.to_natural(quantity, value);
  return values;
}

nlohmann::json write_axes(const Axes& natural, const ParamUnit& unit, Quantity quantity) {
  nlohmann::json values = nlohmann::json::array();
  for (double value : natural) values.push_back(unit.to_reported(quantity, value));
  return values;
}

std::string describe_value(std::string_view name, std::span<const double> natural,
                           const ParamUnit& unit, Quantity quantity) {
  std::vector<double> reported;
  for (double value : natural) reported.push_back(unit.to_reported(quantity, value));
  const bool uniform = std::all_of(reported.begin(), reported.end(),
                                   [&](double value) { return value == reported.front(); });
  const std::string values = uniform ? fmt::format("{:.6g}", reported.front())
                                     : fmt::format("[{:.6g}]", fmt::join(reported, ", "));
  return with_unit(fmt::format("{} = {}", name, values), unit.name(quantity));
}

std::string describe_flag(std::string_view name, bool value) {
  return fmt::format("{} = {}", name, value);
}

bool close(std::span<const double> a, std::span<const double> b, double rel_tol) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!parameters_close(a[i], b[i], rel_tol)) return false;
  }
  return true;
}

std::string document(std::string_view name, const ParamUnit& unit, Bound bound,
                     std::optional<double> fallback, bool per_axis, bool is_flag,
                     std::string_view doc, Quantity quantity) {
  std::string text = fmt::format("{}: {}; ", name, doc);
  if (is_flag) {
    return text + fmt::format("true or false, default {}", fallback.value_or(0.0) != 0.0);
  }
  text += bound_description(bound, unit.name(quantity));
  if (per_axis) text += ", per axis (a number or [x, y, z])";
  if (!fallback) return text + ", required";
  if (std::isnan(*fallback)) return text + ", default derived from the others";
  return text + with_unit(fmt::format(", default {:.6g}", *fallback), unit.name(quantity));
}

}  // namespace stochnav::plugin::param_table_detail
