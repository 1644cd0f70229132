#pragma once
// Declaring a plugin's parameters once. A ParamTable lists each parameter — JSON key, unit
// (with its conversion), kind of value, bound, default, one line of documentation — with the
// member of the plugin's plain params struct that holds it. Reading (strict, via ParamReader,
// converted to natural SI units), writing (NoiseModelPlugin::params()), describing and comparing
// (equals()) all follow from that one list:
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
// Kinds of entries (each a function returning a ParamEntry):
//   scalar    a number                          per_axis        a number for all axes or [x, y, z]
//   flag      true or false                     integer         a whole number in [low, high]
//   choice    one name among several (enum)     choices         a non-empty array of such names
//   text      a non-empty string                series          an array of numbers (ascending,
//   axis_series  [[x...], [y...], [z...]], as long as another series   bounded, non-empty)
//   group     a nested object with its own table   axis_groups  [x, y, z] objects of one table
//   custom    a value with its own reader, writer, describer and comparison (a nested model)
// and ParamTable::plus(lift(&P::member, table)) puts another table's keys (e.g. the aids' NIS
// gate, nis_gate_table()) at the same level.
//
// JSON holds reporting units (deg/h for a gyro's rate, m/s/h for an accelerometer's: the
// quantity passed in picks them), the struct natural units (rad/s, m/s^2). A per-axis value is a
// number for all three axes or [x, y, z]; params() writes it as [x, y, z]. Defaults are in
// reporting units. A table must outlive the models that use it (a namespace-scope constant).
// Errors are ConfigErrors "<pointer>/<key>: found <value>; expected <form>" (ParamReader), a
// likely typo of a key named as such.

#include <algorithm>
#include <array>
#include <functional>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
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

/// One parameter of a ParamTable; build it with the functions below (scalar(), per_axis(), ...).
/// The operations see the whole params struct; each touches its own member only.
template <class Params>
struct ParamEntry {
  std::string_view name;  ///< JSON key
  /// Reads the key (or its default) into the params; ConfigError naming the JSON pointer.
  std::function<void(ParamReader&, Quantity, Params&)> read;
  /// The JSON value params() writes for the key (reporting units).
  std::function<nlohmann::json(const Params&, Quantity)> write;
  /// "name = value unit" for describe().
  std::function<std::string(const Params&, Quantity)> describe;
  /// Within rel_tol (parameters_close) for numbers, equal otherwise.
  std::function<bool(const Params&, const Params&, double)> equal;
  /// "doc; what a value looks like, default", for documentation().
  std::function<std::string(Quantity)> document;
};

/// The non-template work of ParamTable (param_table.cpp).
namespace param_table_detail {
using Axes = std::array<double, 3>;
double read_scalar(ParamReader& reader, std::string_view name, const ParamUnit& unit, Bound bound,
                   std::optional<double> fallback, Quantity quantity);
Axes read_axes(ParamReader& reader, std::string_view name, const ParamUnit& unit, Bound bound,
               std::optional<double> fallback, Quantity quantity);
nlohmann::json write_values(std::span<const double> natural, const ParamUnit& unit,
                            Quantity quantity);
/// "name = 0.05 deg/h", "name = [1, 2, 3] s" (one value when the axes agree), "name = true";
/// a long series as "name = [0 .. 595] s (120 values)".
std::string describe_value(std::string_view name, std::span<const double> natural,
                           const ParamUnit& unit, Quantity quantity, bool series = false);
std::string describe_text(std::string_view name, std::string_view value);
bool close(std::span<const double> a, std::span<const double> b, double rel_tol);
/// "doc; a number > 0 (deg/h), per axis (a number or [x, y, z]), default 0 deg/h".
std::string document(const ParamUnit& unit, Bound bound, std::optional<double> fallback,
                     bool per_axis, std::string_view doc, Quantity quantity);
/// "\"a\", \"b\"" of the names.
std::string quoted_names(std::span<const std::string_view> names);
int read_integer(ParamReader& reader, std::string_view name, int low, int high,
                 std::optional<int> fallback);
std::string read_text(ParamReader& reader, std::string_view name,
                      std::optional<std::string_view> fallback);
/// Index into `names` of the key's value ("found ..; expected one of ..").
std::size_t read_choice(ParamReader& reader, std::string_view name,
                        std::span<const std::string_view> names, std::size_t fallback);
/// Indices into `names` of a non-empty array of distinct names; `fallback` when absent.
std::vector<std::size_t> read_choices(ParamReader& reader, std::string_view name,
                                      std::span<const std::string_view> names,
                                      const std::vector<std::size_t>& fallback);

/// The names and the values of a choice's options.
template <class Value>
std::pair<std::vector<std::string_view>, std::vector<Value>> split(
    std::initializer_list<std::pair<std::string_view, Value>> options) {
  std::pair<std::vector<std::string_view>, std::vector<Value>> split;
  for (const auto& [option, value] : options) {
    split.first.push_back(option);
    split.second.push_back(value);
  }
  return split;
}

/// How a series is checked.
struct SeriesRule {
  Bound bound = Bound::kAny;
  std::size_t min_size = 1;  ///< 0: may be empty
  bool ascending = false;    ///< strictly ascending
  bool required = true;      ///< else absent reads as []
};
std::vector<double> read_series(ParamReader& reader, std::string_view name, const ParamUnit& unit,
                                const SeriesRule& rule, Quantity quantity);
std::array<std::vector<double>, 3> read_axis_series(ParamReader& reader, std::string_view name,
                                                    const ParamUnit& unit, Bound bound,
                                                    std::size_t count, std::string_view count_of,
                                                    Quantity quantity);
/// The JSON of a required key, or a ConfigError ("missing", or a likely typo of it).
const nlohmann::json& required_value(ParamReader& reader, std::string_view name,
                                     const std::string& expected);
/// A ConfigError "<pointer>: found <value>; expected <expected>".
[[noreturn]] void reject(const std::string& pointer, const nlohmann::json& found,
                         std::string_view expected);
}  // namespace param_table_detail

