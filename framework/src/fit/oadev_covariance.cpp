#include "stochnav/fit/oadev_covariance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>
#include <variant>
#include <vector>

namespace stochnav {
namespace {

// Generalized covariance G of the phase of the model's Gaussian terms (see the header), as a
// function of the lag in samples.
class PhaseCovariance {
 public:
  PhaseCovariance(const NoiseModel& model, double tau0) : tau0_(tau0) {
    for (const auto& term : model.terms) {
      std::visit(
          [this](const auto& t) {
            using T = std::decay_t<decltype(t)>;
            if constexpr (std::is_same_v<T, QuantizationTerm>) {
              white_phase_ += t.q * t.q;
            } else if constexpr (std::is_same_v<T, AngleRandomWalkTerm>) {
              linear_ += 0.5 * t.n * t.n;
            } else if constexpr (std::is_same_v<T, BiasInstabilityTerm>) {
              flicker_ += t.b * t.b / (2.0 * std::numbers::pi);
            } else if constexpr (std::is_same_v<T, RateRandomWalkTerm>) {
              cubic_ += t.k * t.k / 12.0;
            } else if constexpr (std::is_same_v<T, RateRampTerm>) {
              ramp_ += t.r;
            } else if constexpr (std::is_same_v<T, GaussMarkovTerm>) {
              if (t.sigma > 0.0) {
                gauss_markov_.push_back({t.sigma * t.sigma * t.tau_c * t.tau_c, t.tau_c});
              }
            }
          },
          term);
    }
  }

  double operator()(double lag) const {
    const double h = std::abs(lag) * tau0_;
    double g = lag == 0.0 ? white_phase_ : 0.0;
    g += h * (cubic_ * h * h - linear_);
    if (flicker_ != 0.0 && h > 0.0) g += flicker_ * h * h * std::log(h);
    for (const auto& [scale, tau_c] : gauss_markov_) {
      g -= scale * (h / tau_c + std::exp(-h / tau_c));
    }
    return g;
  }

  // Lags beyond the window overlap where C12 is still non-zero.
  double tail_lags(std::size_t m1, std::size_t m2) const {
    double tail = 0.0;
    if (flicker_ != 0.0) tail = 64.0 * static_cast<double>(m1 + m2);
    for (const auto& gm : gauss_markov_) tail = std::max(tail, 40.0 * gm.tau_c / tau0_);
    return std::ceil(tail);
  }

  double ramp() const { return ramp_; }
  bool has_ramp() const { return ramp_ != 0.0; }

 private:
  struct GaussMarkovPart {
    double scale;  // s^2 T^2
    double tau_c;
  };
  double tau0_;
  double white_phase_ = 0.0;
  double linear_ = 0.0;
  double flicker_ = 0.0;
  double cubic_ = 0.0;
  double ramp_ = 0.0;
  std::vector<GaussMarkovPart> gauss_markov_;
};

struct LagSums {
  double squared = 0.0;  // sum_l c(l) C12(l)^2
  double linear = 0.0;   // sum_l c(l) C12(l)
  LagSums& operator+=(const LagSums& other) {
    squared += other.squared;
    linear += other.linear;
    return *this;
  }
};

constexpr std::array<double, 4> kGaussNodes{0.1834346424956498, 0.5255324099163290,
                                            0.7966664774136267, 0.9602898564975363};
constexpr std::array<double, 4> kGaussWeights{0.3626837833783620, 0.3137066458778873,
                                              0.2223810344533745, 0.1012285362903763};

class LagSummer {
 public:
  LagSummer(const PhaseCovariance& g, std::size_t m1, std::size_t m2, std::size_t n1,
            std::size_t n2)
      : g_(g),
        m1_(static_cast<double>(m1)),
        m2_(static_cast<double>(m2)),
        n1_(static_cast<double>(n1)),
        n2_(static_cast<double>(n2)) {}

  LagSums at(double lag) const {
    constexpr std::array<double, 3> a{1.0, -2.0, 1.0};
    double c = 0.0;
    for (int p = 0; p < 3; ++p) {
      for (int q = 0; q < 3; ++q) c += a[p] * a[q] * g_(lag + p * m1_ - q * m2_);
    }
    const double count = std::max(0.0, std::min(n1_, n2_ + lag) - std::max(0.0, lag));
    return {count * c * c, count * c};
  }

  /// Per-lag absolute tolerance of the quadrature, from the largest |g| seen at breakpoints:
  /// far tails, where the contrasts of G lose their digits to cancellation, stop refining there.
  void set_scale(const LagSums& largest) {
    squared_tolerance_ = 1e-12 * largest.squared;
    linear_tolerance_ = 1e-12 * std::abs(largest.linear);
  }

  // Sum over the integers strictly between breakpoints a < b.
  LagSums interior(double a, double b) const {
    LagSums sums;
    if (b - a - 1.0 <= 4096.0) {
      for (double lag = a + 1.0; lag < b; lag += 1.0) sums += at(lag);
      return sums;
    }
    // Smooth between breakpoints: the integer sum is the integral over [a + 1/2, b - 1/2].
    const LagSums whole = gauss(a + 0.5, b - 0.5);
    return adaptive(a + 0.5, b - 0.5, whole, 0);
  }

