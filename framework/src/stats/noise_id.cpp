#include "stochnav/stats/noise_id.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <cstdlib>

namespace stochnav {
namespace {

/// The phase decimated by m with its least-squares quadratic removed, differenced d times,
/// evaluated on the fly: no copy of a long record is made.
class DifferencedResidual final {
 public:
  DifferencedResidual(std::span<const double> phase, std::size_t m)
      : phase_(phase), m_(m), points_((phase.size() - 1) / m + 1) {
    fit_quadratic();
  }

  /// Points of the series after `differences` differences.
  std::size_t size() const { return points_ - static_cast<std::size_t>(differences_); }
  int differences() const { return differences_; }
  void difference() { ++differences_; }

  double operator[](std::size_t k) const {
    // Binomial weights (-1)^(d-j) C(d, j) of the d-th forward difference.
    double value = 0.0;
    double weight = differences_ % 2 == 0 ? 1.0 : -1.0;
    for (int j = 0; j <= differences_; ++j) {
      value += weight * residual(k + static_cast<std::size_t>(j));
      weight = -weight * (differences_ - j) / (j + 1.0);
    }
    return value;
  }

 private:
  double abscissa(std::size_t k) const {
    // Scaled to [-1, 1] so the normal equations stay well conditioned for long records.
    const double half = 0.5 * static_cast<double>(points_ - 1);
    return half > 0.0 ? (static_cast<double>(k) - half) / half : 0.0;
  }
  double residual(std::size_t k) const {
    const double t = abscissa(k);
    return phase_[k * m_] - (coefficients_[0] + t * (coefficients_[1] + t * coefficients_[2]));
  }
  void fit_quadratic() {
    static const int degree = getenv("NID_DEG") ? atoi(getenv("NID_DEG")) : 2;
    if (degree < 0) return;
    if (points_ < 3) return;
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d right = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < points_; ++k) {
      const double t = abscissa(k);
      const Eigen::Vector3d basis(1.0, t, t * t);
      normal += basis * basis.transpose();
      right += basis * phase_[k * m_];
    }
    if (degree < 2) { normal(2,2) = 1; normal(0,2)=normal(2,0)=normal(1,2)=normal(2,1)=0; right(2)=0; }
    if (degree < 1) { normal(1,1) = 1; normal(0,1)=normal(1,0)=0; right(1)=0; }
    const Eigen::Vector3d solution = normal.ldlt().solve(right);
    coefficients_ = {solution[0], solution[1], solution[2]};
  }

  std::span<const double> phase_;
  std::size_t m_;
  std::size_t points_;
  int differences_ = 0;
  std::array<double, 3> coefficients_{};
};

/// Lag-1 autocorrelation of any indexable series (two passes: mean, then the sums).
template <typename Series>
double lag1_of(const Series& series, std::size_t n) {
  if (n < 2) return 0.0;
  double mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) mean += series[k];
  mean /= static_cast<double>(n);
  double previous = series[0] - mean;
  double lagged = 0.0;
  double squares = previous * previous;
  for (std::size_t k = 1; k < n; ++k) {
    const double current = series[k] - mean;
    lagged += previous * current;
    squares += current * current;
    previous = current;
  }
  return squares > 0.0 ? lagged / squares : 0.0;
}

NoiseId lag1_noise_id(std::span<const double> phase, std::size_t m, int max_differences) {
  DifferencedResidual series(phase, m);
  while (true) {
    const double r1 = lag1_of(series, series.size());
    const double delta = r1 / (1.0 + r1);
    const int d = series.differences();
    if (delta < 0.25 || d >= max_differences) {
      const double alpha = 2.0 - 2.0 * d - 2.0 * delta;
      const auto rounded = static_cast<int>(2 - 2 * d - std::lround(2.0 * delta));
      return {std::clamp(rounded, -2, 2), NoiseIdMethod::kLag1Autocorrelation, alpha};
    }
    series.difference();
  }
}

