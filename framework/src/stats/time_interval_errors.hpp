#pragma once
// Internal to the stats domain: MTIE and TIE rms (deviation.hpp, kMtie and kTierms).

#include <cstddef>
#include <span>

namespace stochnav {

/// Largest max - min of the phase over the N - m windows x[i .. i + m], i < N - m. Requires
/// 1 <= m <= N - 1. O(N) whatever m: sliding maximum and minimum kept in monotonic deques.
double maximum_time_interval_error(std::span<const double> phase, std::size_t m);

/// sum_{i < N - m} (x[i + m] - x[i])^2. Requires 1 <= m <= N - 1. O(N), vectorised.
double time_interval_error_sum(std::span<const double> phase, std::size_t m);

}  // namespace stochnav
