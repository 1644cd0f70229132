// Greenhall & Riley (2003) EDF algorithm; equation and table numbers refer to that paper.

#include "stochnav/stats/edf.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace stochnav {
namespace {

// Long double: the unmodified filters take second differences of the autocovariance at spacing
// 1/m, which cancels about 2 log10(m) digits.
using Real = long double;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr Real kInfinite = std::numeric_limits<Real>::infinity();
/// Largest number of terms summed exactly (the paper's J_max).
constexpr double kMaxExactTerms = 100.0;

/// Generalized autocovariance of the phase for S_y(f) ~ f^alpha, up to a constant (Eq. 7).
Real power_law_sw(Real t, int alpha) {
  const Real a = std::abs(t);
  const Real log_a = a > 0 ? std::log(a) : 0;  // t^(2k) log|t| -> 0 as t -> 0
  switch (alpha) {
    case 2:
      return -a;
    case 1:
      return a * a * log_a;
    case 0:
      return a * a * a;
    case -1:
      return -a * a * a * a * log_a;
    case -2:
      return -a * a * a * a * a;
    case -3:
      return a * a * a * a * a * a * log_a;
    case -4:
      return a * a * a * a * a * a * a;
    default:
      return std::numeric_limits<Real>::quiet_NaN();
  }
}

/// After the m-point phase average with filter factor F (Eq. 8); F = infinity is the limit.
Real averaged_sx(Real t, Real filter_factor, int alpha) {
  if (std::isinf(filter_factor)) return power_law_sw(t, alpha + 2);
  const Real step = 1 / filter_factor;
  return filter_factor * filter_factor *
         (2 * power_law_sw(t, alpha) - power_law_sw(t - step, alpha) -
          power_law_sw(t + step, alpha));
}

Real binomial(int n, int k) {
  Real result = 1;
  for (int i = 1; i <= k; ++i)
    result = result * static_cast<Real>(n - k + i) / static_cast<Real>(i);
  return result;
}

/// After the d-th difference at lag 1 (time in units of tau) (Eq. 9).
Real differenced_sz(Real t, Real filter_factor, int alpha, int d) {
  Real sum = 0;
  for (int k = -d; k <= d; ++k) {
    const Real sign = (k % 2 == 0) ? 1 : -1;
    sum += sign * binomial(2 * d, d + k) * averaged_sx(t + k, filter_factor, alpha);
  }
  return sum;
}

/// Eq. 10: sz(0)^2 + (1 - J/M) sz(J/S)^2 + 2 sum_{j=1}^{J-1} (1 - j/M) sz(j/S)^2.
Real basic_sum(double terms_summed, double terms, Real stride_factor, Real filter_factor, int alpha,
               int d) {
  const Real J = terms_summed;
  const Real M = terms;
  const Real at_zero = differenced_sz(0, filter_factor, alpha, d);
  const Real at_j = differenced_sz(J / stride_factor, filter_factor, alpha, d);
  Real sum = at_zero * at_zero + (1 - J / M) * at_j * at_j;
  const int last = static_cast<int>(terms_summed);
  for (int j = 1; j < last; ++j) {
    const Real s = differenced_sz(j / stride_factor, filter_factor, alpha, d);
    sum += 2 * (1 - j / M) * s * s;
  }
  return sum;
}

struct TableEntry {
  double a0;
  double a1;
};

/// Rows alpha = 2, 1, 0, -1, -2, -3, -4; columns d = 1, 2, 3. NaN where alpha + 2d <= 1.
using AsymptoticTable = std::array<std::array<TableEntry, 3>, 7>;
constexpr TableEntry kNone{kNaN, kNaN};

/// Table 1: modified variances, large r.
constexpr AsymptoticTable kModifiedTable = {{
    {{{2.0 / 3.0, 1.0 / 3.0}, {7.0 / 9.0, 1.0 / 2.0}, {22.0 / 25.0, 2.0 / 3.0}}},
    {{{0.840, 0.345}, {0.997, 0.616}, {1.141, 0.843}}},
    {{{1.079, 0.368}, {1.033, 0.607}, {1.184, 0.848}}},
    {{kNone, {1.048, 0.534}, {1.180, 0.816}}},
    {{kNone, {1.302, 0.535}, {1.175, 0.777}}},
    {{kNone, kNone, {1.194, 0.703}}},
    {{kNone, kNone, {1.489, 0.702}}},
}};

/// Table 2: unmodified variances, large r.
constexpr AsymptoticTable kUnmodifiedTable = {{
    {{{3.0 / 2.0, 1.0 / 2.0}, {35.0 / 18.0, 1.0}, {231.0 / 100.0, 3.0 / 2.0}}},
    {{{78.6, 25.2}, {790.0, 410.0}, {9950.0, 6520.0}}},
    {{{2.0 / 3.0, 1.0 / 6.0}, {2.0 / 3.0, 1.0 / 3.0}, {7.0 / 9.0, 1.0 / 2.0}}},
    {{kNone, {0.852, 0.375}, {0.997, 0.617}}},
    {{kNone, {1.079, 0.368}, {1.033, 0.607}}},
    {{kNone, kNone, {1.053, 0.553}}},
    {{kNone, kNone, {1.302, 0.535}}},
}};

/// Table 3: unmodified variances, flicker PM (alpha = 1): sz(0) ~ b0 + b1 ln m for d = 1, 2, 3.
constexpr std::array<TableEntry, 3> kFlickerPmNorm = {{{6.0, 4.0}, {15.23, 12.0}, {47.8, 40.0}}};

TableEntry table_entry(const AsymptoticTable& table, int alpha, int d) {
  return table[static_cast<std::size_t>(2 - alpha)][static_cast<std::size_t>(d - 1)];
}

/// Case 4, white PM on an unmodified variance: the filter outputs are correlated only at lags
/// k tau, k <= d, with coefficient rho_k = (-1)^k C(2d, d-k) / C(2d, d).
double white_pm_unmodified_edf(double terms, double r, int d) {
  const Real center = binomial(2 * d, d);
  Real bracket = 1;
  for (int k = 1; k <= d && k < r; ++k) {
    const Real rho = binomial(2 * d, d - k) / center;
    bracket += 2 * (1 - k / static_cast<Real>(r)) * rho * rho;
  }
  return static_cast<double>(static_cast<Real>(terms) / bracket);
}

}  // namespace

