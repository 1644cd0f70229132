#include "spin_motion.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/parallel.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav::davar_noise {
namespace {

using Vector4 = Eigen::Matrix<double, 4, 1>;
using Matrix4 = Eigen::Matrix<double, 4, 4>;

/// Least-squares solution of normal * x = rhs by the pseudo-inverse: while the tool does not
/// spin, e and c are not separable (normal is singular) and any split gives the same residual.
Vector4 pseudo_inverse_solve(const Matrix4& normal, const Vector4& rhs) {
  const Eigen::SelfAdjointEigenSolver<Matrix4> eigen(normal);
  const auto& values = eigen.eigenvalues();
  const double threshold = 1e-12 * values.cwiseAbs().maxCoeff();
  Vector4 projected = eigen.eigenvectors().transpose() * rhs;
  for (int k = 0; k < 4; ++k) projected(k) = values(k) > threshold ? projected(k) / values(k) : 0.0;
  return eigen.eigenvectors() * projected;
}

/// Largest minus smallest mean of `rate` over consecutive 1-s blocks (the last, partial block
/// included; blocks of one sample below 1 Hz).
double one_second_mean_range(std::span<const double> rate, double rate_hz) {
  const auto block = static_cast<std::size_t>(std::max(1.0, std::round(rate_hz)));
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (std::size_t start = 0; start < rate.size(); start += block) {
    const auto part = rate.subspan(start, std::min(block, rate.size() - start));
    double sum = 0.0;
    for (double value : part) sum += value;
    const double mean = sum / static_cast<double>(part.size());
    low = std::min(low, mean);
    high = std::max(high, mean);
  }
  return rate.empty() ? 0.0 : high - low;
}

}  // namespace

std::array<std::size_t, 2> cross_axes(std::size_t spin_axis) {
  return {(spin_axis + 1) % 3, (spin_axis + 2) % 3};
}

SpinFreeWindow spin_free_window(std::span<const double> first, std::span<const double> second,
                                std::span<const double> spin_rate, double rate_hz) {
  const std::size_t count = first.size();
  const double dt = 1.0 / rate_hz;
  std::vector<double> cosines(count), sines(count);
  // The angle at each sample's midpoint: a sample is the mean rate over its interval.
  double angle = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double middle = angle + 0.5 * spin_rate[i] * dt;
    cosines[i] = std::cos(middle);
    sines[i] = std::sin(middle);
    angle += spin_rate[i] * dt;
  }
  // Unknowns (e1, e2, c1, c2); rows a = cos e1 + sin e2 + c1, b = -sin e1 + cos e2 + c2.
  double sum_cos = 0.0, sum_sin = 0.0;
  Vector4 rhs = Vector4::Zero();
  for (std::size_t i = 0; i < count; ++i) {
    sum_cos += cosines[i];
    sum_sin += sines[i];
    rhs(0) += first[i] * cosines[i] - second[i] * sines[i];
    rhs(1) += first[i] * sines[i] + second[i] * cosines[i];
    rhs(2) += first[i];
    rhs(3) += second[i];
  }
  const auto n = static_cast<double>(count);
  Matrix4 normal;
  normal << n, 0.0, sum_cos, -sum_sin,  //
      0.0, n, sum_sin, sum_cos,         //
      sum_cos, sum_sin, n, 0.0,         //
      -sum_sin, sum_cos, 0.0, n;
  const Vector4 x = pseudo_inverse_solve(normal, rhs);
  SpinFreeWindow result;
  result.turns = std::abs(angle) / (2.0 * std::numbers::pi);
  result.spin_rate_range = one_second_mean_range(spin_rate, rate_hz);
  auto& [a, b] = result.residual;
  a.resize(count);
  b.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    a[i] = first[i] - (cosines[i] * x(0) + sines[i] * x(1) + x(2));
    b[i] = second[i] - (-sines[i] * x(0) + cosines[i] * x(1) + x(3));
  }
  if (result.turns < kMinimumTurns) return result;
  // The residual in spin-free axes, v = R(phi) [a; b]; its 2 x 2 covariance's minor direction.
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector2d v(cosines[i] * a[i] - sines[i] * b[i],
                            sines[i] * a[i] + cosines[i] * b[i]);
    covariance += v * v.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> principal(covariance);
  result.anisotropy = principal.eigenvalues()(1) / principal.eigenvalues()(0);  // ascending
  if (!(result.anisotropy >= kSwingAnisotropy)) return result;
  const Eigen::Vector2d quiet = principal.eigenvectors().col(0);
  result.quiet.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    result.quiet[i] = quiet(0) * (cosines[i] * a[i] - sines[i] * b[i]) +
                      quiet(1) * (sines[i] * a[i] + cosines[i] * b[i]);
  }
  return result;
}

SpinWindowDeviations spin_free_window_deviations(std::span<const double> first,
                                                 std::span<const double> second,
                                                 std::span<const double> spin_rate, double rate_hz,
                                                 std::size_t window, std::size_t step,
                                                 std::span<const std::size_t> m_values) {
  const std::size_t windows = first.size() < window ? 0 : (first.size() - window) / step + 1;
  SpinWindowDeviations result;
  for (auto& rows : result.cross) rows.resize(windows);
  result.spinning.resize(windows);
  result.steady_spin.resize(windows);
  const double tau0_s = 1.0 / rate_hz;
  parallel_for(windows, [&](std::size_t k) {
    const std::size_t start = k * step;
    const SpinFreeWindow free =
        spin_free_window(first.subspan(start, window), second.subspan(start, window),
                         spin_rate.subspan(start, window), rate_hz);
    result.spinning[k] = free.turns >= kMinimumTurns;
    result.steady_spin[k] = free.spin_rate_range <= kSteadySpinRange;
    const auto deviations_of = [&](std::span<const double> rate) {
      return deviation_values(Deviation::kOadev, phase_from_rate(rate, tau0_s), tau0_s, m_values);
    };
    if (!free.quiet.empty()) {
      result.cross[0][k] = deviations_of(free.quiet);
      result.cross[1][k] = result.cross[0][k];
      return;
    }
    for (std::size_t axis = 0; axis < 2; ++axis) {
      result.cross[axis][k] = deviations_of(free.residual[axis]);
    }
  });
  return result;
}

void replace_unsteady_spin_rows(std::vector<std::vector<double>>& spin_rows,
                                const SpinWindowDeviations& windows) {
  const std::vector<double>* before = nullptr;
  for (std::size_t k = 0; k < spin_rows.size(); ++k) {
    if (!windows.steady_spin[k]) {
      if (windows.spinning[k]) {
        const auto& first = windows.cross[0][k];
        const auto& second = windows.cross[1][k];
        for (std::size_t i = 0; i < spin_rows[k].size(); ++i) {
          spin_rows[k][i] = std::sqrt(0.5 * (first[i] * first[i] + second[i] * second[i]));
        }
      } else if (before != nullptr) {
        spin_rows[k] = *before;
      } else {
        continue;
      }
    }
    before = &spin_rows[k];
  }
}

}  // namespace stochnav::davar_noise