using param_table_detail::SeriesRule;

template <class Params>
class ParamTable {
 public:
  ParamTable() = default;
  ParamTable(std::initializer_list<ParamEntry<Params>> entries) : entries_(entries) {}

  std::span<const ParamEntry<Params>> entries() const { return entries_; }

  /// The table without the entry `name`, e.g. for a fitter that sets that parameter itself.
  ParamTable without(std::string_view name) const {
    ParamTable rest = *this;
    std::erase_if(rest.entries_, [name](const auto& entry) { return entry.name == name; });
    return rest;
  }

  /// The table followed by the entries of `more` (e.g. lift(&P::gate, nis_gate_table())).
  ParamTable plus(const ParamTable& more) const {
    ParamTable all = *this;
    all.entries_.insert(all.entries_.end(), more.entries_.begin(), more.entries_.end());
    return all;
  }

  /// Reads every entry into `params` (natural units), in table order, leaving other keys to the
  /// caller, who calls reader.finish() after reading them. Throws ConfigError naming the JSON
  /// pointer.
  void read(ParamReader& reader, Quantity quantity, Params& params) const {
    for (const auto& entry : entries_) reader.expect(entry.name);
    for (const auto& entry : entries_) entry.read(reader, quantity, params);
  }

  /// read() of a table whose units are all fixed (aids, fit options): no sensor quantity.
  void read(ParamReader& reader, Params& params) const { read(reader, Quantity::kPlain, params); }

  /// read() of a whole params object into `params` (members not in the table kept), then
  /// ParamReader::finish().
  void parse_into(const nlohmann::json& json, std::string pointer, Quantity quantity,
                  Params& params) const {
    ParamReader reader(json, std::move(pointer));
    read(reader, quantity, params);
    reader.finish();
  }

  /// parse_into() default-constructed params.
  Params parse(const nlohmann::json& json, std::string pointer,
               Quantity quantity = Quantity::kPlain) const {
    Params params{};
    parse_into(json, std::move(pointer), quantity, params);
    return params;
  }

  /// Adds every entry of `params` to the object `out`, in reporting units.
  void write(const Params& params, Quantity quantity, nlohmann::json& out) const {
    for (const auto& entry : entries_) out[std::string(entry.name)] = entry.write(params, quantity);
  }

  /// The params object that parse() reads back into equal params.
  nlohmann::json to_json(const Params& params, Quantity quantity = Quantity::kPlain) const {
    nlohmann::json out = nlohmann::json::object();
    write(params, quantity, out);
    return out;
  }

