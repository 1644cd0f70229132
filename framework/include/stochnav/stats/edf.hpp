#pragma once
// Equivalent degrees of freedom (EDF) of the Allan-family variance estimators, by the algorithm
// of C. A. Greenhall and W. J. Riley, "Uncertainty of Stability Variances Based on Finite
// Differences", Proc. 35th PTTI Meeting, 2003, pp. 267-280 (the one Stable32 uses). It covers
// every estimator built from d-th differences of phase, overlapping or not, modified (phase
// averaged over m points first) or not, for power-law noise S_y(f) ~ f^alpha.
//
// With F = 1 (modified) or m (unmodified) and S = m (overlapping) or 1 (non-overlapping), the
// estimator averages M = 1 + floor(S (N - L) / m) squared filter outputs, L = m / F + m d. The
// EDF is 2 (E v)^2 / Var v for the estimate v, computed from the generalized autocovariance of
// the power-law noise: exactly (a finite sum of at most J = min(M, (d+1) S) terms) while
// J <= 100, and otherwise from the paper's asymptotic Tables 1-3 or its decimated sum.
// White PM (alpha = 2) on unmodified variances uses the exact closed form
//   1/edf = (1/M) [1 + 2 sum_{k=1}^{min(d, K-1)} (1 - k/r) rho_k^2],
// rho_k = C(2d, d-k) / C(2d, d), r = M / S, K = ceil(r), which is the paper's Case 4.
// Where an unmodified, alpha <= 0 estimate switches from the exact sum (finite filter factor
// F = m) to Table 2 (its m -> infinity limit) the EDF steps by about 3 %, in the paper's
// algorithm as in Stable32's output.

#include <cstddef>

namespace stochnav {

struct EdfQuery {
  int alpha = 0;                ///< power-law noise exponent of S_y(f), -4 .. 2, alpha + 2d > 1
  int d = 2;                    ///< difference order: 2 Allan, 3 Hadamard (1 also supported)
  std::size_t m = 1;            ///< averaging factor (>= 1)
  std::size_t phase_count = 0;  ///< N, phase points of the record
  bool overlapping = false;     ///< every start index (OADEV, MDEV, OHDEV) or stride m
  bool modified = false;        ///< modified variance (MDEV, TDEV)
};

/// Greenhall-Riley EDF, > 0. NaN when the query is outside the algorithm's domain: alpha
/// outside [-4, 2], d outside [1, 3], alpha + 2d <= 1, m == 0, or N too short for one term.
double greenhall_edf(const EdfQuery& query);

/// EDF of the total variance (TOTDEV) as Stable32 reports it. For white, flicker and random-walk
/// FM (alpha = 0, -1, -2) the empirical fit of D. A. Howe (NIST SP 1065, Sec. 5.2.11, Table 7):
///   edf = b T / tau - c,  T / tau = N / m (N phase points, tau = m tau0),
///   (b, c) = (1.50, 0), (1.17, 0.22), (0.93, 0.36);
/// for flicker PM (alpha = 1) SP 1065's simple Allan-variance formula (Table 5)
///   edf = exp(sqrt(ln((N-1) / (2m)) ln((2m+1)(N-1) / 4)));
/// for white PM (alpha = 2) the Greenhall EDF of the overlapping Allan variance at the same m.
/// These reproduce Stable32's TOTDEV bounds to 1e-3 (PHASE.DAT, Keysight TIC, GPS) wherever the
/// noise type agrees. NaN for alpha outside [-2, 2], m == 0 or N < 3.
double total_variance_edf(int alpha, std::size_t m, std::size_t phase_count);

/// EDF of the modified total variance (MTOTDEV, TTOTDEV): NIST SP 1065 Sec. 5.2.11, Table 8,
///   edf = b N / m - c,  (b, c) = (1.90, 2.10), (1.20, 1.40), (1.10, 1.20), (0.85, 0.50),
///   (0.75, 0.31) for alpha = 2, 1, 0, -1, -2.
/// Not Stable32's: its MTOTDEV bounds on PHASE.DAT imply about 1.33 N / m - 1.9 for white FM
/// (m >= 16) and the MDEV EDF below; its rule is not published. NaN for alpha outside [-2, 2],
/// m == 0 or N < 3.
double modified_total_variance_edf(int alpha, std::size_t m, std::size_t phase_count);

}  // namespace stochnav
