#pragma once
// Power-law noise identification at one averaging factor, as Stable32 does it: the dominant
// noise S_y(f) ~ f^alpha chooses the EDF, hence the confidence interval, of a deviation.
//
//   alpha   2 white PM   1 flicker PM   0 white FM   -1 flicker FM   -2 random-walk FM
//
// 1. Lag-1 autocorrelation (W. J. Riley and C. A. Greenhall, "Power Law Noise Identification
//    Using the Lag 1 Autocorrelation", Proc. 18th EFTF, 2004), while the phase decimated by m,
//    z[k] = x[k m], has at least kMinLag1Points points: z is differenced until the lag-1
//    autocorrelation r1 of the result gives delta = r1 / (1 + r1) < 0.25, or d_max differences
//    were taken (2 for the Allan family, 3 for Hadamard); then alpha = 2 - 2 d - round(2 delta).
//    No trend is removed first (Stable32's results need the raw decimated phase).
// 2. Otherwise the B1 bias ratio (J. A. Barnes, NBS TN 375, 1969): the sample variance of the
//    floor((N-1)/m) non-overlapping frequency averages over their Allan variance, against its
//    expectation B1(n, mu) = n (1 - n^mu) / (2 (n-1) (1 - 2^mu)) for the Allan tau exponent mu
//    (alpha 2 and 1 -> -2, 0 -> -1, -1 -> 0, -2 -> 1); the nearest in the geometric sense wins.
//    B1 cannot split white from flicker PM (both mu = -2); the R(n) ratio MVAR / AVAR at the
//    same m does: expected 1/m for white PM, 3 ln(256/27) / (2 (1.038 + 3 ln(pi m))) for flicker
//    PM (bandwidth f_h = 1 / (2 tau0)); again the nearer in the geometric sense.
// The result is clamped to [-2, 2], the range Stable32 reports.
//
// Two details are not in the papers but reproduce Stable32's tables (inferred from them:
// PHASE.DAT, Keysight TIC, OCXO, pink FM, GPS and Cs 5071A, about 4500 rows; 99.5 % agree,
// all of the rows that carry confidence bounds):
//  - the B1 expectations are evaluated at n = the estimator's term count (Stable32's `#`
//    column: N - 2m for OADEV, floor((N-1)/m) - 1 for ADEV, ...), while the ratio itself uses
//    the non-overlapping averages;
//  - with very few averages Stable32 keeps the noise type of the previous (shorter) tau of the
//    run instead: see keeps_previous_noise_type.

#include <cstddef>
#include <span>
#include <vector>

#include "stochnav/stats/deviation.hpp"

namespace stochnav {

/// Fewest decimated phase points for the lag-1 autocorrelation method.
inline constexpr std::size_t kMinLag1Points = 30;

enum class NoiseIdMethod { kLag1Autocorrelation, kB1Ratio, kB1AndRn };

/// The integer noise exponents low <= alpha <= high an identification cannot rule out.
struct AlphaRange {
  int low = -2;
  int high = 2;
};

struct NoiseId {
  int alpha = 0;  ///< identified exponent, -2 .. 2
  NoiseIdMethod method = NoiseIdMethod::kLag1Autocorrelation;
  /// Lag-1 method: the unrounded estimate 2 - 2 d - 2 delta. Otherwise the measured B1 ratio.
  double statistic = 0.0;
  /// The plausible exponents (plausible_alphas), always containing alpha.
  AlphaRange plausible;
};

/// Noise type of `phase` (N points) at averaging factor m, for the deviation `kind` (which sets
/// d_max and the B1 term count), with its plausible range (plausible_alphas, widened to contain
/// alpha). Requires m >= 1 and N >= 2m + 2 (throws std::invalid_argument
/// otherwise). Cost O(N / m), plus O(N) when the R(n) ratio is needed.
NoiseId identify_noise(Deviation kind, std::span<const double> phase, std::size_t m);

/// identify_noise at each of `m_values` (any order), computed together: the lag-1 statistics of
/// all factors come from two passes over the record, block by block, spread over the stats
/// threads (parallel.hpp). Equal to identify_noise up to the rounding of the sums (the same
/// alpha but at an exact tie), and bitwise the same for every thread count. Same throws.
std::vector<NoiseId> identify_noises(Deviation kind, std::span<const double> phase,
                                     std::span<const std::size_t> m_values);

/// How far the identification at m can be trusted: the integer alphas within the approximate
/// 95 % interval of the lag-1 estimate alpha^ = 2 - 2 d - 2 delta at the difference order d where
/// the lag-1 method stops (whichever method Stable32 takes at this m). With n = the number of
/// d-th differences of the decimated phase and r their lag-1 autocorrelation,
///   sd(r) ~ sqrt((1 - r^2) / n)  (Bartlett, AR(1)),  sd(alpha^) ~ 2 sd(r) / (1 + r)^2,
/// and the range runs from round(alpha^ - 1.96 sd) to round(alpha^ + 1.96 sd), clamped to
/// [-2, 2]. Every alpha whose rounding cell the interval reaches is plausible: 30 decimated
/// points (Riley's minimum) leave sd ~ 0.37 for white noise, so white FM and flicker PM are
/// rarely told apart there; 1000 points leave sd ~ 0.06. [-2, 2] (nothing ruled out) when fewer
/// than 4 differences remain (the longest taus). Cost O(N / m). Throws std::invalid_argument
/// for m == 0.
AlphaRange plausible_alphas(Deviation kind, std::span<const double> phase, std::size_t m);

/// True where Stable32 reuses the noise type of the previous averaging factor of a run instead
/// of identifying one: the B1 method would rest on fewer than 8 (overlapping and modified
/// estimators) or 10 (ADEV, HDEV) averages floor((N-1)/m). compute_deviation applies it to
/// every point but the first.
bool keeps_previous_noise_type(Deviation kind, std::size_t m, std::size_t phase_count);

/// Lag-1 autocorrelation of a series (mean removed):
///   sum_{i<n-1} (z_i - mean)(z_{i+1} - mean) / sum_i (z_i - mean)^2.
/// 0 for fewer than 2 points or a constant series.
double lag1_autocorrelation(std::span<const double> series);

/// Expected B1 ratio for n frequency averages and Allan-variance tau exponent mu (-2 .. 2);
/// mu = 0 is the limit n ln n / (2 (n-1) ln 2).
double b1_expected(double n, int mu);

}  // namespace stochnav
