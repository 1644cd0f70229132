#pragma once
// Declaring a plugin's parameters once. A ParamTable lists each parameter — JSON key, unit
// (with its conversion), scalar or per axis, bound, default, one line of documentation — with
// the member of the plugin's plain params struct that holds it. Reading (strict, via
// ParamReader, converted to natural SI units), writing (NoiseModelPlugin::params()), describing
// and comparing (equals()) all follow from that one list:
//
//   struct WhiteParams {
//     Axes n{};  ///< angle random walk, rad/sqrt(s) or m/s/sqrt(s)
//     Axes k{};  ///< rate random walk, rad/s/sqrt(s) or m/s^2/sqrt(s)
//   };
//   const ParamTable<WhiteParams> kWhiteTable{
//       per_axis(&WhiteParams::n, "N", ParamUnit::of(ParameterDimension::kAnglePerRootTime),
//                Bound::kNonNegative, kRequired, "angle random walk"),
//       per_axis(&WhiteParams::k, "K", ParamUnit::of(ParameterDimension::kRatePerRootTime),
//                Bound::kNonNegative, 0.0, "rate random walk of the core bias")};
//
// JSON holds reporting units (deg/h for a gyro's rate, m/s/h for an accelerometer's: the
// quantity passed in picks them), the struct natural units (rad/s, m/s^2). A per-axis value is a
// number for all three axes or [x, y, z]; params() writes it as [x, y, z]. Defaults are in
// reporting units. A table must outlive the models that use it (a namespace-scope constant).

#include <algorithm>
#include <array>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "stochnav/core/units.hpp"
#include "stochnav/plugin/param_unit.hpp"
#include "stochnav/plugin/params.hpp"

namespace stochnav::plugin {

/// The default of a parameter that must be given.
inline constexpr std::optional<double> kRequired = std::nullopt;
/// The default of an optional parameter the factory derives from others when absent: the member
/// is left NaN (in natural units) for the factory to fill in.
inline constexpr std::optional<double> kDerived = std::numeric_limits<double>::quiet_NaN();

/// One parameter of a ParamTable; build it with scalar(), per_axis() or flag().
template <class Params>
struct ParamEntry {
  using Axes = std::array<double, 3>;
  std::variant<double Params::*, Axes Params::*, bool Params::*> member;
  std::string_view name;  ///< JSON key
  ParamUnit unit = ParamUnit::fixed("");
  Bound bound = Bound::kAny;
  std::optional<double> fallback;  ///< default, reporting units (flags: 0 or 1); kRequired
  std::string_view doc;            ///< what it is, for ParamTable::documentation()
};

/// A number.
template <class Params>
ParamEntry<Params> scalar(double Params::*member, std::string_view name, ParamUnit unit,
                          Bound bound, std::optional<double> fallback, std::string_view doc) {
  return {member, name, unit, bound, fallback, doc};
}

/// A number for all three axes, or [x, y, z].
template <class Params>
ParamEntry<Params> per_axis(std::array<double, 3> Params::*member, std::string_view name,
                            ParamUnit unit, Bound bound, std::optional<double> fallback,
                            std::string_view doc) {
  return {member, name, unit, bound, fallback, doc};
}

/// true or false. Call it qualified (stochnav::plugin::flag): no argument brings it in by ADL.
template <class Params>
ParamEntry<Params> flag(bool Params::*member, std::string_view name, bool fallback,
                        std::string_view doc) {
  return {member, name, ParamUnit::fixed(""), Bound::kAny, fallback ? 1.0 : 0.0, doc};
}

/// The non-template work of ParamTable (param_table.cpp).
namespace param_table_detail {
using Axes = std::array<double, 3>;
double read_scalar(ParamReader& reader, std::string_view name, const ParamUnit& unit, Bound bound,
                   std::optional<double> fallback, Quantity quantity);
Axes read_axes(ParamReader& reader, std::string_view name, const ParamUnit& unit, Bound bound,
               std::optional<double> fallback, Quantity quantity);
nlohmann::json write_axes(const Axes& natural, const ParamUnit& unit, Quantity quantity);
/// "name = 0.05 deg/h", "name = [1, 2, 3] s" (one value when the axes agree), "name = true".
std::string describe_value(std::string_view name, std::span<const double> natural,
                           const ParamUnit& unit, Quantity quantity);
std::string describe_flag(std::string_view name, bool value);
bool close(std::span<const double> a, std::span<const double> b, double rel_tol);
/// "name: doc; unit, bound, per axis, default x" for `plugins check` and docs.
std::string document(std::string_view name, const ParamUnit& unit, Bound bound,
                     std::optional<double> fallback, bool per_axis, bool is_flag,
                     std::string_view doc, Quantity quantity);
}  // namespace param_table_detail

template <class Params>
class ParamTable {
 public:
  ParamTable(std::initializer_list<ParamEntry<Params>> entries) : entries_(entries) {}

