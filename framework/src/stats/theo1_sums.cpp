// Theo1 (D. A. Howe and T. N. Tasset, "Theo1: characterization of very long-term frequency
// stability", EFTF 2004; NIST SP 1065 Eq. 30) and Stable32's bias removal by ThêoBR
// (J. A. Taylor and D. A. Howe, "Fast ThêoBR: a method for long data set stability analysis").

#include "theo1_sums.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/parallel.hpp"
#include "vector_clones.hpp"

namespace stochnav {
namespace {

/// Lags j per task of theo1_sum.
constexpr std::size_t kLagsPerTask = 16;

/// sum_{i < count} (x[i] - x[i+j] + x[i+m] - x[i+m-j])^2, eight independent accumulators.
STOCHNAV_WIDE_VECTOR_CLONES
double theo1_lag_sum(const double* x, std::size_t m, std::size_t j, std::size_t count) {
  const double* a = x;
  const double* b = x + j;
  const double* c = x + m;
  const double* d = x + m - j;
  std::array<double, 8> acc{};
  std::size_t i = 0;
  for (; i + 8 <= count; i += 8) {
    for (std::size_t lane = 0; lane < 8; ++lane) {
      const double term = (a[i + lane] - b[i + lane]) + (c[i + lane] - d[i + lane]);
      acc[lane] += term * term;
    }
  }
  for (; i < count; ++i) {
    const double term = (a[i] - b[i]) + (c[i] - d[i]);
    acc[0] += term * term;
  }
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

struct NominalBias {
  int alpha;
  double avar_over_theo1;
};
constexpr std::array<NominalBias, 5> kNominalBias = {
    {{2, 0.4}, {1, 0.6}, {0, 1.0}, {-1, 1.71}, {-2, 2.24}}};

}  // namespace

double theo1_sum(std::span<const double> phase, std::size_t m) {
  const std::size_t half = m / 2;
  const std::size_t count = phase.size() - m;
  const std::size_t tasks = (half + kLagsPerTask - 1) / kLagsPerTask;
  std::vector<double> partial(tasks, 0.0);
  parallel_for(tasks, [&](std::size_t task) {
    const std::size_t first = task * kLagsPerTask + 1;
    const std::size_t last = std::min(half, first + kLagsPerTask - 1);
    double sum = 0.0;
    for (std::size_t j = first; j <= last; ++j) {
      sum += theo1_lag_sum(phase.data(), m, j, count) / static_cast<double>(j);
    }
    partial[task] = sum;
  });
  double sum = 0.0;
  for (double value : partial) sum += value;
  return sum;
}

double theo1_variance(std::span<const double> phase, double tau0_s, std::size_t m) {
  const double tau = static_cast<double>(m) * tau0_s;
  const double count = static_cast<double>(phase.size() - m);
  return theo1_sum(phase, m) / (0.75 * count * tau * tau);
}

double theo1_bias_factor(std::span<const double> phase) {
  const std::size_t n = phase.size();
  if (n < 24) return 1.0;
  std::size_t ratios = n / 6 - 3 + 1;
  // The last Allan factor can reach N / 2 (no term left) when 6 divides N: stop before it.
  while (ratios > 0 && 2 * (9 + 3 * (ratios - 1)) >= n) --ratios;
  if (ratios == 0) return 1.0;
  std::vector<std::size_t> allan_m(ratios);
  for (std::size_t i = 0; i < ratios; ++i) allan_m[i] = 9 + 3 * i;
  const std::vector<double> allan = deviation_values(Deviation::kOadev, phase, 1.0, allan_m);
  std::vector<double> ratio(ratios, 0.0);
  // One task per ratio: its Theo1 sum runs serially inside (parallel_for nests serially).
  parallel_for(ratios, [&](std::size_t i) {
    const double theo1 = theo1_variance(phase, 1.0, 12 + 4 * i);
    ratio[i] = allan[i] * allan[i] / theo1;
  });
  double sum = 0.0;
  for (double value : ratio) sum += value;
  return sum / static_cast<double>(ratios);
}

int theo1_bias_noise_type(double bias_factor) {
  for (std::size_t k = 0; k + 1 < kNominalBias.size(); ++k) {
    const double boundary =
        std::sqrt(kNominalBias[k].avar_over_theo1 * kNominalBias[k + 1].avar_over_theo1);
    if (bias_factor < boundary) return kNominalBias[k].alpha;
  }
  return kNominalBias.back().alpha;
}

}  // namespace stochnav
