#pragma once
// Allan-family deviations of a phase record, with the averaging-factor sets, term counts, noise
// identification, equivalent degrees of freedom and 68.3 % confidence intervals that Stable32
// (W. Riley, Hamilton Technical Services) reports, so results can be checked against its tables.
//
// Conventions (NIST SP 1065, "Handbook of Frequency Stability Analysis", W. Riley, 2008):
//   x[0 .. N-1]  phase points taken every tau0 seconds (unit U*s for a rate in unit U; clock
//                phase in s). Rate records are integrated first (phase.hpp).
//   m            averaging factor, tau = m * tau0 (s).
//   deviation    in the unit of the rate (U), except TDEV, a time deviation in U*s.
//
//   kAdev   Allan, non-overlapping:   AVAR = sum over i = 0, m, 2m, ... of
//           (x[i+2m] - 2 x[i+m] + x[i])^2 / (2 tau^2 n),  n = floor((N-1)/m) - 1 terms
//   kOadev  Allan, overlapping: same sum over every i, n = N - 2m terms
//   kMdev   modified Allan: MVAR = sum over j of (sum_{i=j}^{j+m-1} x[i+2m] - 2 x[i+m] + x[i])^2
//           / (2 m^2 tau^2 n),  n = N - 3m + 1 terms
//   kTdev   time deviation: TDEV = tau * MDEV / sqrt(3) (same terms as MDEV)
//   kHdev   Hadamard, non-overlapping: HVAR = sum over i = 0, m, 2m, ... of
//           (x[i+3m] - 3 x[i+2m] + 3 x[i+m] - x[i])^2 / (6 tau^2 n),  n = floor((N-1)/m) - 2
//   kOhdev  Hadamard, overlapping: same sum over every i, n = N - 3m terms
//   kTotdev total (D. A. Howe): TOTVAR = sum_{i=1}^{N-2} (x*[i-m] - 2 x[i] + x*[i+m])^2
//           / (2 tau^2 (N - 2)),  n = N - 2 terms at every m, where x* is the phase extended
//           by odd reflection about both end points: x*[-j] = 2 x[0] - x[j] and
//           x*[N-1+j] = 2 x[N-1] - x[N-1-j] (NIST SP 1065 Eq. 25)
//   kMtotdev modified total (Howe & Vernotte): for each of the N - 3m + 1 subsequences of 3m
//           phase points, the linear trend of its half means is removed (slope = difference of
//           the means of the first and last floor(3m/2) points over their distance
//           3m - floor(3m/2)), the result z is extended to 9m points by even reflection at both
//           ends (reverse(z), z, reverse(z)) and the 6m terms (S1 - 2 S2 + S3) / m, S the sums
//           of three adjacent m-point blocks, are averaged squared; MTOTVAR is the mean of
//           those averages over the subsequences / (2 tau^2) (SP 1065 Eq. 27). No bias
//           correction (Stable32's octave and decade runs), n = N - 3m + 1 terms
//   kTtotdev time total: TTOTDEV = tau * MTOTDEV / sqrt(3) (SP 1065 Eq. 28 with tau^2)
//   kHtotdev Hadamard total (Howe et al., PTTI 2000): the kMtotdev construction applied to the
//           N - 1 frequency values y[i] = (x[i+1] - x[i]) / tau0 with 1/6 in place of 1/(2 tau^2);
//           n = N - 3m terms. At m = 1 it is OHDEV, as in Stable32. Stable32's bias correction
//           HTOTVAR / (1 + a) for m > 1, a = -0.005, -0.149, -0.229 for alpha = 0, -1, -2
//           (white, flicker, random-walk FM; none for PM noise), with the identified alpha
//   kHtotdevNobias the same without the bias correction
//   kTheo1Nobias Theo1 (Howe & Tasset), even m >= 10 only, tau = 0.75 m tau0:
//           THEO1 = sum_{i=0}^{N-m-1} sum_{j=1}^{m/2} (x[i] - x[i+j] + x[i+m] - x[i+m-j])^2 / j
//           / (0.75 (N - m) (m tau0)^2)  (SP 1065 Eq. 30),  n = (N - m) m / 2 terms
//   kTheo1 Theo1 with Stable32's bias removal (ThêoBR, Taylor & Howe): THEO1 * k, one factor
//           for the whole record, k = mean over i = 0 .. floor(N/6) - 3 of
//           OAVAR(9 + 3i) / THEO1(12 + 4i) (equal taus; needs N >= 24, else k = 1). Its alpha
//           is the nominal noise type nearest k (theo1_bias_noise_type)
//   kMtie   maximum time interval error: the largest max - min of the phase over the N - m
//           windows of m + 1 points (unit of the phase, U*s); n = N - m
//   kTierms rms time interval error: sqrt(mean of (x[i+m] - x[i])^2), n = N - m terms (U*s)
// MTIE and TIE rms carry no noise type, EDF or interval (alpha 0, edf and bounds NaN).

