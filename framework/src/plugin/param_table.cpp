#include "stochnav/plugin/param_table.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"

namespace stochnav::plugin::param_table_detail {
namespace {

std::string with_unit(std::string text, const std::string& unit) {
  return unit.empty() ? text : text + " " + unit;
}

/// A series shown in full up to this many values, else as its first and last.
constexpr std::size_t kShownValues = 6;

}  // namespace

void reject(const std::string& pointer, const nlohmann::json& found, std::string_view expected) {
  std::string shown = found.dump();
  if (shown.size() > 40) shown = shown.substr(0, 37) + "...";
  throw ConfigError(fmt::format("{}: found {}; expected {}", pointer, shown, expected));
}

const nlohmann::json& required_value(ParamReader& reader, std::string_view name,
                                     const std::string& expected) {
  return reader.required(name, expected);
}

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

int read_integer(ParamReader& reader, std::string_view name, int low, int high,
                 std::optional<int> fallback) {
  const std::string expected = fmt::format("an integer in [{}, {}]", low, high);
  if (!reader.has(name)) {
    if (fallback) return *fallback;
    required_value(reader, name, expected);
  }
  const double value = reader.number(name, Bound::kAny, "");
  if (value != std::round(value) || value < low || value > high) {
    reject(reader.pointer(name), nlohmann::json(value), expected);
  }
  return static_cast<int>(value);
}

std::string read_text(ParamReader& reader, std::string_view name,
                      std::optional<std::string_view> fallback) {
  // An empty default stands for "derived by the factory": params() may write it back.
  if (fallback && fallback->empty() && reader.raw(name) == "") return "";
  return fallback ? reader.text_or(name, *fallback) : reader.text(name);
}

std::size_t read_choice(ParamReader& reader, std::string_view name,
                        std::span<const std::string_view> names, std::size_t fallback) {
  const std::string chosen = reader.choice_or(name, names[fallback], names);
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), chosen) - names.begin());
}

std::vector<std::size_t> read_choices(ParamReader& reader, std::string_view name,
                                      std::span<const std::string_view> names,
                                      const std::vector<std::size_t>& fallback) {
  if (!reader.has(name)) return fallback;
  const nlohmann::json& json = reader.raw(name);
  const std::string pointer = reader.pointer(name);
  const std::string expected = "an array of distinct names among " + quoted_names(names);
  if (!json.is_array() || json.empty()) reject(pointer, json, expected);
  std::vector<std::size_t> chosen;
  for (std::size_t j = 0; j < json.size(); ++j) {
    const std::string item = json[j].is_string() ? json[j].get<std::string>() : "";
    const auto index =
        static_cast<std::size_t>(std::find(names.begin(), names.end(), item) - names.begin());
    if (index == names.size() || std::find(chosen.begin(), chosen.end(), index) != chosen.end()) {
      reject(pointer + "/" + std::to_string(j), json[j], expected);
    }
    chosen.push_back(index);
  }
  return chosen;
}

std::vector<double> read_series(ParamReader& reader, std::string_view name, const ParamUnit& unit,
                                const SeriesRule& rule, Quantity quantity) {
  const std::string unit_name = unit.name(quantity);
  const std::string item = bound_description(rule.bound, unit_name);
  const std::string expected = fmt::format(
      "{} array ({}each {})", rule.ascending ? "an ascending" : "an",
      rule.min_size > 0
          ? fmt::format("at least {} value{}; ", rule.min_size, rule.min_size == 1 ? "" : "s")
          : "",
      item);
  if (!rule.required && !reader.has(name)) return {};
  const nlohmann::json& json = required_value(reader, name, expected);
  const std::string pointer = reader.pointer(name);
  if (!json.is_array() || json.size() < rule.min_size) reject(pointer, json, expected);
  std::vector<double> values;
  for (std::size_t j = 0; j < json.size(); ++j) {
    const auto& value = json[j];
    if (!value.is_number() || !within_bound(rule.bound, value.get<double>()) ||
        (rule.ascending && j > 0 && !(value.get<double>() > json[j - 1].get<double>()))) {
      reject(pointer + "/" + std::to_string(j), value,
             rule.ascending ? item + " greater than the one before" : item);
    }
    values.push_back(unit.to_natural(quantity, value.get<double>()));
  }
  return values;
}