  std::span<const ParamEntry<Params>> entries() const { return entries_; }

  /// The table without the entry `name`, e.g. for a fitter that sets that parameter itself.
  ParamTable without(std::string_view name) const {
    ParamTable rest = *this;
    std::erase_if(rest.entries_, [name](const auto& entry) { return entry.name == name; });
    return rest;
  }

  /// Reads every entry into `params` (natural units), leaving other keys to the caller, who
  /// calls reader.finish() after reading them. Throws ConfigError naming the JSON pointer.
  void read(ParamReader& reader, Quantity quantity, Params& params) const {
    for (const auto& entry : entries_) reader.expect(entry.name);
    namespace d = param_table_detail;
    for (const auto& entry : entries_) {
      if (const auto* number = std::get_if<double Params::*>(&entry.member)) {
        params.*(*number) =
            d::read_scalar(reader, entry.name, entry.unit, entry.bound, entry.fallback, quantity);
      } else if (const auto* axes = std::get_if<Axes Params::*>(&entry.member)) {
        params.*(*axes) =
            d::read_axes(reader, entry.name, entry.unit, entry.bound, entry.fallback, quantity);
      } else {
        params.*std::get<bool Params::*>(entry.member) =
            reader.boolean_or(entry.name, entry.fallback.value_or(0.0) != 0.0);
      }
    }
  }

  /// read() of a table whose units are all fixed (aids): no sensor quantity to convert for.
  void read(ParamReader& reader, Params& params) const { read(reader, Quantity::kPlain, params); }

  /// read() of a whole params object, then ParamReader::finish().
  Params parse(const nlohmann::json& json, std::string pointer, Quantity quantity) const {
    ParamReader reader(json, std::move(pointer));
    Params params;
    read(reader, quantity, params);
    reader.finish();
    return params;
  }

  /// Adds every entry of `params` to the object `out`, in reporting units.
  void write(const Params& params, Quantity quantity, nlohmann::json& out) const {
    for (const auto& entry : entries_) {
      const std::string key(entry.name);
      if (const auto* number = std::get_if<double Params::*>(&entry.member)) {
        out[key] = entry.unit.to_reported(quantity, params.*(*number));
      } else if (const auto* axes = std::get_if<Axes Params::*>(&entry.member)) {
        out[key] = param_table_detail::write_axes(params.*(*axes), entry.unit, quantity);
      } else {
        out[key] = params.*std::get<bool Params::*>(entry.member);
      }
    }
  }

  /// The params object that parse() reads back into equal params.
  nlohmann::json to_json(const Params& params, Quantity quantity) const {
    nlohmann::json out = nlohmann::json::object();
    write(params, quantity, out);
    return out;
  }

  /// "sigma = 0.5 deg/h, tau_c = [10, 20, 30] s", in table order.
  std::string describe(const Params& params, Quantity quantity) const {
    namespace d = param_table_detail;
    std::string text;
    for (const auto& entry : entries_) {
      if (!text.empty()) text += ", ";
      if (const auto* number = std::get_if<double Params::*>(&entry.member)) {
        const double value = params.*(*number);
        text += d::describe_value(entry.name, {&value, 1}, entry.unit, quantity);
      } else if (const auto* axes = std::get_if<Axes Params::*>(&entry.member)) {
        text += d::describe_value(entry.name, params.*(*axes), entry.unit, quantity);
      } else {
        text += d::describe_flag(entry.name, params.*std::get<bool Params::*>(entry.member));
      }
    }
    return text;
  }

  /// Every entry within rel_tol (parameters_close), flags equal.
  bool equal(const Params& a, const Params& b, double rel_tol) const {
    namespace d = param_table_detail;
    for (const auto& entry : entries_) {
      if (const auto* number = std::get_if<double Params::*>(&entry.member)) {
        if (!d::close({&(a.*(*number)), 1}, {&(b.*(*number)), 1}, rel_tol)) return false;
      } else if (const auto* axes = std::get_if<Axes Params::*>(&entry.member)) {
        if (!d::close(a.*(*axes), b.*(*axes), rel_tol)) return false;
      } else {
        const auto flag_member = std::get<bool Params::*>(entry.member);
        if (a.*flag_member != b.*flag_member) return false;
      }
    }
    return true;
  }

  /// One line per parameter, e.g. "tau_c: correlation time; a number > 0 (s), default 10 s".
  std::vector<std::string> documentation(Quantity quantity) const {
    std::vector<std::string> lines;
    for (const auto& entry : entries_) {
      lines.push_back(param_table_detail::document(
          entry.name, entry.unit, entry.bound, entry.fallback,
          std::holds_alternative<Axes Params::*>(entry.member),
          std::holds_alternative<bool Params::*>(entry.member), entry.doc, quantity));
    }
    return lines;
  }

 private:
  using Axes = std::array<double, 3>;
  std::vector<ParamEntry<Params>> entries_;
};

}  // namespace stochnav::plugin
