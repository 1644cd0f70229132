#include "stochnav/diagnose/stationarity.hpp"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>

#include "stochnav/diagnose/effective_model.hpp"

namespace stochnav {
namespace {

constexpr std::size_t kMinWindowSamples = 500;
constexpr std::size_t kMaxLag = 4;

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  double result = *middle;
  if (values.size() % 2 == 0) {
    result = 0.5 * (result + *std::max_element(values.begin(), middle));
  }
  return result;
}

}  // namespace

WindowVariances window_variances(std::span<const double> rate, double rate_hz,
                                 std::size_t windows) {
  WindowVariances result;
  if (rate.size() < 4 * kMinWindowSamples || windows < 2) return result;
  windows = std::min(windows, rate.size() / kMinWindowSamples);
  const std::size_t length = rate.size() / windows;
  std::vector<double> u;
  for (std::size_t k = 0; k < windows; ++k) {
    const std::size_t begin = k * length;
    const std::size_t end = k + 1 == windows ? rate.size() : begin + length;
    u.clear();
    for (std::size_t i = begin; i + 1 < end; ++i) {
      const double difference = rate[i + 1] - rate[i];
      u.push_back(0.5 * difference * difference);
    }
    const double n = static_cast<double>(u.size());
    double mean = 0.0;
    for (double value : u) mean += value;
    mean /= n;
    double long_run = 0.0;
    for (std::size_t lag = 0; lag <= kMaxLag; ++lag) {
      double sum = 0.0;
      for (std::size_t i = 0; i + lag < u.size(); ++i) sum += (u[i] - mean) * (u[i + lag] - mean);
      long_run += (lag == 0 ? 1.0 : 2.0) * sum / n;
    }
    // The truncated sum can come out small or negative for strongly anticorrelated u; never
    // claim more precision than a tenth of the independent-sample variance.
    double gamma0 = 0.0;
    for (double value : u) gamma0 += (value - mean) * (value - mean);
    gamma0 /= n;
    long_run = std::max(long_run, 0.1 * gamma0);
    result.start_s.push_back(static_cast<double>(begin) / rate_hz);
    result.end_s.push_back(static_cast<double>(end) / rate_hz);
    result.avar.push_back(mean);
    result.log_sd.push_back(mean > 0.0 ? std::sqrt(long_run / n) / mean : 1.0);
  }
  return result;
}

StationarityTest stationarity_test(const WindowVariances& windows, const NoiseModel& model,
                                   double z_deviating) {
  StationarityTest test;
  const std::size_t count = windows.avar.size();
  if (count < 2) {
    test.reduced_chi_square = 1.0;
    return test;
  }
  std::vector<double> residual(count);
  double weight_sum = 0.0;
  double weighted = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    const double factor = mean_scale_squared(model, windows.start_s[k], windows.end_s[k]);
    residual[k] = std::log(std::max(windows.avar[k], 1e-300)) - std::log(std::max(factor, 1e-300));
    const double weight = 1.0 / (windows.log_sd[k] * windows.log_sd[k]);
    weight_sum += weight;
    weighted += weight * residual[k];
  }
  const double mean = weighted / weight_sum;
  test.reference_log = median(residual);
  for (std::size_t k = 0; k < count; ++k) {
    const double s = windows.log_sd[k];
    test.chi_square += (residual[k] - mean) * (residual[k] - mean) / (s * s);
    test.z.push_back((residual[k] - test.reference_log) / s);
    test.deviating.push_back(std::abs(test.z.back()) > z_deviating);
  }
  test.dof = static_cast<double>(count - 1);
  test.reduced_chi_square = test.chi_square / test.dof;
  const boost::math::chi_squared_distribution<double> distribution(test.dof);
  test.p_value = boost::math::cdf(boost::math::complement(distribution, test.chi_square));
  return test;
}

std::optional<NonstationaryTerm> nonstationary_candidate(const WindowVariances& windows,
                                                         const StationarityTest& test,
                                                         const NoiseModel& model) {
  if (std::none_of(test.deviating.begin(), test.deviating.end(), [](bool d) { return d; })) {
    return std::nullopt;
  }
  // Per window: the scale it needs (deviating) or nothing (keep the model's own segments).
  struct Piece {
    double start_s, end_s, scale;
  };
  std::vector<Piece> pieces;
  for (std::size_t k = 0; k < windows.avar.size(); ++k) {
    if (!test.deviating[k]) continue;
    // The window's whole variance relative to the quiet level: the new segment replaces any
    // scaling the model had there.
    const double scale = std::sqrt(windows.avar[k] / std::exp(test.reference_log));
    if (!pieces.empty() && std::abs(pieces.back().end_s - windows.start_s[k]) < 1e-9 &&
        std::abs(scale / pieces.back().scale - 1.0) < 0.1) {
      const double a = pieces.back().end_s - pieces.back().start_s;
      const double b = windows.end_s[k] - windows.start_s[k];
      pieces.back().scale =
          std::sqrt((a * pieces.back().scale * pieces.back().scale + b * scale * scale) / (a + b));
      pieces.back().end_s = windows.end_s[k];
    } else {
      pieces.push_back({windows.start_s[k], windows.end_s[k], scale});
    }
  }
  // A window at the edge of a stretch that is only partly inside it shows a scale between 1 and
  // the stretch's: with r^2 = 1 + f (s^2 - 1) the covered fraction is f, so the stretch's edge
  // moves into that window by f of its width and the window's own piece goes.
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const Piece edge = pieces[i];
    const double width = edge.end_s - edge.start_s;
    const double r2 = edge.scale * edge.scale;
    for (std::size_t j : {i + 1, i - 1}) {
      if (j >= pieces.size()) continue;  // i - 1 wraps around for i == 0
      Piece& stretch = pieces[j];
      const double s2 = stretch.scale * stretch.scale;
      const bool before = std::abs(edge.end_s - stretch.start_s) < 1e-9;
      const bool after = std::abs(stretch.end_s - edge.start_s) < 1e-9;
      const bool between = (r2 > 1.0 && s2 > r2) || (r2 < 1.0 && s2 < r2);
      if (!(before || after) || !between || stretch.end_s - stretch.start_s < width * 0.999) {
        continue;
      }
      const double fraction = (r2 - 1.0) / (s2 - 1.0);
      if (before) {
        stretch.start_s = edge.end_s - fraction * width;
      } else {
        stretch.end_s = edge.start_s + fraction * width;
      }
      pieces.erase(pieces.begin() + static_cast<std::ptrdiff_t>(i));
      i = static_cast<std::size_t>(-1);  // start over: the list changed
      break;
    }
  }
  NonstationaryTerm term;
  // The model's own segments outside the deviating windows stay as they are.
  if (const NonstationaryTerm* existing = find_nonstationary(model)) {
    for (const auto& segment : existing->segments) {
      double start = segment.start_s;
      const double end = segment.end_s;
      for (const auto& piece : pieces) {
        if (piece.end_s <= start || piece.start_s >= end) continue;
        if (piece.start_s > start) term.segments.push_back({start, piece.start_s, segment.scale});
        start = std::max(start, piece.end_s);
      }
      if (end > start) term.segments.push_back({start, end, segment.scale});
    }
  }
  for (const auto& piece : pieces)
    term.segments.push_back({piece.start_s, piece.end_s, piece.scale});
  std::sort(term.segments.begin(), term.segments.end(),
            [](const auto& a, const auto& b) { return a.start_s < b.start_s; });
  return term;
}

}  // namespace stochnav
