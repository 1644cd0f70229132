#pragma once
// Internal to the stats domain: the sum behind MTOTDEV, TTOTDEV and HTOTDEV (deviation.hpp),
// which estimators.cpp normalises.

#include <cstddef>
#include <span>

namespace stochnav {

/// sum over the n - 3m + 1 subsequences of 3m points of `sequence` (n points) of
///   (1 / 6m) sum_{j=0}^{6m-1} ((S(j) - 2 S(j+m) + S(j+2m)) / m)^2,
/// where the subsequence has its half-mean linear trend removed and is extended to 9m points by
/// even reflection at both ends, and S(p) is the sum of the extended points p .. p + m - 1
/// (the kMtotdev construction of deviation.hpp). The phase for MTOTDEV, the frequency for
/// HTOTDEV. Requires 1 <= m and 3m <= n. Cost O(n m): per subsequence one running sum of its
/// 3m points and 6m terms read off prefix sums, vectorised; subsequences spread over the stats
/// threads in tasks fixed by n and m (bitwise the same for every thread count).
double modified_total_sum(std::span<const double> sequence, std::size_t m);

}  // namespace stochnav
