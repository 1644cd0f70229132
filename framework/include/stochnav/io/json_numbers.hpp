#pragma once
// Numbers in result JSON (metrics.json, results.json, fit reports): JSON has no NaN or
// infinity, so an undefined value is written as null.

#include <cmath>
#include <nlohmann/json.hpp>

namespace stochnav {

/// `value` as a JSON number, or null when it is NaN or infinite.
inline nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace stochnav
