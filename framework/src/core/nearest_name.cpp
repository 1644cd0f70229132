#include "stochnav/core/nearest_name.hpp"

#include <algorithm>
#include <cctype>
#include <vector>

namespace stochnav {

std::size_t typo_distance(std::string_view a, std::string_view b) {
  const auto same = [](char x, char y) {
    return std::tolower(static_cast<unsigned char>(x)) ==
           std::tolower(static_cast<unsigned char>(y));
  };
  const std::size_t n = a.size(), m = b.size();
  // d[i][j]: distance between the first i characters of a and the first j of b.
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = same(a[i - 1], b[j - 1]) ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && same(a[i - 1], b[j - 2]) && same(a[i - 2], b[j - 1])) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

bool likely_typo(std::string_view typed, std::string_view name) {
  const std::size_t longer = std::max(typed.size(), name.size());
  const std::size_t distance = typo_distance(typed, name);
  return distance <= std::max<std::size_t>(1, longer / 4) && distance < longer;
}

std::optional<std::string> nearest_name(std::string_view typed,
                                        std::span<const std::string> known) {
  std::optional<std::string> best;
  std::size_t best_distance = 0;
  for (const std::string& name : known) {
    if (!likely_typo(typed, name)) continue;
    const std::size_t distance = typo_distance(typed, name);
    if (!best || distance < best_distance) {
      best = name;
      best_distance = distance;
    }
  }
  return best;
}

std::string unknown_key_problem(std::string_view typed, std::span<const std::string> known) {
  if (const auto nearest = nearest_name(typed, known)) {
    return "unknown key '" + std::string(typed) + "'; did you mean '" + *nearest + "'?";
  }
  std::string names;
  for (const std::string& name : known) names += (names.empty() ? "" : ", ") + name;
  return "unknown key; expected only " + (names.empty() ? std::string("an empty object") : names);
}

}  // namespace stochnav
