#pragma once
// The names of the averaging-factor sets (stats/deviation.hpp, TauSpacing) as users type them,
// parsed in one place for the CLI (`--taus octave`) and the Python module (`taus="octave"`).

#include <string_view>

#include "stochnav/stats/deviation.hpp"

namespace stochnav {

/// "octave", "decade", "dense", and "all" when `allow_all` (a fit takes no "all": its hundreds
/// of strongly correlated points add nothing). Otherwise throws ConfigError
/// "<option> 'x': use octave, decade, dense or all" (without "all": "... use octave, decade or
/// dense for a fit"); `option` is the front end's spelling ("--taus", "taus").
TauSpacing parse_tau_spacing(std::string_view text, std::string_view option,
                             bool allow_all = true);

}  // namespace stochnav
