// The raw Allan-family estimators. The overlapping ones dominate the cost on long records, so
// their sums run over cache-sized blocks of start indices, all averaging factors per block:
// the phase around each block offset (0, m, 2m, ...) is then read from memory once and shared
// by every factor that needs it (with octave factors, offset 2m of one is offset m of the next).
// No allocation per factor; the memory traffic, not the arithmetic, bounds the speed.
// The blocks are grouped into tasks fixed by the record length alone and spread over the stats
// threads (parallel.hpp); per-task sums are added in task order, so every thread count gives
// bitwise the same result.

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "extended_estimators.hpp"
#include "fused_passes.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/parallel.hpp"
#include "total_variances.hpp"
#include "vector_clones.hpp"

namespace stochnav {
namespace {

/// Start indices per block: a few dozen offsets of it stay within the L2 cache.
constexpr std::size_t kBlockTerms = 2048;

/// Blocks per task of the pass along the record: 2^16 terms, about 150 tasks on 1e7 points.
constexpr std::size_t kBlocksPerTask = 32;

/// sum_{i = begin}^{end - 1} (x[i+2m] - 2 x[i+m] + x[i])^2. Eight independent accumulators
/// let the compiler keep the adds in vector registers (no reassociation is needed).
STOCHNAV_WIDE_VECTOR_CLONES
double sum_second_differences(const double* x, std::size_t m, std::size_t begin, std::size_t end) {
  const double* x0 = x + begin;
  const double* x1 = x0 + m;
  const double* x2 = x1 + m;
  const std::size_t count = end - begin;
  std::array<double, 8> acc{};
  std::size_t i = 0;
  for (; i + 8 <= count; i += 8) {
    for (std::size_t lane = 0; lane < 8; ++lane) {
      const double diff = x2[i + lane] - 2.0 * x1[i + lane] + x0[i + lane];
      acc[lane] += diff * diff;
    }
  }
  for (; i < count; ++i) {
    const double diff = x2[i] - 2.0 * x1[i] + x0[i];
    acc[0] += diff * diff;
  }
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

/// sum_{i = begin}^{end - 1} (x[i+3m] - 3 x[i+2m] + 3 x[i+m] - x[i])^2.
STOCHNAV_WIDE_VECTOR_CLONES
double sum_third_differences(const double* x, std::size_t m, std::size_t begin, std::size_t end) {
  const double* x0 = x + begin;
  const double* x1 = x0 + m;
  const double* x2 = x1 + m;
  const double* x3 = x2 + m;
  const std::size_t count = end - begin;
  std::array<double, 8> acc{};
  std::size_t i = 0;
  for (; i + 8 <= count; i += 8) {
    for (std::size_t lane = 0; lane < 8; ++lane) {
      const double diff = x3[i + lane] - 3.0 * x2[i + lane] + 3.0 * x1[i + lane] - x0[i + lane];
      acc[lane] += diff * diff;
    }
  }
  for (; i < count; ++i) {
    const double diff = x3[i] - 3.0 * x2[i] + 3.0 * x1[i] - x0[i];
    acc[0] += diff * diff;
  }
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

/// Factors summed together in one sweep over a block (sum_second_differences_of_four).
constexpr std::size_t kGroup = 4;

/// sum_second_differences of four factors m[0..3] at once, each over [begin, end) (all of them
/// must have that many terms): per factor the very same operations in the same order, so the
/// sums are bitwise those of four single calls. Four independent chains of additions instead of
/// one keep the vector units busy, and x[i] is loaded once for all four; where each factor is
/// twice the one before (octave and decade runs: m, 2m, 4m, 8m), x[i + 2m] of one is x[i + m]
/// of the next, so 6 loads serve 4 terms instead of 12.
STOCHNAV_WIDE_VECTOR_CLONES
void sum_second_differences_of_four(const double* x, const std::size_t* m, std::size_t begin,
                                    std::size_t end, double* sums) {
  const double* x0 = x + begin;
  const std::size_t count = end - begin;
  std::array<std::array<double, 8>, kGroup> acc{};
  const auto reduce = [](const std::array<double, 8>& a) {
    return ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7]));
  };
  std::size_t i = 0;
  if (m[1] == 2 * m[0] && m[2] == 2 * m[1] && m[3] == 2 * m[2]) {
    // x0 + k m[0] for k = 1, 2, 4, 8, 16.
    const double* a1 = x0 + m[0];
    const double* a2 = x0 + m[1];
    const double* a4 = x0 + m[2];
    const double* a8 = x0 + m[3];
    const double* a16 = x0 + 2 * m[3];
    for (; i + 8 <= count; i += 8) {
      for (std::size_t lane = 0; lane < 8; ++lane) {
        const double z = x0[i + lane];
        const double v1 = a1[i + lane];
        const double v2 = a2[i + lane];
        const double v4 = a4[i + lane];
        const double v8 = a8[i + lane];
        const double v16 = a16[i + lane];
        const double d0 = v2 - 2.0 * v1 + z;
        const double d1 = v4 - 2.0 * v2 + z;
        const double d2 = v8 - 2.0 * v4 + z;
        const double d3 = v16 - 2.0 * v8 + z;
        acc[0][lane] += d0 * d0;
        acc[1][lane] += d1 * d1;
        acc[2][lane] += d2 * d2;
        acc[3][lane] += d3 * d3;
      }
    }
  } else {
    const double* b0 = x0 + m[0];
    const double* b1 = x0 + m[1];
    const double* b2 = x0 + m[2];
    const double* b3 = x0 + m[3];
    const double* c0 = b0 + m[0];
    const double* c1 = b1 + m[1];
    const double* c2 = b2 + m[2];
    const double* c3 = b3 + m[3];
    for (; i + 8 <= count; i += 8) {
      for (std::size_t lane = 0; lane < 8; ++lane) {
        const double z = x0[i + lane];
        const double d0 = c0[i + lane] - 2.0 * b0[i + lane] + z;
        const double d1 = c1[i + lane] - 2.0 * b1[i + lane] + z;
        const double d2 = c2[i + lane] - 2.0 * b2[i + lane] + z;
        const double d3 = c3[i + lane] - 2.0 * b3[i + lane] + z;
        acc[0][lane] += d0 * d0;
        acc[1][lane] += d1 * d1;
        acc[2][lane] += d2 * d2;
        acc[3][lane] += d3 * d3;
      }
    }
  }
  for (std::size_t k = 0; k < kGroup; ++k) {
    const double* x1 = x0 + m[k];
    const double* x2 = x1 + m[k];
    for (std::size_t j = i; j < count; ++j) {
      const double diff = x2[j] - 2.0 * x1[j] + x0[j];
      acc[k][0] += diff * diff;
    }
    sums[k] = reduce(acc[k]);
  }
}

double sum_differences(int d, const double* x, std::size_t m, std::size_t begin, std::size_t end) {
  return d == 2 ? sum_second_differences(x, m, begin, end)
                : sum_third_differences(x, m, begin, end);
}

/// Overlapping sums of squared d-th differences (d = 2 or 3) for every m, in two passes.
///  - Factors below kRowFactor: blocks of start indices in order, all factors per block. Their
///    offsets (up to 3 kRowFactor points) stay in the last-level cache between uses.
///  - Larger factors that are multiples of the smallest of them, P (octave and decade sets):
///    the phase is seen as rows of P points, and term i = c + r P of factor q P reads rows
///    r, r + q, r + 2q (and r + 3q) at column c. Walking down the rows of one column block,
///    every row block comes from memory once and serves all those factors from cache, where
///    walking along the record would fetch each far offset anew (4 of 22 octave factors of a
///    1e7 record cost as much as the other 18 that way).
/// Other large factors (all-tau sets) go with the first pass.
/// With a `job`, its block b runs right after along-record task b (the same start indices), and
/// its blocks beyond the last such task as tasks of their own.
std::vector<double> overlapping_sums(int d, std::span<const double> phase,
                                     std::span<const std::size_t> m_values,
                                     const AlongsideJob* job) {
  constexpr std::size_t kRowFactor = std::size_t{1} << 16;
  const std::size_t n = phase.size();
  const auto order = static_cast<std::size_t>(d);
  const auto terms_of = [&](std::size_t m) { return n - order * m; };

  std::size_t row_length = 0;  // P
  for (std::size_t m : m_values) {
    if (m >= kRowFactor && (row_length == 0 || m < row_length)) row_length = m;
  }
  std::vector<std::size_t> along_record;  // indices into m_values
  std::vector<std::size_t> down_rows;
  for (std::size_t k = 0; k < m_values.size(); ++k) {
    const bool on_rows = row_length != 0 && m_values[k] % row_length == 0;
    (on_rows ? down_rows : along_record).push_back(k);
  }

  std::size_t most_terms = 0;
  for (std::size_t k : along_record) most_terms = std::max(most_terms, terms_of(m_values[k]));
  constexpr std::size_t kTaskTerms = kBlockTerms * kBlocksPerTask;
  const std::size_t record_tasks = (most_terms + kTaskTerms - 1) / kTaskTerms;
  const std::size_t column_tasks = (row_length + kBlockTerms - 1) / kBlockTerms;
  // partial[task * factors + k]: the sum of factor k over the terms of one task.
  const std::size_t factors = m_values.size();
  std::vector<double> partial((record_tasks + column_tasks) * factors, 0.0);

  // Adds to out[k] the terms [begin, begin + width) of each listed factor k (fewer where the
  // factor has fewer terms); false if none of them has a term there. Factors with every term of
  // the block go four at a time (second differences), in the same order as one by one.
  const auto add_block = [&](std::span<const std::size_t> listed, std::size_t begin,
                             std::size_t width, double* out) {
    std::array<std::size_t, kGroup> group_k{};
    std::array<std::size_t, kGroup> group_m{};
    std::size_t grouped = 0;
    bool any_term = false;
    for (std::size_t k : listed) {
      const std::size_t terms = terms_of(m_values[k]);
      if (begin >= terms) continue;
      any_term = true;
      const std::size_t end = std::min(begin + width, terms);
      if (d == 2 && end == begin + width) {
        group_k[grouped] = k;
        group_m[grouped] = m_values[k];
        if (++grouped == kGroup) {
          std::array<double, kGroup> sums{};
          sum_second_differences_of_four(phase.data(), group_m.data(), begin, end, sums.data());
          for (std::size_t j = 0; j < kGroup; ++j) out[group_k[j]] += sums[j];
          grouped = 0;
        }
      } else {
        out[k] += sum_differences(d, phase.data(), m_values[k], begin, end);
      }
    }
    for (std::size_t j = 0; j < grouped; ++j) {
      out[group_k[j]] += sum_second_differences(phase.data(), group_m[j], begin, begin + width);
    }
    return any_term;
  };
  const auto along_record_task = [&](std::size_t task) {
    double* out = partial.data() + task * factors;
    const std::size_t task_end = std::min(most_terms, (task + 1) * kTaskTerms);
    for (std::size_t begin = task * kTaskTerms; begin < task_end; begin += kBlockTerms) {
      add_block(along_record, begin, kBlockTerms, out);
    }
  };
  const auto down_rows_task = [&](std::size_t task) {
    double* out = partial.data() + (record_tasks + task) * factors;
    const std::size_t column = task * kBlockTerms;
    const std::size_t width = std::min(kBlockTerms, row_length - column);
    for (std::size_t begin = column; add_block(down_rows, begin, width, out);) {
      begin += row_length;
    }
  };
  static_assert(kTaskTerms == kAlongsideBlockPoints, "a job block is the stretch of one task");
  const std::size_t job_blocks = job != nullptr ? job->blocks : 0;
  const std::size_t job_tasks = job_blocks > record_tasks ? job_blocks - record_tasks : 0;
  parallel_for(record_tasks + column_tasks + job_tasks, [&](std::size_t task) {
    if (task < record_tasks) {
      along_record_task(task);
      if (task < job_blocks) job->run(task);
    } else if (task < record_tasks + column_tasks) {
      down_rows_task(task - record_tasks);
    } else {
      job->run(record_tasks + (task - record_tasks - column_tasks));
    }
  });

  std::vector<double> sums(factors, 0.0);
  for (std::size_t task = 0; task < record_tasks + column_tasks; ++task) {
    for (std::size_t k = 0; k < factors; ++k) sums[k] += partial[task * factors + k];
  }
  return sums;
}

/// Non-overlapping: the terms start at 0, m, 2m, ...
double strided_sum(int d, std::span<const double> x, std::size_t m, std::size_t terms) {
  double sum = 0.0;
  for (std::size_t t = 0, i = 0; t < terms; ++t, i += m) {
    const double diff = d == 2 ? x[i + 2 * m] - 2.0 * x[i + m] + x[i]
                               : x[i + 3 * m] - 3.0 * x[i + 2 * m] + 3.0 * x[i + m] - x[i];
    sum += diff * diff;
  }
  return sum;
}

/// sum over j < terms of w(j)^2, w(j) = sum_{i=j}^{j+m-1} d(i), d(i) = x[i+2m] - 2 x[i+m] + x[i].
/// w slides by one index per term, w(j) = w(j-1) + d(j+m-1) - d(j-1). Four lanes slide through
/// four quarters of each block at once (independent dependency chains), and every block starts
/// from freshly summed windows, so the rounding errors of the sliding updates cannot build up.
double modified_sum(std::span<const double> x, std::size_t m, std::size_t terms) {
  const double* p = x.data();
  const auto second_difference = [p, m](std::size_t i) {
    return p[i + 2 * m] - 2.0 * p[i + m] + p[i];
  };
  const auto window_at = [&](std::size_t j) {
    double window = 0.0;
    for (std::size_t i = j; i < j + m; ++i) window += second_difference(i);
    return window;
  };
  constexpr std::size_t kLanes = 4;
  // Restarting costs kLanes * m additions per block: at most a quarter of the block's work.
  const std::size_t block = std::max<std::size_t>(16 * m, 1 << 16);
  double total = 0.0;
  for (std::size_t begin = 0; begin < terms; begin += block) {
    const std::size_t count = std::min(block, terms - begin);
    const std::size_t lane_length = count / kLanes;
    std::array<double, kLanes> window{};
    std::array<double, kLanes> squares{};
    std::array<std::size_t, kLanes> start{};
    for (std::size_t lane = 0; lane < kLanes; ++lane) {
      start[lane] = begin + lane * lane_length;
      if (lane_length > 0) window[lane] = window_at(start[lane]);
    }
    for (std::size_t step = 0; step < lane_length; ++step) {
      for (std::size_t lane = 0; lane < kLanes; ++lane) {
        const std::size_t j = start[lane] + step;
        if (step > 0) window[lane] += second_difference(j + m - 1) - second_difference(j - 1);
        squares[lane] += window[lane] * window[lane];
      }
    }
    // The remainder of the block (fewer than kLanes terms): directly.
    for (std::size_t j = begin + kLanes * lane_length; j < begin + count; ++j) {
      const double w = window_at(j);
      squares[0] += w * w;
    }
    total += (squares[0] + squares[1]) + (squares[2] + squares[3]);
  }
  return total;
}

/// Variance sum -> deviation, with the normalisation of each estimator.
double to_deviation(Deviation kind, double sum, double tau0_s, std::size_t m, std::size_t terms) {
  const double tau = static_cast<double>(m) * tau0_s;
  const double n = static_cast<double>(terms);
  switch (kind) {
    case Deviation::kAdev:
    case Deviation::kOadev:
    case Deviation::kTotdev:
      return std::sqrt(sum / (2.0 * tau * tau * n));
    case Deviation::kMdev: {
      const double md = static_cast<double>(m);
      return std::sqrt(sum / (2.0 * md * md * tau * tau * n));
    }
    case Deviation::kTdev: {
      const double md = static_cast<double>(m);
      return tau * std::sqrt(sum / (2.0 * md * md * tau * tau * n) / 3.0);
    }
    case Deviation::kHdev:
    case Deviation::kOhdev:
      return std::sqrt(sum / (6.0 * tau * tau * n));
    default:  // the extended estimators are normalised where they are summed
      return 0.0;
  }
}

/// deviation_values with an optional job run in the same pass (deviation_values_alongside).
std::vector<double> deviation_values_with(Deviation kind, std::span<const double> phase,
                                          double tau0_s, std::span<const std::size_t> m_values,
                                          const AlongsideJob* job) {
  const std::size_t n = phase.size();
  for (std::size_t m : m_values) require_deviation_terms(kind, m, n);
  if (is_extended_estimator(kind)) {
    if (job != nullptr) parallel_for(job->blocks, job->run);
    return extended_deviation_values(kind, phase, tau0_s, m_values);
  }

  std::vector<double> sums;
  if (kind == Deviation::kOadev || kind == Deviation::kOhdev) {
    sums = overlapping_sums(difference_order(kind), phase, m_values, job);
  } else {
    if (job != nullptr) parallel_for(job->blocks, job->run);
    // One task per factor: each sum is computed whole by one thread.
    sums.assign(m_values.size(), 0.0);
    parallel_for(m_values.size(), [&](std::size_t k) {
      const std::size_t m = m_values[k];
      const std::size_t terms = term_count(kind, m, n);
      if (kind == Deviation::kTotdev) {
        sums[k] = total_variance_sum(phase, m);
      } else {
        sums[k] = is_modified(kind) ? modified_sum(phase, m, terms)
                                    : strided_sum(difference_order(kind), phase, m, terms);
      }
    });
  }
  std::vector<double> deviations(m_values.size());
  for (std::size_t k = 0; k < m_values.size(); ++k) {
    const std::size_t m = m_values[k];
    deviations[k] = to_deviation(kind, sums[k], tau0_s, m, term_count(kind, m, n));
  }
  return deviations;
}

}  // namespace

void require_deviation_terms(Deviation kind, std::size_t m, std::size_t phase_count) {
  if (term_count(kind, m, phase_count) == 0) {
    throw std::invalid_argument(
        std::string(deviation_name(kind)) + ": averaging factor m = " + std::to_string(m) +
        " leaves no terms on " + std::to_string(phase_count) + " phase points");
  }
}

std::vector<double> deviation_values(Deviation kind, std::span<const double> phase, double tau0_s,
                                     std::span<const std::size_t> m_values) {
  return deviation_values_with(kind, phase, tau0_s, m_values, nullptr);
}

std::vector<double> deviation_values_alongside(Deviation kind, std::span<const double> phase,
                                               double tau0_s, std::span<const std::size_t> m_values,
                                               const AlongsideJob& job) {
  return deviation_values_with(kind, phase, tau0_s, m_values, &job);
}

double deviation_value(Deviation kind, std::span<const double> phase, double tau0_s,
                       std::size_t m) {
  const std::size_t factors[] = {m};
  return deviation_values(kind, phase, tau0_s, factors).front();
}

}  // namespace stochnav
