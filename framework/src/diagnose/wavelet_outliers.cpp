#include "stochnav/diagnose/wavelet_outliers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <queue>

#include "stochnav/core/errors.hpp"
#include "stochnav/stats/robust_wavelet_variance.hpp"

namespace stochnav {
namespace {

// Candidates kept while streaming: enough that neighbours merged still leave
// kOutlierSamplesListed events.
constexpr std::size_t kOutlierCandidatesKept = 8 * kOutlierSamplesListed;

struct OutlierCandidateOrder {
  bool operator()(const OutlierSample& a, const OutlierSample& b) const {
    return std::abs(a.z) > std::abs(b.z);  // a min-heap on |z|
  }
};

void locate_outlier_samples(std::span<const double> rate, double rate_hz, double start_time_s,
                            double robust_finest, double unit_per_rate,
                            WaveletOutlierCheck& check) {
  const double scale = 2.0 * std::sqrt(robust_finest) / unit_per_rate;
  if (!(scale > 0.0)) return;
  std::priority_queue<OutlierSample, std::vector<OutlierSample>, OutlierCandidateOrder> kept;
  for (std::size_t k = 1; k < rate.size(); ++k) {
    const double z = (rate[k] - rate[k - 1]) / scale;
    if (!(std::abs(z) > check.z_threshold)) continue;
    ++check.differences_beyond;
    if (kept.size() < kOutlierCandidatesKept) {
      kept.push({k, 0.0, z});
    } else if (std::abs(z) > std::abs(kept.top().z)) {
      kept.pop();
      kept.push({k, 0.0, z});
    }
  }
  std::vector<OutlierSample> candidates;
  while (!kept.empty()) {
    candidates.push_back(kept.top());
    kept.pop();
  }
  std::sort(
      candidates.begin(), candidates.end(),
      [](const OutlierSample& a, const OutlierSample& b) { return std::abs(a.z) > std::abs(b.z); });
  for (const OutlierSample& candidate : candidates) {
    if (check.worst.size() == kOutlierSamplesListed) break;
    const bool neighbour =
        std::any_of(check.worst.begin(), check.worst.end(), [&](const OutlierSample& listed) {
          const std::size_t gap = listed.index > candidate.index ? listed.index - candidate.index
                                                                 : candidate.index - listed.index;
          return gap <= kOutlierNeighbourSamples;
        });
    if (neighbour) continue;
    OutlierSample listed = candidate;
    listed.time_s = start_time_s + static_cast<double>(candidate.index) / rate_hz;
    check.worst.push_back(listed);
  }
}

}  // namespace

std::vector<WaveletLevelSplit> compare_wavelet_variances(
    std::span<const WaveletVariancePoint> classical, std::span<const WaveletVariancePoint> robust) {
  if (classical.size() != robust.size()) {
    throw ConfigError(
        "compare_wavelet_variances: the classical and robust levels differ in number");
  }
  std::vector<WaveletLevelSplit> levels;
  levels.reserve(classical.size());
  for (std::size_t i = 0; i < classical.size(); ++i) {
    const WaveletVariancePoint& c = classical[i];
    const WaveletVariancePoint& r = robust[i];
    if (c.level != r.level) {
      throw ConfigError("compare_wavelet_variances: the classical and robust levels differ");
    }
    WaveletLevelSplit split;
    split.level = c.level;
    split.scale_s = c.scale_s;
    split.edf = wavelet_variance_edf(c.coefficients, c.scale_samples);
    split.classical = c.variance;
    split.classical_lo = c.lower;
    split.classical_hi = c.upper;
    split.robust = r.variance;
    split.robust_lo = r.lower;
    split.robust_hi = r.upper;
    split.tested = split.edf >= kOutlierMinLevelEdf && r.variance > 0.0;
    split.flagged = split.tested && c.lower > r.upper;
    levels.push_back(split);
  }
  return levels;
}

WaveletOutlierCheck check_wavelet_outliers(std::span<const double> rate, double rate_hz,
                                           double start_time_s, double alpha,
                                           std::span<const WaveletVariancePoint> classical,
                                           std::span<const WaveletVariancePoint> robust,
                                           double unit_per_rate) {
  if (rate.size() < 4) throw InputError("check_wavelet_outliers: fewer than 4 samples");
  if (!(alpha > 0.0 && alpha < 0.5)) {
    throw ConfigError(fmt::format("check_wavelet_outliers: alpha {}; expected in (0, 0.5)", alpha));
  }
  WaveletOutlierCheck check;
  check.levels = compare_wavelet_variances(classical, robust);
  check.contaminated = std::any_of(check.levels.begin(), check.levels.end(),
                                   [](const WaveletLevelSplit& l) { return l.flagged; });
  const double differences = static_cast<double>(rate.size() - 1);
  check.z_threshold = boost::math::quantile(boost::math::complement(
      boost::math::normal_distribution<double>(), alpha / (2.0 * differences)));
  if (!check.levels.empty()) {
    locate_outlier_samples(rate, rate_hz, start_time_s, check.levels.front().robust, unit_per_rate,
                           check);
  }
  return check;
}

WaveletOutlierCheck check_wavelet_outliers(std::span<const double> rate, double rate_hz,
                                           double start_time_s, double alpha) {
  if (rate.size() < 4) throw InputError("check_wavelet_outliers: fewer than 4 samples");
  const auto classical = haar_wavelet_variance(rate, rate_hz);
  const auto robust = robust_haar_wavelet_variance(rate, rate_hz);
  return check_wavelet_outliers(rate, rate_hz, start_time_s, alpha, classical, robust);
}

std::pair<double, double> WaveletOutlierCheck::flagged_scale_range_s() const {
  double low = 0.0, high = 0.0;
  for (const WaveletLevelSplit& level : levels) {
    if (!level.flagged) continue;
    if (low == 0.0) low = level.scale_s;
    high = level.scale_s;
  }
  return {low, high};
}

std::pair<double, double> WaveletOutlierCheck::largest_excess() const {
  double excess = 0.0, scale = 0.0;
  for (const WaveletLevelSplit& level : levels) {
    if (level.flagged && level.excess() > excess) {
      excess = level.excess();
      scale = level.scale_s;
    }
  }
  return {excess, scale};
}

std::string WaveletOutlierCheck::summary() const {
  std::size_t tested = 0, flagged = 0;
  for (const WaveletLevelSplit& level : levels) {
    tested += level.tested ? 1 : 0;
    flagged += level.flagged ? 1 : 0;
  }
  std::string samples;
  if (!worst.empty()) {
    samples = fmt::format(
        " {} first difference(s) lie beyond the robust z-score {:.1f} (Bonferroni over the "
        "record); the worst at t =",
        differences_beyond, z_threshold);
    for (std::size_t i = 0; i < worst.size(); ++i) {
      samples +=
          fmt::format("{} {:.2f} s (z = {:.1f})", i == 0 ? "" : ",", worst[i].time_s, worst[i].z);
    }
    samples += ".";
  } else {
    samples =
        fmt::format(" No first difference lies beyond the robust z-score {:.1f}.", z_threshold);
  }
  if (!contaminated) {
    return fmt::format(
        "The classical and robust Haar wavelet variances agree within their 95 % intervals at "
        "all {} levels tested: no sign of outliers.{}",
        tested, samples);
  }
  const auto [low, high] = flagged_scale_range_s();
  const auto [excess, at] = largest_excess();
  if (explained_by_nonstationary) {
    return fmt::format(
        "The classical Haar wavelet variance exceeds the robust one beyond their 95 % intervals "
        "at {} of {} levels tested (scales {:.3g} .. {:.3g} s), by up to {:.0f} % (at {:.3g} s): "
        "the nonstationary term of the model, a stretch of louder noise, which the robust "
        "estimator down-weights as it does outliers.{} Nothing more to do for it; if the "
        "listed samples are not in that stretch, look at the record around them.",
        flagged, tested, low, high, 100.0 * excess, at, samples);
  }
  return fmt::format(
      "Outliers or contamination: the classical Haar wavelet variance exceeds the robust one "
      "beyond their 95 % intervals at {} of {} levels tested (scales {:.3g} .. {:.3g} s), by up "
      "to {:.0f} % (at {:.3g} s); the Allan variance at half those scales is inflated the same "
      "way, so the model above describes the outliers as noise.{} What to do: look at the record "
      "around "
      "those times; fit with `stochnav fit --method gmwm --robust` (the robust wavelet "
      "variance), or remove the outliers and diagnose again.",
      flagged, tested, low, high, 100.0 * excess, at, samples);
}

}  // namespace stochnav