double greenhall_edf(const EdfQuery& query) {
  const int alpha = query.alpha;
  const int d = query.d;
  if (alpha < -4 || alpha > 2 || d < 1 || d > 3 || alpha + 2 * d <= 1 || query.m == 0) {
    return kNaN;
  }
  const double m = static_cast<double>(query.m);
  const double n = static_cast<double>(query.phase_count);
  const double filter_factor = query.modified ? 1.0 : m;
  const double stride_factor = query.overlapping ? m : 1.0;
  const double filter_length = m / filter_factor + m * d;  // L, phase points per term
  if (n < filter_length) return kNaN;
  const double terms = 1.0 + std::floor(stride_factor * (n - filter_length) / m);  // M
  const double summed = std::min(terms, (d + 1) * stride_factor);                  // J
  const double r = terms / stride_factor;
  const bool exact = summed <= kMaxExactTerms;
  const bool asymptotic = !exact && r > d + 1;
  const Real decimated_stride = kMaxExactTerms / r;  // m' of the decimated sums

  Real inverse_edf = 0;
  if (query.modified) {  // Case 1
    const Real norm = differenced_sz(0, 1, alpha, d);
    if (exact) {
      inverse_edf = basic_sum(summed, terms, stride_factor, 1, alpha, d) / (norm * norm * terms);
    } else if (asymptotic) {
      const TableEntry e = table_entry(kModifiedTable, alpha, d);
      inverse_edf = (e.a0 - e.a1 / r) / r;
    } else {
      inverse_edf = basic_sum(kMaxExactTerms, kMaxExactTerms, decimated_stride, 1, alpha, d) /
                    (norm * norm * kMaxExactTerms);
    }
  } else if (alpha <= 0) {  // Case 2
    if (exact) {
      const Real filter = m * (d + 1) <= kMaxExactTerms ? static_cast<Real>(m) : kInfinite;
      const Real norm = differenced_sz(0, filter, alpha, d);
      inverse_edf =
          basic_sum(summed, terms, stride_factor, filter, alpha, d) / (norm * norm * terms);
    } else if (asymptotic) {
      const TableEntry e = table_entry(kUnmodifiedTable, alpha, d);
      inverse_edf = (e.a0 - e.a1 / r) / r;
    } else {
      const Real norm = differenced_sz(0, kInfinite, alpha, d);
      inverse_edf =
          basic_sum(kMaxExactTerms, kMaxExactTerms, decimated_stride, kInfinite, alpha, d) /
          (norm * norm * kMaxExactTerms);
    }
  } else if (alpha == 1) {  // Case 3
    const TableEntry b = kFlickerPmNorm[static_cast<std::size_t>(d - 1)];
    const Real log_norm = b.a0 + b.a1 * std::log(static_cast<Real>(m));
    if (exact) {
      const Real norm = differenced_sz(0, m, alpha, d);
      inverse_edf = basic_sum(summed, terms, stride_factor, m, alpha, d) / (norm * norm * terms);
    } else if (asymptotic) {
      const TableEntry e = table_entry(kUnmodifiedTable, alpha, d);
      inverse_edf = (e.a0 - e.a1 / r) / (r * log_norm * log_norm);
    } else {
      inverse_edf =
          basic_sum(kMaxExactTerms, kMaxExactTerms, decimated_stride, decimated_stride, alpha, d) /
          (log_norm * log_norm * kMaxExactTerms);
    }
  } else {  // Case 4, alpha == 2
    return white_pm_unmodified_edf(terms, r, d);
  }
  return static_cast<double>(1 / inverse_edf);
}

