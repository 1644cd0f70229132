// The modified total sum (Howe & Vernotte 1999; NIST SP 1065 Eq. 27), computed from prefix
// sums: no 9m-point copy is built, and the three block sums of a term come from one third
// difference of the extended prefix sums, so each term costs a handful of vector operations.

#include "modified_total_sum.hpp"

#include <algorithm>
#include <vector>

#include "stochnav/stats/parallel.hpp"

namespace stochnav {
namespace {

/// Subsequences per task: enough work to amortise the task, few enough to spread the record.
constexpr std::size_t kSubsequencesPerTask = 256;

/// The work space of one subsequence: prefix sums of its detrended points and of their
/// reflected extension.
struct SubsequenceScratch {
  explicit SubsequenceScratch(std::size_t m) : local(3 * m + 1), extended(9 * m + 1) {}
  std::vector<double> local;     // local[k] = sum of the first k detrended points
  std::vector<double> extended;  // extended[p] = sum of the first p extended points
};

/// (1 / 6m) sum over the 6m terms of one subsequence, s[0 .. 3m - 1].
double subsequence_mean_square(const double* s, std::size_t m, SubsequenceScratch& scratch) {
  const std::size_t length = 3 * m;
  double* local = scratch.local.data();
  // Raw prefix sums relative to the first point (constants cancel in every term; keeping the
  // sums small keeps their digits).
  const double origin = s[0];
  local[0] = 0.0;
  for (std::size_t k = 0; k < length; ++k) local[k + 1] = local[k] + (s[k] - origin);
  const std::size_t half = length / 2;
  const double first_mean = local[half] / static_cast<double>(half);
  const double last_mean = (local[length] - local[length - half]) / static_cast<double>(half);
  const double slope = (last_mean - first_mean) / static_cast<double>(length - half);
  // Removing slope * k from point k removes slope * k (k - 1) / 2 from the k-th prefix sum.
  for (std::size_t k = 0; k <= length; ++k) {
    const auto kd = static_cast<double>(k);
    local[k] -= slope * 0.5 * kd * (kd - 1.0);
  }
  // Extended prefix sums: reverse(z) | z | reverse(z).
  double* extended = scratch.extended.data();
  const double total = local[length];
  for (std::size_t p = 0; p <= length; ++p) extended[p] = total - local[length - p];
  for (std::size_t p = 1; p <= length; ++p) extended[length + p] = total + local[p];
  for (std::size_t p = 1; p <= length; ++p) {
    extended[2 * length + p] = 3.0 * total - local[length - p];
  }
  // S(j) - 2 S(j+m) + S(j+2m) = E[j+3m] - 3 E[j+2m] + 3 E[j+m] - E[j].
  const double* e0 = extended;
  const double* e1 = extended + m;
  const double* e2 = extended + 2 * m;
  const double* e3 = extended + 3 * m;
  double squares = 0.0;
  for (std::size_t j = 0; j < 2 * length; ++j) {
    const double term = e3[j] - 3.0 * e2[j] + 3.0 * e1[j] - e0[j];
    squares += term * term;
  }
  const auto md = static_cast<double>(m);
  return squares / (md * md * 6.0 * md);
}

}  // namespace

double modified_total_sum(std::span<const double> sequence, std::size_t m) {
  const std::size_t subsequences = sequence.size() + 1 - 3 * m;
  const std::size_t tasks = (subsequences + kSubsequencesPerTask - 1) / kSubsequencesPerTask;
  std::vector<double> partial(tasks, 0.0);
  parallel_for(tasks, [&](std::size_t task) {
    SubsequenceScratch scratch(m);
    const std::size_t begin = task * kSubsequencesPerTask;
    const std::size_t end = std::min(subsequences, begin + kSubsequencesPerTask);
    double sum = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      sum += subsequence_mean_square(sequence.data() + i, m, scratch);
    }
    partial[task] = sum;
  });
  double sum = 0.0;
  for (double value : partial) sum += value;
  return sum;
}

}  // namespace stochnav