 private:
  LagSums gauss(double a, double b) const {
    const double half = 0.5 * (b - a);
    const double mid = 0.5 * (a + b);
    LagSums sums;
    for (std::size_t k = 0; k < kGaussNodes.size(); ++k) {
      for (double sign : {-1.0, 1.0}) {
        const LagSums value = at(mid + sign * half * kGaussNodes[k]);
        sums.squared += kGaussWeights[k] * half * value.squared;
        sums.linear += kGaussWeights[k] * half * value.linear;
      }
    }
    return sums;
  }

  LagSums adaptive(double a, double b, const LagSums& whole, int depth) const {
    const double mid = 0.5 * (a + b);
    const LagSums left = gauss(a, mid);
    const LagSums right = gauss(mid, b);
    LagSums both = left;
    both += right;
    // The signed sum matters only with a ramp; its tolerance is set by the squared sum's scale
    // (|sum c C| <= sqrt(sum c sum c C^2)), so sign changes cannot stall the refinement.
    const bool converged =
        std::abs(both.squared - whole.squared) <=
            1e-9 * std::abs(both.squared) + squared_tolerance_ * (b - a) &&
        (!g_.has_ramp() || std::abs(both.linear - whole.linear) <=
                               1e-9 * std::abs(both.linear) + linear_tolerance_ * (b - a));
    // Depth 10 (1024 pieces, 4-point Gauss each) is far beyond what a smooth stretch needs; where
    // the contrasts of G lose their digits to cancellation (long tails of a random walk or
    // flicker term) the tolerance can never be met, and deeper refinement would cost a direct
    // sum over up to the whole record: seconds per pair of averaging factors.
    if (converged || depth >= 10 || b - a < 8.0) return both;
    LagSums sums = adaptive(a, mid, left, depth + 1);
    sums += adaptive(mid, b, right, depth + 1);
    return sums;
  }

  const PhaseCovariance& g_;
  double m1_, m2_, n1_, n2_;
  double squared_tolerance_ = 0.0;
  double linear_tolerance_ = 0.0;
};

LagSums sum_over_lags(const PhaseCovariance& g, std::size_t m1, std::size_t m2, std::size_t n1,
                      std::size_t n2) {
  LagSummer summer(g, m1, m2, n1, n2);
  const double low_domain = -(static_cast<double>(n2) - 1.0);
  const double high_domain = static_cast<double>(n1) - 1.0;
  const double tail = g.tail_lags(m1, m2);
  const double low = std::max(low_domain, -2.0 * static_cast<double>(m1) - tail);
  const double high = std::min(high_domain, 2.0 * static_cast<double>(m2) + tail);
  std::vector<double> breaks{low, high, 0.0,
                             static_cast<double>(n1) - static_cast<double>(n2)};
  for (int p = 0; p < 3; ++p) {
    for (int q = 0; q < 3; ++q) {
      breaks.push_back(q * static_cast<double>(m2) - p * static_cast<double>(m1));
    }
  }
  std::erase_if(breaks, [&](double b) { return b < low || b > high; });
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  LagSums sums;
  LagSums largest;
  for (double lag : breaks) {
    const LagSums value = summer.at(lag);
    sums += value;
    largest.squared = std::max(largest.squared, value.squared);
    largest.linear = std::max(largest.linear, std::abs(value.linear));
  }
  summer.set_scale(largest);
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    sums += summer.interior(breaks[k], breaks[k + 1]);
  }
  return sums;
}

}  // namespace

Eigen::MatrixXd oadev_estimate_covariance(const NoiseModel& model, double tau0_s,
                                          std::size_t phase_count,
                                          std::span<const std::size_t> m_values) {
  const PhaseCovariance g(model, tau0_s);
  const auto size = static_cast<Eigen::Index>(m_values.size());
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(size, size);
  for (Eigen::Index i = 0; i < size; ++i) {
    for (Eigen::Index j = i; j < size; ++j) {
      const std::size_t m1 = m_values[static_cast<std::size_t>(i)];
      const std::size_t m2 = m_values[static_cast<std::size_t>(j)];
      if (m1 == 0 || m2 == 0 || 2 * m1 >= phase_count || 2 * m2 >= phase_count) {
        covariance(i, j) = covariance(j, i) = std::numeric_limits<double>::quiet_NaN();
        continue;
      }
      const std::size_t n1 = phase_count - 2 * m1;
      const std::size_t n2 = phase_count - 2 * m2;
      const LagSums sums = sum_over_lags(g, m1, m2, n1, n2);
      const double tau1 = static_cast<double>(m1) * tau0_s;
      const double tau2 = static_cast<double>(m2) * tau0_s;
      const double r1 = g.ramp() * tau1 * tau1;
      const double r2 = g.ramp() * tau2 * tau2;
      const double value = (2.0 * sums.squared + 4.0 * r1 * r2 * sums.linear) /
                           (4.0 * tau1 * tau1 * tau2 * tau2 * static_cast<double>(n1) *
                            static_cast<double>(n2));
      covariance(i, j) = covariance(j, i) = value;
    }
  }
  return covariance;
}

}  // namespace stochnav
