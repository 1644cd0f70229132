#pragma once
// Steering a fit's parameters by name (`stochnav fit --start/--fix/--bound`, both methods): items
//   TERM[#K].PARAM=VALUE        (--start, --fix)      e.g. gauss_markov.tau_c=20
//   TERM[#K].PARAM=LOW:HIGH     (--bound)             e.g. gauss_markov#2.tau_c=5:500
// comma-separated, values in the reporting units of DESIGN.md for the record's unit (tau_c in s,
// sigma and B in deg/h for a gyro in deg/h, N in deg/sqrt(h), ...). K (1-based) picks the K-th
// term of that type in the term list; without it, the n-th mention of TERM.PARAM in one option
// refers to the n-th term of that type (so "gauss_markov.tau_c=1,gauss_markov.tau_c=100" starts
// the first Gauss-Markov term at 1 s and the second at 100 s). The plugins' fitters read the
// same names from JSON (plugin/fit_steering.hpp) through control_items_to_controls.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochnav/core/units.hpp"
#include "stochnav/fit/parameter_control.hpp"

namespace stochnav {

enum class ControlKind { kStart, kFix, kBound };

/// One named steering item, values in reporting units: one for kStart and kFix, LOW and HIGH
/// for kBound. `where` starts every message about it ("--fix 'gauss_markov.tau_c=300'", or a
/// JSON pointer).
struct ControlItem {
  ControlKind kind = ControlKind::kStart;
  std::string name;  ///< TERM[#K].PARAM
  std::vector<double> values;
  std::string where;
};

/// The controls of `items` for a fit of `terms`, converted from `quantity`'s reporting units to
/// natural units and merged per parameter (not checked: see check_parameter_controls). Throws
/// ConfigError "<where>: why; how" for a name that is not TERM[#K].PARAM, a term not in `terms`,
/// or an unknown parameter.
std::vector<ParameterControl> control_items_to_controls(std::span<const TermType> terms,
                                                        Quantity quantity,
                                                        std::span<const ControlItem> items);

/// The controls of `start`, `fix` and `bound` (each may be empty) for a fit of `terms` to a
/// record in `unit`, converted to natural units, merged per parameter and checked. Throws
/// ConfigError "<option> 'item': why; how" for a malformed item, a term not in `terms`, an
/// unknown parameter, or a value that is not a number, and "--<key> <TERM.PARAM>: why" for
/// controls check_parameter_controls refuses (a bound with LOW >= HIGH, a fixed value outside
/// its bound, every parameter fixed, ...).
std::vector<ParameterControl> parse_parameter_controls(std::span<const TermType> terms, Unit unit,
                                                       std::string_view start, std::string_view fix,
                                                       std::string_view bound);

}  // namespace stochnav