  /// "sigma = 0.5 deg/h, tau_c = [10, 20, 30] s", in table order.
  std::string describe(const Params& params, Quantity quantity = Quantity::kPlain) const {
    std::string text;
    for (const auto& entry : entries_) {
      if (!text.empty()) text += ", ";
      text += entry.describe(params, quantity);
    }
    return text;
  }

  /// Every entry within rel_tol (parameters_close), other values equal.
  bool equal(const Params& a, const Params& b, double rel_tol) const {
    return std::all_of(entries_.begin(), entries_.end(),
                       [&](const auto& entry) { return entry.equal(a, b, rel_tol); });
  }

  /// One line per parameter, e.g. "tau_c: correlation time; a number > 0 (s), default 10 s".
  std::vector<std::string> documentation(Quantity quantity = Quantity::kPlain) const {
    std::vector<std::string> lines;
    for (const auto& entry : entries_) {
      lines.push_back(std::string(entry.name) + ": " + entry.document(quantity));
    }
    return lines;
  }

 private:
  std::vector<ParamEntry<Params>> entries_;
};

// ---- numbers ----------------------------------------------------------------------------------

/// A number.
template <class Params>
ParamEntry<Params> scalar(double Params::*member, std::string_view name, ParamUnit unit,
                          Bound bound, std::optional<double> fallback, std::string_view doc) {
  namespace d = param_table_detail;
  return {
      name,
      [=](ParamReader& reader, Quantity q, Params& p) {
        p.*member = d::read_scalar(reader, name, unit, bound, fallback, q);
      },
      [=](const Params& p, Quantity q) -> nlohmann::json { return unit.to_reported(q, p.*member); },
      [=](const Params& p, Quantity q) {
        return d::describe_value(name, {&(p.*member), 1}, unit, q);
      },
      [=](const Params& a, const Params& b, double tol) {
        return d::close({&(a.*member), 1}, {&(b.*member), 1}, tol);
      },
      [=](Quantity q) { return d::document(unit, bound, fallback, false, doc, q); }};
}

/// A number for all three axes, or [x, y, z].
template <class Params>
ParamEntry<Params> per_axis(std::array<double, 3> Params::*member, std::string_view name,
                            ParamUnit unit, Bound bound, std::optional<double> fallback,
                            std::string_view doc) {
  namespace d = param_table_detail;
  return {name,
          [=](ParamReader& reader, Quantity q, Params& p) {
            p.*member = d::read_axes(reader, name, unit, bound, fallback, q);
          },
          [=](const Params& p, Quantity q) { return d::write_values(p.*member, unit, q); },
          [=](const Params& p, Quantity q) { return d::describe_value(name, p.*member, unit, q); },
          [=](const Params& a, const Params& b, double tol) {
            return d::close(a.*member, b.*member, tol);
          },
          [=](Quantity q) { return d::document(unit, bound, fallback, true, doc, q); }};
}

/// A whole number in [low, high]; fallback std::nullopt: required.
template <class Params>
ParamEntry<Params> integer(int Params::*member, std::string_view name, int low, int high,
                           std::optional<int> fallback, std::string_view doc) {
  namespace d = param_table_detail;
  return {
      name,
      [=](ParamReader& reader, Quantity, Params& p) {
        p.*member = d::read_integer(reader, name, low, high, fallback);
      },
      [=](const Params& p, Quantity) -> nlohmann::json { return p.*member; },
      [=](const Params& p, Quantity) { return d::describe_text(name, std::to_string(p.*member)); },
      [=](const Params& a, const Params& b, double) { return a.*member == b.*member; },
      [=](Quantity) {
        return std::string(doc) + "; an integer in [" + std::to_string(low) + ", " +
               std::to_string(high) + "]" +
               (fallback ? ", default " + std::to_string(*fallback) : ", required");
      }};
}

/// An array of numbers (each within rule.bound, converted like a scalar), e.g. analysis times.
template <class Params>
ParamEntry<Params> series(std::vector<double> Params::*member, std::string_view name,
                          ParamUnit unit, SeriesRule rule, std::string_view doc) {
  namespace d = param_table_detail;
  return {name,
          [=](ParamReader& reader, Quantity q, Params& p) {
            p.*member = d::read_series(reader, name, unit, rule, q);
          },
          [=](const Params& p, Quantity q) { return d::write_values(p.*member, unit, q); },
          [=](const Params& p, Quantity q) {
            return d::describe_value(name, p.*member, unit, q, true);
          },
          [=](const Params& a, const Params& b, double tol) {
            return (a.*member).size() == (b.*member).size() && d::close(a.*member, b.*member, tol);
          },
          [=](Quantity q) {
            return std::string(doc) +
                   (rule.ascending ? "; an ascending array of " : "; an array of ") +
                   bound_description(rule.bound, unit.name(q)) +
                   (rule.required ? ", required" : ", default []");
          }};
}