#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "stochnav/stats/confidence.hpp"

namespace stochnav {

enum class Deviation {
  kAdev,
  kOadev,
  kMdev,
  kTdev,
  kHdev,
  kOhdev,
  kTotdev,
  kMtotdev,
  kTtotdev,
  kHtotdev,
  kHtotdevNobias,
  kTheo1,
  kTheo1Nobias,
  kMtie,
  kTierms,
};

/// Which averaging factors to evaluate.
enum class TauSpacing {
  kOctave,  ///< m = 1, 2, 4, 8, ... (Stable32 "octave")
  kDecade,  ///< m = 1, 2, 4, 10, 20, 40, 100, ... (Stable32 "decade")
  kDense,   ///< about 10 log-spaced distinct integers per decade (stochnav's own choice)
  kAll,     ///< Stable32 "all tau": every m at first, then ever sparser, about 490 points
            ///< spread over the decades of tau the result spans (see averaging_factors)
};

/// "adev", "oadev", "mdev", "tdev", "hdev", "ohdev", "totdev", "mtotdev", "ttotdev", "htotdev",
/// "htotdev_nobias", "theo1", "theo1_nobias", "mtie", "tierms".
std::string_view deviation_name(Deviation kind);
/// The inverse of deviation_name; nullopt for anything else (case-sensitive).
std::optional<Deviation> deviation_from_name(std::string_view name);
/// deviation_from_name, or throws ConfigError naming the text and the accepted names.
Deviation parse_deviation(std::string_view name);

/// Which noise type's EDF sets a point's confidence interval.
enum class EdfRule {
  /// The smallest EDF of the identified noise type and the types the identification cannot
  /// rule out at that m (noise_id.hpp, plausible_alphas), less the PM types (alpha 1, 2) once a
  /// shorter tau of the run has ruled PM out (a PM variance falls as tau^-2 or faster, every FM
  /// one no faster than tau^-1). At long taus the identification rests on a few decimated points
  /// and can slip (to white or flicker PM on a rate record, whose EDF grows with the number of
  /// overlapping terms rather than with N / m: an interval 25 times too narrow); this rule keeps
  /// the interval as wide as the least informative plausible type makes it, and never narrower
  /// than Stable32's. The default (docs/allan.md).
  kPlausibleMinimum,
  /// The EDF of the identified noise type alone, as Stable32 computes it (its tables are
  /// reproduced this way).
  kStable32,
};
/// "plausible" or "stable32" (the CLI's --edf), or throws ConfigError naming the text.
EdfRule parse_edf_rule(std::string_view name);

/// Order d of the phase difference the variance is built on: 2 (Allan family), 3 (Hadamard).
int difference_order(Deviation kind);
/// True for the estimators that use every start index (OADEV, MDEV, TDEV, OHDEV, TOTDEV).
bool is_overlapping(Deviation kind);
/// True for MDEV and TDEV (the phase is averaged over m points before differencing).
bool is_modified(Deviation kind);
/// True for Theo1 (corrected or not): tau = 0.75 m tau0, m even and >= 10.
bool is_theo1(Deviation kind);
/// False for MTIE and TIE rms: no noise type, EDF or confidence interval.
bool has_confidence_interval(Deviation kind);
/// tau (s) of averaging factor m: m tau0, or 0.75 m tau0 for Theo1.
double tau_of(Deviation kind, std::size_t m, double tau0_s);

/// Number of terms (squared differences) of the estimator at averaging factor m on N phase
/// points, as Stable32 reports it in its `#` column: OADEV N - 2m; ADEV floor((N-1)/m) - 1;
/// MDEV and TDEV N - 3m + 1; HDEV floor((N-1)/m) - 2; OHDEV N - 3m; TOTDEV N - 2 for every
/// m <= N - 2 (the reflected record is long enough); MTOTDEV, TTOTDEV N - 3m + 1; HTOTDEV
/// N - 3m; Theo1 (N - m) m / 2 for even m >= 10 (0 for odd m or m < 10); MTIE, TIE rms N - m.
/// 0 when m == 0 or the record is too short for even one term.
std::size_t term_count(Deviation kind, std::size_t m, std::size_t phase_count);

/// Largest averaging factor Stable32 evaluates on N phase points: the largest m with
/// 5m < N - 1 (ADEV, HDEV), 4m < N - 1 (the other overlapping and modified estimators) or
/// 2m < N - 1 (TOTDEV); 3m <= N - 1 (MTOTDEV, TTOTDEV, HTOTDEV); m <= N - 3 (Theo1); m <= N - 1
/// (MTIE); TIE rms as OADEV. Inferred from Stable32 tables: PHASE.DAT (N = 1001) stops ADEV at
/// m = 197 < 200, OADEV at 247, TOTDEV at 499, MTOTDEV at 332 and Theo1 at 998.
/// 0 when the record is too short.
std::size_t max_averaging_factor(Deviation kind, std::size_t phase_count);

/// The averaging factors Stable32 would use for `kind` on N phase points, ascending, all
/// <= max_averaging_factor(kind, N); empty when N is too short.
///   kOctave, kDecade: powers of two; 1, 2, 4 times powers of ten. Theo1 takes the even
///     factors >= 10 of those sets (octave 16, 32, ...), MTIE's octave set is 2^k - 1 (windows
///     of 2^k points, Stable32's "fast" MTIE).
///   kAll: m = 1, then m <- m + floor(m / K) + 1 with K = floor(213 / D), where D is the number
///     of decades of tau the result spans, ceil(log10(m_max * tau0_s)) - floor(log10(tau0_s)):
///     about 490 / D points per decade. Inferred from Stable32's all-tau tables, which it
///     reproduces exactly (D = 3 .. 6, records of 1001 .. 556990 points, tau0 = 1 s and 42 s);
///     tau0_s matters only here.
///   kDense: round(10^(k/10)), k = 0, 1, 2, ..., duplicates removed.
std::vector<std::size_t> averaging_factors(Deviation kind, TauSpacing spacing,
                                           std::size_t phase_count, double tau0_s = 1.0);

/// The raw estimator (see the formulas above) at averaging factor m, tau = m * tau0_s. Throws
/// std::invalid_argument when term_count(kind, m, phase.size()) == 0 (m == 0 included).
double deviation_value(Deviation kind, std::span<const double> phase, double tau0_s, std::size_t m);

/// deviation_value at each of `m_values` (any order), sharing the passes over the data: the
/// overlapping Allan and Hadamard sums of all factors are accumulated block by block, so each
/// cache-sized block of the phase is read from memory once for all of them. Same throws.
/// Cost O(N) per factor, no allocation per factor; prefer it to a loop of deviation_value for
/// long records (the 22 octave OADEV factors of 1e7 points: about 0.02 s of CPU here, four
/// factors per sweep of a block). The work runs over the stats threads (parallel.hpp) in tasks
/// fixed by the record length: bitwise the same result for every thread count. ADEV, HDEV, MDEV,
/// TDEV, TOTDEV: one task per factor (TOTDEV O(N) per factor, the reflections read in place).
std::vector<double> deviation_values(Deviation kind, std::span<const double> phase, double tau0_s,
                                     std::span<const std::size_t> m_values);

/// One row of a Stable32-style result table.
struct DeviationPoint {
  std::size_t m = 0;       ///< averaging factor
  double tau_s = 0.0;      ///< m * tau0 (s); 0.75 m tau0 for Theo1
  double deviation = 0.0;  ///< the estimate (unit of the rate; U*s for TDEV, TTOTDEV, MTIE, TIE)
  std::size_t terms = 0;   ///< term_count(kind, m, N)
  int alpha = 0;           ///< identified power-law noise, S_y(f) ~ f^alpha, in [-2, 2]
  double edf = 0.0;        ///< equivalent degrees of freedom of the variance (Greenhall)
  int edf_alpha = 0;       ///< the noise type whose EDF `edf` is (EdfRule); alpha for kStable32
  double lower = 0.0;      ///< lower bound of the chi-square confidence interval (deviation units)
  double upper = 0.0;      ///< upper bound
};

/// Deviation, noise type (noise_id.hpp), EDF (edf.hpp, chosen by `edf_rule`) and the chi-square
/// interval (confidence.hpp) at each averaging factor, in the order given. Like Stable32, a
/// factor with very few averages takes the noise type of the one before it
/// (keeps_previous_noise_type), so pass a run's factors in ascending order; its plausible types
/// are still read at its own m. `confidence` is the two-sided probability of [lower, upper];
/// Stable32 uses 0.683. Throws std::invalid_argument when an m leaves no terms.
/// Cost: the deviations (see deviation_values) plus O(N / m) per factor for the noise type, whose
/// pass over the phase runs inside the deviations' pass (each stretch read once for both).
std::vector<DeviationPoint> compute_deviation(Deviation kind, std::span<const double> phase,
                                              double tau0_s, std::span<const std::size_t> m_values,
                                              double confidence = kStable32Confidence,
                                              EdfRule edf_rule = EdfRule::kPlausibleMinimum);

}  // namespace stochnav
