#pragma once
// Steering a fit's parameters by name (`stochnav fit --start/--fix/--bound`): items
//   TERM[#K].PARAM=VALUE        (--start, --fix)      e.g. gauss_markov.tau_c=20
//   TERM[#K].PARAM=LOW:HIGH     (--bound)             e.g. gauss_markov#2.tau_c=5:500
// comma-separated, values in the reporting units of DESIGN.md for the record's unit (tau_c in s,
// sigma and B in deg/h for a gyro in deg/h, N in deg/sqrt(h), ...). K (1-based) picks the K-th
// term of that type in the term list; without it, the n-th mention of TERM.PARAM in one option
// refers to the n-th term of that type (so "gauss_markov.tau_c=1,gauss_markov.tau_c=100" starts
// the first Gauss-Markov term at 1 s and the second at 100 s).

#include <span>
#include <string_view>
#include <vector>

#include "stochnav/core/units.hpp"
#include "stochnav/fit/gmwm_fit.hpp"

namespace stochnav {

/// The controls of `start`, `fix` and `bound` (each may be empty) for a fit of `terms` to a
/// record in `unit`, converted to natural units and merged per parameter. Throws ConfigError
/// "<option> 'item': why; how" for a malformed item, a term not in `terms`, an unknown
/// parameter, or a value that is not a number.
std::vector<ParameterControl> parse_parameter_controls(std::span<const TermType> terms,
                                                       Unit unit, std::string_view start,
                                                       std::string_view fix,
                                                       std::string_view bound);

}  // namespace stochnav
