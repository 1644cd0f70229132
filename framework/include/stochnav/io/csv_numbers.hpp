#pragma once
// Numbers appended to CSV text by std::to_chars: the same characters as printf's "%.Nf" and
// "%.Ng" (and fmt's "{:.Nf}", "{:.Ng}"), correctly rounded, in about half fmt's time: the
// formatting of the per-epoch output files (experiment/navigation_run.hpp).

#include <charconv>
#include <string>

namespace stochnav {

/// Appends `value` with `decimals` digits after the point ("%.{decimals}f").
inline void append_fixed(std::string& out, double value, int decimals) {
  char text[352];  // the longest fixed form of a double (1.8e308 with decimals <= 17) fits
  const auto result =
      std::to_chars(text, text + sizeof text, value, std::chars_format::fixed, decimals);
  out.append(text, result.ptr);
}

/// Appends `value` with `significant` significant digits ("%.{significant}g").
inline void append_general(std::string& out, double value, int significant) {
  char text[64];
  const auto result =
      std::to_chars(text, text + sizeof text, value, std::chars_format::general, significant);
  out.append(text, result.ptr);
}

}  // namespace stochnav
