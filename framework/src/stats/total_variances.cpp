// The total-variance family (D. A. Howe): the deviations of a phase record extended by
// reflection at both ends, so that long averaging times keep N - 2 terms.

#include "total_variances.hpp"

#include <algorithm>
#include <array>

namespace stochnav {

double total_variance_sum(std::span<const double> phase, std::size_t m) {
  const double* x = phase.data();
  const std::size_t n = phase.size();
  const std::size_t last = n - 1;
  // x*[i - m] and x*[i + m] for centre i in [1, N - 2]: below 0 and beyond N - 1 the odd
  // reflection 2 x[end] - x[mirror]. The centres split into up to three runs by which side
  // reflects; each run is a plain loop (no branch per term).
  const auto left = [&](std::size_t i) { return i >= m ? x[i - m] : 2.0 * x[0] - x[m - i]; };
  const auto right = [&](std::size_t i) {
    return i + m <= last ? x[i + m] : 2.0 * x[last] - x[2 * last - (i + m)];
  };
  // Four accumulators keep independent chains of additions (vectorisable without reassociation).
  std::array<double, 4> acc{};
  const auto add_run = [&](std::size_t begin, std::size_t end, auto&& term) {
    std::size_t i = begin;
    for (; i + 4 <= end; i += 4) {
      for (std::size_t lane = 0; lane < 4; ++lane) {
        const double diff = term(i + lane);
        acc[lane] += diff * diff;
      }
    }
    for (; i < end; ++i) {
      const double diff = term(i);
      acc[0] += diff * diff;
    }
  };
  const std::size_t first = 1;
  const std::size_t end = n - 1;  // one past the last centre, N - 2
  // Centres whose left neighbour is inside the record: i >= m; right neighbour inside: i <= N-1-m.
  const std::size_t inner_begin = std::clamp(m, first, end);
  const std::size_t inner_end = std::clamp(n > m ? n - m : first, inner_begin, end);
  // Centres below inner_begin reflect on the left (and possibly on the right too when 2m > N-1).
  add_run(first, inner_begin, [&](std::size_t i) { return left(i) - 2.0 * x[i] + right(i); });
  add_run(inner_begin, inner_end, [&](std::size_t i) { return x[i - m] - 2.0 * x[i] + x[i + m]; });
  add_run(inner_end, end, [&](std::size_t i) { return left(i) - 2.0 * x[i] + right(i); });
  return (acc[0] + acc[1]) + (acc[2] + acc[3]);
}

}  // namespace stochnav