/// [[x...], [y...], [z...]]: per axis, one number per value of the series `length_of` (an entry
/// read before this one), e.g. N at each analysis time.
template <class Params>
ParamEntry<Params> axis_series(std::array<std::vector<double>, 3> Params::*member,
                               std::string_view name, ParamUnit unit, Bound bound,
                               std::vector<double> Params::*length_of, std::string_view length_name,
                               std::string_view doc) {
  namespace d = param_table_detail;
  return {name,
          [=](ParamReader& reader, Quantity q, Params& p) {
            p.*member = d::read_axis_series(reader, name, unit, bound, (p.*length_of).size(),
                                            length_name, q);
          },
          [=](const Params& p, Quantity q) {
            nlohmann::json axes = nlohmann::json::array();
            for (const auto& values : p.*member) axes.push_back(d::write_values(values, unit, q));
            return axes;
          },
          [=](const Params& p, Quantity q) {
            std::string text;
            const char* axis_names[] = {"x", "y", "z"};
            for (std::size_t axis = 0; axis < 3; ++axis) {
              text += (axis == 0 ? "" : ", ") +
                      d::describe_value(std::string(name) + " " + axis_names[axis],
                                        (p.*member)[axis], unit, q, true);
            }
            return text;
          },
          [=](const Params& a, const Params& b, double tol) {
            for (std::size_t axis = 0; axis < 3; ++axis) {
              if ((a.*member)[axis].size() != (b.*member)[axis].size() ||
                  !d::close((a.*member)[axis], (b.*member)[axis], tol)) {
                return false;
              }
            }
            return true;
          },
          [=](Quantity q) {
            return std::string(doc) + "; [[x...], [y...], [z...]] of " +
                   bound_description(bound, unit.name(q)) + ", one per value of " +
                   std::string(length_name) + ", required";
          }};
}

// ---- names, flags and strings -------------------------------------------------------------------

/// true or false. Call it qualified (stochnav::plugin::flag): no argument brings it in by ADL.
template <class Params>
ParamEntry<Params> flag(bool Params::*member, std::string_view name, bool fallback,
                        std::string_view doc) {
  namespace d = param_table_detail;
  return {name,
          [=](ParamReader& reader, Quantity, Params& p) {
            p.*member = reader.boolean_or(name, fallback);
          },
          [=](const Params& p, Quantity) -> nlohmann::json { return p.*member; },
          [=](const Params& p, Quantity) {
            return d::describe_text(name, p.*member ? "true" : "false");
          },
          [=](const Params& a, const Params& b, double) { return a.*member == b.*member; },
          [=](Quantity) {
            return std::string(doc) + "; true or false, default " + (fallback ? "true" : "false");
          }};
}

/// The value of a name among `options` ({"burg", ArMethod::kBurg}, ...): an enum in the struct,
/// its name in JSON.
template <class Params, class Value>
ParamEntry<Params> choice(Value Params::*member, std::string_view name,
                          std::initializer_list<std::pair<std::string_view, Value>> options,
                          Value fallback, std::string_view doc) {
  namespace d = param_table_detail;
  const auto split = d::split(options);  // (no structured bindings: clang 14 cannot capture them)
  const std::vector<std::string_view>& names = split.first;
  const std::vector<Value>& values = split.second;
  const auto index_of = [values](const Value& value) {
    return static_cast<std::size_t>(std::find(values.begin(), values.end(), value) -
                                    values.begin());
  };
  const std::size_t fallback_index = index_of(fallback);
  return {
      name,
      [=](ParamReader& reader, Quantity, Params& p) {
        p.*member = values[d::read_choice(reader, name, names, fallback_index)];
      },
      [=](const Params& p, Quantity) -> nlohmann::json {
        return std::string(names[index_of(p.*member)]);
      },
      [=](const Params& p, Quantity) { return d::describe_text(name, names[index_of(p.*member)]); },
      [=](const Params& a, const Params& b, double) { return a.*member == b.*member; },
      [=](Quantity) {
        return std::string(doc) + "; one of " + d::quoted_names(names) + ", default \"" +
               std::string(names[fallback_index]) + "\"";
      }};
}

