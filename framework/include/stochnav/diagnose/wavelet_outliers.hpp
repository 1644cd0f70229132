#pragma once
// Outliers and contamination read off the split between the classical and the robust Haar
// wavelet variance (stats/wavelet_variance.hpp, stats/robust_wavelet_variance.hpp; the robust
// GMWM of Guerrier, Molinari, Victoria-Feser 2014), for `stochnav diagnose` (record mode).
//
// Why it works: on Gaussian noise both estimates target the same nu^2_j; the robust one (Tukey
// biweight, efficiency 0.6) down-weights coefficients far out in the tails, the classical one
// squares them. Isolated spikes or bursts put a few huge coefficients into the finest levels, so
// the classical estimate rises above the robust one there and not at long scales.
//
// Rule (per level j, variances in the record's unit squared): the level is flagged when the
// 95 % intervals are disjoint with the classical above, classical_lo_j > robust_hi_j, at a level
// with eta_j = wavelet_variance_edf >= kOutlierMinLevelEdf. The record is contaminated when at
// least one level is flagged. Size of this test on Gaussian records: the two estimates come
// from the same coefficients; the robust one's log has variance (1 / eff) times the classical
// one's, and (Hausman) their difference has variance (1 / eff - 1) Var(ln nu_c). Disjoint
// intervals need ln(nu_c / nu_r) > z_0.975 (1 + sqrt(1 / eff)) sd(ln nu_c), that is
// 1.96 x 2.29 / sqrt(0.667) = 5.5 standard deviations of the difference: about 2e-8 a level.
// The rule is conservative on purpose: a record of 1e6 samples resolves a 1 % split, and real
// MEMS noise is seldom exactly Gaussian (the ADIS16405 gyro X splits by 0.55 % at the finest
// level, 3.4 sd, and is not flagged). The tests (tests/diagnose/wavelet_findings_test.cpp)
// measure detection and false alarms on simulated records.
//
// Locating the worst samples: the robust z-score of the first differences,
//   z_t = (y_t - y_(t-1)) / (2 sqrt(nu_r,1)),
// since W_(1,t) = (y_t - y_(t-1)) / 2 and nu_r,1 is a robust variance of W_(1,t) (its mean is
// 0 by construction): no sort of the record, one pass. A sample is an outlier when
// |z_t| > Phi^-1(1 - alpha / (2 N)) (Bonferroni over the N - 1 differences). A spike at sample k
// makes two large differences (k and k + 1): neighbours within kOutlierNeighbourSamples of a
// larger one are not listed again.

#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "stochnav/stats/wavelet_variance.hpp"

namespace stochnav {

/// Levels whose equivalent degrees of freedom are below this are not tested (too few
/// independent coefficients for the chi-square interval to hold).
inline constexpr double kOutlierMinLevelEdf = 16.0;
/// Worst samples listed at most.
inline constexpr std::size_t kOutlierSamplesListed = 5;
/// Differences closer than this to a listed larger one belong to the same event.
inline constexpr std::size_t kOutlierNeighbourSamples = 2;

/// One level compared: variances in the record's unit squared, intervals 95 %.
struct WaveletLevelSplit {
  int level = 0;
  double scale_s = 0.0;  ///< 2^j tau0 (s)
  double edf = 0.0;      ///< eta_j
  double classical = 0.0, classical_lo = 0.0, classical_hi = 0.0;
  double robust = 0.0, robust_lo = 0.0, robust_hi = 0.0;
  bool tested = false;   ///< edf >= kOutlierMinLevelEdf
  bool flagged = false;  ///< tested and classical_lo > robust_hi
  /// classical / robust - 1: how much the classical estimate exceeds the robust one.
  double excess() const { return classical / robust - 1.0; }
};

/// A first difference far out in the tails.
struct OutlierSample {
  std::size_t index = 0;  ///< sample k of the difference y_k - y_(k-1)
  double time_s = 0.0;    ///< record time of sample k (s)
  double z = 0.0;         ///< robust z-score of the difference
};

struct WaveletOutlierCheck {
  std::vector<WaveletLevelSplit> levels;
  bool contaminated = false;  ///< some level flagged
  double z_threshold = 0.0;   ///< Phi^-1(1 - alpha / (2 N))
  /// Differences with |z| > z_threshold (a spike counts twice: its rise and its fall).
  std::size_t differences_beyond = 0;
  /// The worst events, largest |z| first, at most kOutlierSamplesListed, neighbours merged.
  std::vector<OutlierSample> worst;
  /// Set by diagnose when its final model has a nonstationary term: a stretch of louder noise
  /// is contamination for the robust estimator too (a scale mixture; the split then shows at
  /// every scale, not only the short ones), and the loop has already named it.
  bool explained_by_nonstationary = false;

  /// The flagged levels' scale range (s), {0, 0} when none.
  std::pair<double, double> flagged_scale_range_s() const;
  /// The largest excess over the flagged levels (0 when none) and its scale (s).
  std::pair<double, double> largest_excess() const;
  /// One paragraph: the verdict, the scales, by how much, the samples and what to do.
  std::string summary() const;
};

/// Compares `classical` and `robust` (the levels of the same record, same order) level by level.
/// Requires equal sizes and levels.
std::vector<WaveletLevelSplit> compare_wavelet_variances(
    std::span<const WaveletVariancePoint> classical, std::span<const WaveletVariancePoint> robust);

/// The check on rate samples `rate` (record unit) at rate_hz, the first at start_time_s:
/// computes both wavelet variances, compares them and locates the worst samples.
/// `alpha`: false-alarm probability of the sample-level threshold, (0, 0.5). Throws InputError
/// for fewer than 4 samples.
WaveletOutlierCheck check_wavelet_outliers(std::span<const double> rate, double rate_hz,
                                           double start_time_s, double alpha);

/// The same with both wavelet variances given (from check_wavelet_outliers' caller, which may
/// need them again). `unit_per_rate`: the factor from the samples of `rate` to the unit of the
/// wavelet variances (1 when they are the same; 1 / si_per_unit(U) for natural-unit samples and
/// variances in U^2), so that the record need not be copied to another unit.
WaveletOutlierCheck check_wavelet_outliers(std::span<const double> rate, double rate_hz,
                                           double start_time_s, double alpha,
                                           std::span<const WaveletVariancePoint> classical,
                                           std::span<const WaveletVariancePoint> robust,
                                           double unit_per_rate = 1.0);

}  // namespace stochnav
