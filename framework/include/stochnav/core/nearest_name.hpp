#pragma once
// Typo suggestions for configuration keys: "unknown key 'sigam'; did you mean 'sigma'?".

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace stochnav {

/// Edit distance between a and b counting insertions, deletions, substitutions and swaps of
/// two neighbouring characters as one each (optimal string alignment), case-insensitively.
std::size_t typo_distance(std::string_view a, std::string_view b);

/// Whether `typed` is a likely misspelling of `name`: typo_distance at most max(1, n / 4) and
/// below n, n the longer length (so "x" is no typo of "N", "NN" is one of "N").
bool likely_typo(std::string_view typed, std::string_view name);

/// The name among `known` closest to `typed` when it is a likely typo of it (the first of equal
/// distance); nullopt otherwise.
std::optional<std::string> nearest_name(std::string_view typed, std::span<const std::string> known);

/// "unknown key '<typed>'; did you mean '<nearest>'?" when a known name is a likely match, else
/// "unknown key; expected only <known, comma-separated>" ("an empty object" if none); the
/// caller's JSON pointer already names the key.
std::string unknown_key_problem(std::string_view typed, std::span<const std::string> known);

}  // namespace stochnav
