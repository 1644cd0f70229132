#include "stochnav/diagnose/signature.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "stochnav/diagnose/effective_model.hpp"
#include "stochnav/model/allan_variance.hpp"

namespace stochnav {
namespace {

constexpr double kRangeZ = 2.0;

TermType name_slope(double slope) {
  if (slope < -1.5) return TermType::kQuantization;
  if (slope < -0.5) return TermType::kAngleRandomWalk;
  if (slope < 0.5) return TermType::kBiasInstability;
  if (slope < 1.5) return TermType::kRateRandomWalk;
  return TermType::kRateRamp;
}

// Least-squares slope of log y against log x.
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() < 2) return 0.0;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]);
    const double ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  const double denominator = n * sxx - sx * sx;
  return denominator > 0.0 ? (n * sxy - sx * sy) / denominator : 0.0;
}

}  // namespace

Signature read_signature(const AvarGap& gap, std::span<const double> dense_tau_s,
                         std::span<const double> dense_avar, std::span<const double> dense_edf,
                         const NoiseModel& model) {
  Signature signature;
  const auto& points = gap.points;
  if (points.empty()) return signature;
  std::size_t peak = 0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (std::abs(points[i].z) > std::abs(points[peak].z)) peak = i;
  }
  signature.max_abs_z = std::abs(points[peak].z);
  signature.tau_at_max_s = points[peak].tau_s;
  if (signature.max_abs_z <= kRangeZ) return signature;
  signature.found = true;
  signature.above = points[peak].z > 0.0;
  const auto same_side = [&](std::size_t i) {
    return std::abs(points[i].z) > kRangeZ && (points[i].z > 0.0) == signature.above;
  };
  std::size_t first = peak;
  std::size_t last = peak;
  while (first > 0 && same_side(first - 1)) --first;
  while (last + 1 < points.size() && same_side(last + 1)) ++last;
  signature.tau_range_s = std::array<double, 2>{points[first].tau_s, points[last].tau_s};

  // Excess (or deficit) on the dense taus of the range widened by an octave each side.
  // The slope over the range widened by an octave each side; the shape (nulls, a bump) over
  // two octaves each side, so that the fall after a peak and the next lobe after a null count.
  const double lower = points[first].tau_s / 4.0 * (1.0 - 1e-9);
  const double upper = points[last].tau_s * 4.0 * (1.0 + 1e-9);
  const double slope_lower = points[first].tau_s / 2.0 * (1.0 - 1e-9);
  const double slope_upper = points[last].tau_s * 2.0 * (1.0 + 1e-9);
  const NoiseModel equivalent =
      stationary_equivalent(model, dense_tau_s.empty() ? 1.0 : 4.0 * dense_tau_s.back()).model;
  std::vector<double> tau, excess;
  std::vector<bool> significant;
  for (std::size_t i = 0; i < dense_tau_s.size(); ++i) {
    if (dense_tau_s[i] < lower || dense_tau_s[i] > upper) continue;
    const double model_avar = allan_variance(equivalent, dense_tau_s[i]);
    const double difference = dense_avar[i] - model_avar;
    const double value = signature.above ? difference : -difference;
    tau.push_back(dense_tau_s[i]);
    excess.push_back(value);
    const double edf = i < dense_edf.size() ? dense_edf[i] : 2.0;
    significant.push_back(value > 3.0 * std::sqrt(2.0 / edf) * model_avar);
  }
  std::vector<double> positive_tau, positive;
  const auto in_slope_range = [&](std::size_t i) {
    return tau[i] >= slope_lower && tau[i] <= slope_upper;
  };
  for (std::size_t i = 0; i < tau.size(); ++i) {
    if (significant[i] && in_slope_range(i)) {
      positive_tau.push_back(tau[i]);
      positive.push_back(excess[i]);
    }
  }
  if (positive.size() < 2) {
    // Too few clearly significant points: use every positive one.
    positive_tau.clear();
    positive.clear();
    for (std::size_t i = 0; i < tau.size(); ++i) {
      if (excess[i] > 0.0 && in_slope_range(i)) {
        positive_tau.push_back(tau[i]);
        positive.push_back(excess[i]);
      }
    }
  }
  signature.slope = log_log_slope(positive_tau, positive);

  if (signature.above && excess.size() >= 3) {
    // A null: a local minimum far below the maxima on both sides, after a rise.
    // Maxima count only where the excess is significant.
    const auto largest_significant = [&](std::size_t begin, std::size_t end) {
      double largest = 0.0;
      for (std::size_t j = begin; j < end; ++j) {
        if (significant[j]) largest = std::max(largest, excess[j]);
      }
      return largest;
    };
    for (std::size_t i = 1; i + 1 < excess.size(); ++i) {
      const double left = largest_significant(0, i);
      const double right = largest_significant(i + 1, excess.size());
      if (left > 0.0 && right > 0.0 && excess[i] < 0.25 * left && excess[i] < 0.25 * right &&
          excess[i] <= excess[i - 1] && excess[i] <= excess[i + 1]) {
        signature.suggested = TermType::kSinusoid;
        signature.shape = fmt::format("oscillating excess with a null near tau = {:.4g} s", tau[i]);
        return signature;
      }
    }
    // A single bump inside the tau axis.
    const auto top = std::max_element(excess.begin(), excess.end());
    const auto top_index = static_cast<std::size_t>(top - excess.begin());
    if (top_index > 0 && top_index + 1 < excess.size() && significant[top_index] &&
        excess.front() < 0.5 * *top && excess.back() < 0.5 * *top) {
      signature.suggested = TermType::kGaussMarkov;
      signature.shape =
          fmt::format("single bump of excess AVAR peaking near tau = {:.4g} s", tau[top_index]);
      return signature;
    }
  }
  signature.suggested = name_slope(signature.slope);
  signature.shape = fmt::format("{} AVAR with log-log slope {:+.2f}",
                                signature.above ? "excess" : "deficit", signature.slope);
  return signature;
}

}  // namespace stochnav