/// Allan-variance tau exponent mu -> noise alpha; mu = -2 is white or flicker PM (alpha 2, 1).
int alpha_from_mu(int mu) { return std::clamp(-1 - mu, -2, 2); }

/// Sample variance of the non-overlapping frequency averages over their Allan variance.
double b1_ratio(std::span<const double> phase, std::size_t m) {
  const std::size_t n = (phase.size() - 1) / m;
  const auto average = [&](std::size_t k) { return phase[(k + 1) * m] - phase[k * m]; };
  double mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) mean += average(k);
  mean /= static_cast<double>(n);
  double variance = 0.0;
  double allan = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double deviation = average(k) - mean;
    variance += deviation * deviation;
    if (k + 1 < n) {
      const double step = average(k + 1) - average(k);
      allan += step * step;
    }
  }
  variance /= static_cast<double>(n - 1);
  allan /= 2.0 * static_cast<double>(n - 1);
  return allan > 0.0 ? variance / allan : 1.0;
}

/// R(n) = MVAR / AVAR at m: about 1/m for white PM, much larger for flicker PM.
int white_or_flicker_pm(std::span<const double> phase, std::size_t m) {
  const double md = static_cast<double>(m);
  const double modified = deviation_value(Deviation::kMdev, phase, 1.0, m);
  const double allan = deviation_value(Deviation::kOadev, phase, 1.0, m);
  if (!(allan > 0.0)) return 1;
  const double ratio = (modified * modified) / (allan * allan);
  const double white_pm = 1.0 / md;
  const double flicker_pm = 3.0 * std::log(256.0 / 27.0) /
                            (2.0 * (1.038 + 3.0 * std::log(std::numbers::pi * md)));
  return ratio < std::sqrt(white_pm * flicker_pm) ? 2 : 1;
}

NoiseId b1_noise_id(Deviation kind, std::span<const double> phase, std::size_t m) {
  const double n = static_cast<double>((phase.size() - 1) / m);
  const double ratio = b1_ratio(phase, m);
  int mu = -2;
  while (mu < 2 && ratio >= std::sqrt(b1_expected(n, mu) * b1_expected(n, mu + 1))) ++mu;
  if (mu != -2) return {alpha_from_mu(mu), NoiseIdMethod::kB1Ratio, ratio};
  // R(n) needs one MDEV term: N >= 3m.
  if (term_count(Deviation::kMdev, m, phase.size()) == 0) {
    return {1, NoiseIdMethod::kB1Ratio, ratio};
  }
  (void)kind;
  return {white_or_flicker_pm(phase, m), NoiseIdMethod::kB1AndRn, ratio};
}

}  // namespace

double lag1_autocorrelation(std::span<const double> series) {
  return lag1_of(series, series.size());
}

double b1_expected(double n, int mu) {
  if (mu == 0) return n * std::log(n) / (2.0 * (n - 1.0) * std::numbers::ln2);
  const double p = static_cast<double>(mu);
  return n * (1.0 - std::pow(n, p)) / (2.0 * (n - 1.0) * (1.0 - std::pow(2.0, p)));
}

NoiseId identify_noise(Deviation kind, std::span<const double> phase, std::size_t m) {
  if (m == 0 || phase.size() < 2 * m + 2) {
    throw std::invalid_argument("identify_noise: m = " + std::to_string(m) + " needs more than " +
                                std::to_string(2 * m + 1) + " phase points, got " +
                                std::to_string(phase.size()));
  }
  const std::size_t decimated_points = (phase.size() - 1) / m + 1;
  static const std::size_t min_points = getenv("NID_MIN") ? atoi(getenv("NID_MIN")) : kMinLag1Points;
  if (decimated_points >= min_points) {
    return lag1_noise_id(phase, m, difference_order(kind));
  }
  return b1_noise_id(kind, phase, m);
}

}  // namespace stochnav