std::array<std::vector<double>, 3> read_axis_series(ParamReader& reader, std::string_view name,
                                                    const ParamUnit& unit, Bound bound,
                                                    std::size_t count, std::string_view count_of,
                                                    Quantity quantity) {
  const std::string unit_name = unit.name(quantity);
  const nlohmann::json& json = required_value(
      reader, name,
      fmt::format("[[x...], [y...], [z...]], {} values ({}) per axis", count, unit_name));
  const std::string pointer = reader.pointer(name);
  if (!json.is_array() || json.size() != 3) {
    reject(pointer, json,
           fmt::format("[[x...], [y...], [z...]], {} values of {} ({}) per axis", count, name,
                       unit_name));
  }
  std::array<std::vector<double>, 3> series;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const auto& values = json[axis];
    const std::string axis_pointer = pointer + "/" + std::to_string(axis);
    if (!values.is_array() || values.size() != count) {
      reject(axis_pointer, values,
             fmt::format("an array of {} values (one per value of {})", count,
                         reader.pointer(count_of)));
    }
    for (std::size_t j = 0; j < count; ++j) {
      const auto& value = values[j];
      if (!value.is_number() || !within_bound(bound, value.get<double>())) {
        reject(axis_pointer + "/" + std::to_string(j), value, bound_description(bound, unit_name));
      }
      series[axis].push_back(unit.to_natural(quantity, value.get<double>()));
    }
  }
  return series;
}

nlohmann::json write_values(std::span<const double> natural, const ParamUnit& unit,
                            Quantity quantity) {
  nlohmann::json values = nlohmann::json::array();
  for (double value : natural) values.push_back(unit.to_reported(quantity, value));
  return values;
}

std::string describe_value(std::string_view name, std::span<const double> natural,
                           const ParamUnit& unit, Quantity quantity, bool series) {
  std::vector<double> reported;
  for (double value : natural) reported.push_back(unit.to_reported(quantity, value));
  std::string values;
  if (series && reported.size() > kShownValues) {
    values = fmt::format("[{:.6g} .. {:.6g}] ({} values)", reported.front(), reported.back(),
                         reported.size());
  } else if (!series && !reported.empty() &&
             std::all_of(reported.begin(), reported.end(),
                         [&](double value) { return value == reported.front(); })) {
    values = fmt::format("{:.6g}", reported.front());
  } else {
    values = fmt::format("[{:.6g}]", fmt::join(reported, ", "));
  }
  return with_unit(fmt::format("{} = {}", name, values), unit.name(quantity));
}

std::string describe_text(std::string_view name, std::string_view value) {
  return fmt::format("{} = {}", name, value);
}

bool close(std::span<const double> a, std::span<const double> b, double rel_tol) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!parameters_close(a[i], b[i], rel_tol)) return false;
  }
  return true;
}

std::string quoted_names(std::span<const std::string_view> names) {
  std::string text;
  for (std::string_view name : names) {
    text += (text.empty() ? "\"" : ", \"") + std::string(name) + "\"";
  }
  return text;
}

std::string document(const ParamUnit& unit, Bound bound, std::optional<double> fallback,
                     bool per_axis, std::string_view doc, Quantity quantity) {
  std::string text = fmt::format("{}; ", doc);
  text += bound_description(bound, unit.name(quantity));
  if (per_axis) text += ", per axis (a number or [x, y, z])";
  if (!fallback) return text + ", required";
  if (std::isnan(*fallback)) return text + ", default derived from the others";
  return text + with_unit(fmt::format(", default {:.6g}", *fallback), unit.name(quantity));
}

}  // namespace stochnav::plugin::param_table_detail
