#pragma once
// The Haar wavelet variance (maximal-overlap discrete wavelet transform, MODWT) of a rate record
// at dyadic scales, with the chi-square confidence interval of the R package `wv` (SMAC-Group;
// Guerrier et al., JASA 2013), computed the way that package computes it.
//
// Conventions:
//   y[0 .. N-1]  rate samples (unit U: deg/s, m/s^2, fractional frequency, ...) taken every
//                tau0 seconds.
//   level j      j = 1 .. J, J = floor(log2 N) - 1 (the `wv` default); scale 2^j samples,
//                tau_j = 2^j tau0 (s).
//   W_{j,t}      the Haar MODWT coefficient at level j, time t = 2^j - 1 .. N - 1 (the boundary
//                coefficients, whose filter would wrap around the record, are left out):
//                  W_{j,t} = (mean of y[t-2^(j-1)+1 .. t] - mean of y[t-2^j+1 .. t-2^(j-1)]) / 2
//                (unit U); n_j = N - 2^j + 1 coefficients.
//   nu^2_j       classical estimate sum_t W_{j,t}^2 / n_j (unit U^2). In expectation it is half
//                the Allan variance at averaging time tau_j / 2 (the filters are the same), so a
//                noise model's implied wavelet variance is AVAR(tau_j / 2) / 2.
//   interval     [eta nu^2 / chi2_inv(1 - a/2, eta), eta nu^2 / chi2_inv(a/2, eta)] with
//                eta = max(n_j / 2^j, 1) (Percival's "eta3"), a = 0.05 for the 95 % interval.

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace stochnav {

/// The `wv` package's confidence level (95 %).
inline constexpr double kWaveletVarianceConfidence = 0.95;

/// One level of a wavelet-variance result.
struct WaveletVariancePoint {
  int level = 0;                  ///< j >= 1
  std::size_t scale_samples = 0;  ///< 2^j
  double scale_s = 0.0;           ///< 2^j tau0 (s)
  std::size_t coefficients = 0;   ///< n_j = N - 2^j + 1
  double variance = 0.0;          ///< nu^2_j (U^2)
  double lower = 0.0;             ///< lower bound of the interval (U^2)
  double upper = 0.0;             ///< upper bound (U^2)
};

/// J = floor(log2 N) - 1 for N samples (0 when N < 4): the levels `wv` reports.
int wavelet_variance_levels(std::size_t samples);

/// eta3 = max(n_j / 2^j, 1), the equivalent degrees of freedom `wv` gives level j.
double wavelet_variance_edf(std::size_t coefficients, std::size_t scale_samples);

/// [eta nu^2 / chi2_inv((1 + confidence) / 2, eta), eta nu^2 / chi2_inv((1 - confidence) / 2,
/// eta)] with eta = wavelet_variance_edf. Requires 0 < confidence < 1.
void set_wavelet_variance_interval(WaveletVariancePoint& point,
                                   double confidence = kWaveletVarianceConfidence);

/// Classical Haar wavelet variance, streamed: push the rate samples block by block, then ask for
/// the levels. The Haar pyramid runs level by level (V_0 = y; W_j and V_j from V_{j-1} at lag
/// 2^(j-1): W_{j,t} = (V_{j-1,t} - V_{j-1,t-2^(j-1)}) / 2, V_{j,t} = their mean), the way the
/// `wv` package filters, so the numbers agree with it to rounding (no running sum of the record,
/// whose cancellation would cost digits on records with a large bias). Each squared coefficient
/// is summed as it is made; nothing per coefficient is kept.
/// Memory: a delay line of 2^(j-1) values at each level j <= max_level, 2^max_level values in
/// all, independent of the record length once max_level is fixed. With max_level =
/// wavelet_variance_levels(N) that is at most N / 2 values: the largest scale's Haar filter spans
/// 2^J samples, so an exact one-pass estimator cannot keep less. A bound on N (a file's line
/// count) is enough to choose it.
class HaarWaveletVarianceAccumulator final {
 public:
  /// Levels above max_level (>= 1) are not computed.
  explicit HaarWaveletVarianceAccumulator(int max_level);
  ~HaarWaveletVarianceAccumulator();
  HaarWaveletVarianceAccumulator(const HaarWaveletVarianceAccumulator&) = delete;
  HaarWaveletVarianceAccumulator& operator=(const HaarWaveletVarianceAccumulator&) = delete;

  /// Appends rate samples (any block sizes: the result does not depend on them).
  void push(std::span<const double> rate);

  /// Samples pushed so far.
  std::size_t samples() const;
  /// Values held in the delay lines now (<= 2^max_level), for the memory guarantee's tests.
  std::size_t buffered_values() const;

  /// Levels 1 .. min(max_level, wavelet_variance_levels(samples())), each with its 95 %
  /// interval; scale_s = 2^j / rate_hz. Empty when fewer than 4 samples were pushed.
  std::vector<WaveletVariancePoint> result(double rate_hz) const;

 private:
  class Level;
  int max_level_;
  std::size_t samples_ = 0;
  std::vector<std::unique_ptr<Level>> levels_;
  std::vector<double> scratch_[2];
};

/// The classical wavelet variance of a whole record in memory (levels 1 .. J).
std::vector<WaveletVariancePoint> haar_wavelet_variance(std::span<const double> rate,
                                                        double rate_hz);

}  // namespace stochnav