/// A non-empty array of distinct names among `options`; `fallback` when absent.
template <class Params, class Value>
ParamEntry<Params> choices(std::vector<Value> Params::*member, std::string_view name,
                           std::initializer_list<std::pair<std::string_view, Value>> options,
                           std::vector<Value> fallback, std::string_view doc) {
  namespace d = param_table_detail;
  const auto split = d::split(options);  // (no structured bindings: clang 14 cannot capture them)
  const std::vector<std::string_view>& names = split.first;
  const std::vector<Value>& values = split.second;
  const auto indices_of = [values](const std::vector<Value>& chosen) {
    std::vector<std::size_t> indices;
    for (const Value& value : chosen) {
      indices.push_back(static_cast<std::size_t>(std::find(values.begin(), values.end(), value) -
                                                 values.begin()));
    }
    return indices;
  };
  const auto names_of = [names, indices_of](const std::vector<Value>& chosen) {
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t index : indices_of(chosen)) out.push_back(std::string(names[index]));
    return out;
  };
  const std::vector<std::size_t> fallback_indices = indices_of(fallback);
  return {
      name,
      [=](ParamReader& reader, Quantity, Params& p) {
        std::vector<Value> chosen;
        for (std::size_t index : d::read_choices(reader, name, names, fallback_indices)) {
          chosen.push_back(values[index]);
        }
        p.*member = std::move(chosen);
      },
      [=](const Params& p, Quantity) { return names_of(p.*member); },
      [=](const Params& p, Quantity) { return d::describe_text(name, names_of(p.*member).dump()); },
      [=](const Params& a, const Params& b, double) { return a.*member == b.*member; },
      [=](Quantity) {
        return std::string(doc) + "; an array of distinct names among " + d::quoted_names(names) +
               ", default " + names_of(fallback).dump();
      }};
}

/// A non-empty string; fallback std::nullopt: required.
template <class Params>
ParamEntry<Params> text(std::string Params::*member, std::string_view name,
                        std::optional<std::string_view> fallback, std::string_view doc) {
  namespace d = param_table_detail;
  return {name,
          [=](ParamReader& reader, Quantity, Params& p) {
            p.*member = d::read_text(reader, name, fallback);
          },
          [=](const Params& p, Quantity) -> nlohmann::json { return p.*member; },
          [=](const Params& p, Quantity) {
            return d::describe_text(name, nlohmann::json(p.*member).dump());
          },
          [=](const Params& a, const Params& b, double) { return a.*member == b.*member; },
          [=](Quantity) {
            return std::string(doc) + "; a non-empty string" +
                   (fallback ? ", default \"" + std::string(*fallback) + "\"" : ", required");
          }};
}

// ---- nested objects -----------------------------------------------------------------------------

/// What a group does when its key is absent.
enum class Absent {
  kDefaults,  ///< read as {}: every entry of the group takes its default
  kKeep,      ///< the member is left as it was (the factory set it before reading)
};

/// A nested object read with its own table: {"site": {"latitude_deg": ..}}. `table` must outlive
/// this table (a namespace-scope constant).
template <class Params, class Group>
ParamEntry<Params> group(Group Params::*member, std::string_view name,
                         const ParamTable<Group>& table, Absent absent, std::string_view doc) {
  const ParamTable<Group>* sub = &table;
  return {name,
          [=](ParamReader& reader, Quantity q, Params& p) {
            if (absent == Absent::kKeep && !reader.has(name)) return;
            const nlohmann::json& json = reader.raw(name);
            sub->parse_into(json, reader.pointer(name), q, p.*member);
          },
          [=](const Params& p, Quantity q) { return sub->to_json(p.*member, q); },
          [=](const Params& p, Quantity q) {
            return std::string(name) + " = {" + sub->describe(p.*member, q) + "}";
          },
          [=](const Params& a, const Params& b, double tol) {
            return sub->equal(a.*member, b.*member, tol);
          },
          [=](Quantity q) {
            std::string text = std::string(doc) + "; an object {";
            for (const std::string& line : sub->documentation(q)) {
              text += (text.back() == '{' ? "" : "; ") + line;
            }
            return text + (absent == Absent::kKeep ? "}, optional" : "}");
          }};
}

