#pragma once
// Stationarity across DAVAR windows: do the record's windows agree with each other (after the
// model's own nonstationary scaling), or is a stretch of the record louder or quieter?
//
// The record is cut into K non-overlapping windows (K = 32 by default, each at least 500
// samples). In window k, A_k is the overlapping Allan variance at the shortest averaging time
// (m = 1: the DAVAR of those windows at tau0), the average of u_i = (y_{i+1} - y_i)^2 / 2 over the
// window's rate samples y. Its variance is estimated from the window's own data, model-free:
//   Var A_k = (1/n) [gamma_0 + 2 sum_{l=1}^{4} gamma_l]
// with gamma_l the autocovariances of u within the window (first differences of every noise
// type of the vocabulary decorrelate within a few lags at m = 1), so s_k^2 = Var A_k / A_k^2 is
// the variance of ln A_k. An outlier raises both A_k and its s_k, so isolated spikes do not pass
// for nonstationarity.
//
// With f_k = mean of scale(t)^2 over window k under the model's nonstationary term (1 without
// one), the residuals r_k = ln A_k - ln f_k should be equal up to their scatter. The test is
//   X = sum_k (r_k - rbar)^2 / s_k^2,  rbar = the s_k^-2 weighted mean,  X ~ chi2(K - 1),
// reported as the reduced chi-square G_stat = X / (K - 1). A window deviates when
// |r_k - median(r)| / s_k > z_deviating (4 by default): the median keeps a loud stretch from
// hiding itself.

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "stochnav/model/noise_model.hpp"

namespace stochnav {

/// Short-tau Allan variances of the record's windows (record time from 0 at the first sample).
struct WindowVariances {
  std::vector<double> start_s;  ///< window start (s)
  std::vector<double> end_s;    ///< window end (s)
  std::vector<double> avar;     ///< A_k at tau0, natural units^2
  std::vector<double> log_sd;   ///< s_k, standard deviation of ln A_k
};

/// A_k and s_k of `windows` equal windows of the rate samples (natural units) of a record at
/// rate_hz. Fewer windows are used when the record is short (each keeps >= 500 samples); none
/// when it has fewer than 2000 samples.
WindowVariances window_variances(std::span<const double> rate, double rate_hz, std::size_t windows);

struct StationarityTest {
  std::vector<double> z;            ///< (r_k - median r) / s_k per window
  std::vector<bool> deviating;      ///< |z_k| > z_deviating
  double reference_log = 0.0;       ///< median of r_k: ln of the quiet level A at tau0
  double chi_square = 0.0;          ///< X
  double dof = 0.0;                 ///< K - 1 (0 without windows)
  double reduced_chi_square = 0.0;  ///< X / (K - 1); 1 without windows
  double p_value = 1.0;             ///< P(chi2(K - 1) > X)
};

/// The test of the file comment under `model`.
StationarityTest stationarity_test(const WindowVariances& windows, const NoiseModel& model,
                                   double z_deviating = 4.0);

/// A nonstationary term that makes the deviating windows agree: each deviating window gets the
/// scale sqrt(A_k / exp(reference_log)) (its variance relative to the quiet level); adjacent
/// deviating windows whose scales agree within 10 % merge into one segment; a single window at
/// the edge of a longer segment whose scale lies between 1 and the segment's is taken as partly
/// covered, the fraction f from r^2 = 1 + f (s^2 - 1), and the segment's edge moves into it.
/// Windows that do not deviate keep the model's scale (its segments inside them are kept).
/// nullopt when no window deviates.
std::optional<NonstationaryTerm> nonstationary_candidate(const WindowVariances& windows,
                                                         const StationarityTest& test,
                                                         const NoiseModel& model);

}  // namespace stochnav
