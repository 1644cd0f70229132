#pragma once
// Small text helpers shared by the record readers: trimming, splitting and number parsing.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace stochnav {

/// `text` without leading and trailing spaces and tabs.
std::string_view trim(std::string_view text);

/// Splits `line` at `separator` into `cells` (cleared first). A space separator splits at runs
/// of spaces and tabs and ignores leading and trailing blanks (whitespace-separated text).
void split_cells(std::string_view line, char separator, std::vector<std::string_view>& cells);

/// Parses a whole cell (surrounding blanks allowed) as a double with std::from_chars.
/// Returns false if anything but a number is in the cell. "nan" and "inf" parse (and are
/// rejected by the caller with a clearer message).
bool parse_number(std::string_view cell, double& value);

/// Text of an input (a cell, a column name) as an error message echoes it: control bytes
/// escaped as \xNN (a NUL byte would end the message) and, past kEchoedCharacters characters,
/// cut: the first ones then "... (N characters)". A 10 MB cell gives a line, not 10 MB.
inline constexpr std::size_t kEchoedCharacters = 60;
std::string echoed_text(std::string_view text);

}  // namespace stochnav
