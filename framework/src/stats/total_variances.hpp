#pragma once
// Internal to the stats domain: the sums of the total-variance family (deviation.hpp), which
// estimators.cpp normalises like the other deviations.

#include <cstddef>
#include <span>

namespace stochnav {

/// sum_{i=1}^{N-2} (x*[i-m] - 2 x[i] + x*[i+m])^2 with x* the phase reflected oddly about both
/// end points (deviation.hpp, kTotdev). Requires N >= 3 and 1 <= m <= N - 2. O(N): the
/// reflected points are read from the record in place, no extended copy is made.
double total_variance_sum(std::span<const double> phase, std::size_t m);

}  // namespace stochnav
