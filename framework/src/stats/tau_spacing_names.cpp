#include "stochnav/stats/tau_spacing_names.hpp"

#include <string>

#include "stochnav/core/errors.hpp"

namespace stochnav {

TauSpacing parse_tau_spacing(std::string_view text, std::string_view option, bool allow_all) {
  if (text == "octave") return TauSpacing::kOctave;
  if (text == "decade") return TauSpacing::kDecade;
  if (text == "dense") return TauSpacing::kDense;
  if (allow_all && text == "all") return TauSpacing::kAll;
  throw ConfigError(std::string(option) + " '" + std::string(text) + "': use " +
                    (allow_all ? "octave, decade, dense or all"
                               : "octave, decade or dense for a fit"));
}

}  // namespace stochnav