double total_variance_edf(int alpha, std::size_t m, std::size_t phase_count) {
  if (alpha < -2 || alpha > 2 || m == 0 || phase_count < 3) return kNaN;
  if (alpha == 1) {
    // NIST SP 1065 Table 5, flicker PM (the "simple" approximation for the Allan variance).
    const double n = static_cast<double>(phase_count);
    const double md = static_cast<double>(m);
    const double a = (n - 1.0) / (2.0 * md);
    const double b = (2.0 * md + 1.0) * (n - 1.0) / 4.0;
    return std::exp(std::sqrt(std::log(a) * std::log(b)));
  }
  if (alpha == 2) {
    return greenhall_edf({.alpha = alpha,
                          .d = 2,
                          .m = m,
                          .phase_count = phase_count,
                          .overlapping = true,
                          .modified = false});
  }
  // NIST SP 1065 Table 7, rows alpha = 0, -1, -2.
  constexpr std::array<TableEntry, 3> kTotalTable = {{{1.50, 0.0}, {1.17, 0.22}, {0.93, 0.36}}};
  const TableEntry e = kTotalTable[static_cast<std::size_t>(-alpha)];
  return e.a0 * static_cast<double>(phase_count) / static_cast<double>(m) - e.a1;
}

double modified_total_variance_edf(int alpha, std::size_t m, std::size_t phase_count) {
  if (alpha < -2 || alpha > 2 || m == 0 || phase_count < 3) return kNaN;
  constexpr std::array<TableEntry, 5> kModifiedTotalTable = {
      {{1.90, 2.10}, {1.20, 1.40}, {1.10, 1.20}, {0.85, 0.50}, {0.75, 0.31}}};
  const TableEntry e = kModifiedTotalTable[static_cast<std::size_t>(2 - alpha)];
  return e.a0 * static_cast<double>(phase_count) / static_cast<double>(m) - e.a1;
}

}  // namespace stochnav