/// A required array of three objects [x, y, z], each read with `table`: per-axis models.
template <class Params, class Group>
ParamEntry<Params> axis_groups(std::array<Group, 3> Params::*member, std::string_view name,
                               const ParamTable<Group>& table, std::string_view doc) {
  namespace d = param_table_detail;
  const ParamTable<Group>* sub = &table;
  return {name,
          [=](ParamReader& reader, Quantity q, Params& p) {
            const std::string expected = "an array of 3 objects [x, y, z]";
            const nlohmann::json& json = d::required_value(reader, name, expected);
            if (!json.is_array() || json.size() != 3)
              d::reject(reader.pointer(name), json, expected);
            for (std::size_t axis = 0; axis < 3; ++axis) {
              sub->parse_into(json[axis], reader.pointer(name) + "/" + std::to_string(axis), q,
                              (p.*member)[axis]);
            }
          },
          [=](const Params& p, Quantity q) {
            nlohmann::json axes = nlohmann::json::array();
            for (const Group& axis : p.*member) axes.push_back(sub->to_json(axis, q));
            return axes;
          },
          [=](const Params& p, Quantity q) {
            std::string text = std::string(name) + " = [";
            const char* axis_names[] = {"x", "y", "z"};
            for (std::size_t axis = 0; axis < 3; ++axis) {
              text += std::string(axis == 0 ? "" : ", ") + axis_names[axis] + ": {" +
                      sub->describe((p.*member)[axis], q) + "}";
            }
            return text + "]";
          },
          [=](const Params& a, const Params& b, double tol) {
            for (std::size_t axis = 0; axis < 3; ++axis) {
              if (!sub->equal((a.*member)[axis], (b.*member)[axis], tol)) return false;
            }
            return true;
          },
          [=](Quantity q) {
            std::string text = std::string(doc) + "; an array of 3 objects [x, y, z] of {";
            for (const std::string& line : sub->documentation(q)) {
              text += (text.back() == '{' ? "" : "; ") + line;
            }
            return text + "}, required";
          }};
}

/// The entries of `table`, reading into the member `member`, for ParamTable::plus: another
/// table's keys at the same level (the NIS gate keys of every aid).
template <class Params, class Group>
ParamTable<Params> lift(Group Params::*member, const ParamTable<Group>& table) {
  ParamTable<Params> lifted;
  for (const ParamEntry<Group>& entry : table.entries()) {
    lifted = lifted.plus(ParamTable<Params>{ParamEntry<Params>{
        entry.name,
        [=, read = entry.read](ParamReader& reader, Quantity q, Params& p) {
          read(reader, q, p.*member);
        },
        [=, write = entry.write](const Params& p, Quantity q) { return write(p.*member, q); },
        [=, describe = entry.describe](const Params& p, Quantity q) {
          return describe(p.*member, q);
        },
        [=, equal = entry.equal](const Params& a, const Params& b, double tol) {
          return equal(a.*member, b.*member, tol);
        },
        entry.document}});
  }
  return lifted;
}

/// How a custom value (a nested noise model, ...) is read, written, described and compared.
template <class Value>
struct ValueCodec {
  std::function<Value(ParamReader& reader, Quantity)> read;  ///< reads the key(s) it needs
  std::function<nlohmann::json(const Value&, Quantity)> write;
  std::function<std::string(const Value&, Quantity)> describe;  ///< the value, without the name
  std::function<bool(const Value&, const Value&, double)> equal;
  std::string_view form;  ///< what a value looks like, for documentation()
};

/// A value with its own codec.
template <class Params, class Value>
ParamEntry<Params> custom(Value Params::*member, std::string_view name, ValueCodec<Value> codec,
                          std::string_view doc) {
  return {name,
          [=](ParamReader& reader, Quantity q, Params& p) { p.*member = codec.read(reader, q); },
          [=](const Params& p, Quantity q) { return codec.write(p.*member, q); },
          [=](const Params& p, Quantity q) {
            return std::string(name) + " = " + codec.describe(p.*member, q);
          },
          [=](const Params& a, const Params& b, double tol) {
            return codec.equal(a.*member, b.*member, tol);
          },
          [=](Quantity) { return std::string(doc) + "; " + std::string(codec.form); }};
}

}  // namespace stochnav::plugin
