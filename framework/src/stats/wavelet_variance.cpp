#include "stochnav/stats/wavelet_variance.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <limits>

namespace stochnav {

int wavelet_variance_levels(std::size_t samples) {
  if (samples < 4) return 0;
  return static_cast<int>(std::bit_width(samples)) - 2;  // floor(log2 N) - 1
}

double wavelet_variance_edf(std::size_t coefficients, std::size_t scale_samples) {
  return std::max(static_cast<double>(coefficients) / static_cast<double>(scale_samples), 1.0);
}

void set_wavelet_variance_interval(WaveletVariancePoint& point, double confidence) {
  const double eta = wavelet_variance_edf(point.coefficients, point.scale_samples);
  const boost::math::chi_squared_distribution<double> chi_square(eta);
  const double tail = (1.0 - confidence) / 2.0;
  point.lower = eta * point.variance / boost::math::quantile(chi_square, 1.0 - tail);
  point.upper = eta * point.variance / boost::math::quantile(chi_square, tail);
}

/// One level j of the Haar pyramid: takes V_{j-1}, sums (V_{j-1,t} - V_{j-1,t-lag})^2 = 4 W^2
/// and hands V_{j,t} on. The delay line holds the last `lag` inputs, oldest at `oldest_`.
class HaarWaveletVarianceAccumulator::Level {
 public:
  explicit Level(std::size_t lag) : lag_(lag) { line_.reserve(lag); }

  /// Consumes `in`; when `next` is not null, appends the V_j made from it.
  void push(std::span<const double> in, std::vector<double>* next) {
    std::size_t i = 0;
    while (line_.size() < lag_ && i < in.size()) line_.push_back(in[i++]);
    const std::size_t count = in.size() - i;
    if (count == 0) return;
    const double* x = in.data() + i;
    double* v = nullptr;
    if (next != nullptr) {
      next->resize(next->size() + count);
      v = next->data() + next->size() - count;
    }
    // The delayed partner of x[k] is the line, oldest first (two contiguous stretches), for the
    // first `lag` inputs, and x[k - lag] after them.
    const std::size_t from_line = std::min(count, lag_);
    const std::size_t first = std::min(from_line, lag_ - oldest_);
    pairs(x, line_.data() + oldest_, first, v);
    pairs(x + first, line_.data(), from_line - first, v == nullptr ? nullptr : v + first);
    if (count > lag_) pairs(x + lag_, x, count - lag_, v == nullptr ? nullptr : v + lag_);
    // The line becomes the last `lag` inputs.
    if (count >= lag_) {
      std::copy(x + count - lag_, x + count, line_.begin());
      oldest_ = 0;
    } else {
      for (std::size_t k = 0; k < count; ++k) line_[(oldest_ + k) % lag_] = x[k];
      oldest_ = (oldest_ + count) % lag_;
    }
  }

  /// Coefficients W_{j,t} summed so far.
  std::size_t coefficients() const { return coefficients_; }
  /// sum of W_{j,t}^2: the four lanes added in a fixed order.
  double sum_of_squares() const {
    return ((lanes_[0] + lanes_[1]) + (lanes_[2] + lanes_[3])) / 4.0;
  }
  std::size_t buffered() const { return line_.size(); }

 private:
  // Four partial sums (the additions pipeline), coefficient t in lane t mod 4: the sums do not
  // depend on how the record was cut into blocks.
  void pairs(const double* x, const double* old, std::size_t count, double* v) {
    std::size_t k = 0;
    for (; k < count && coefficients_ % 4 != 0; ++k) one(x[k], old[k], v, k);
    for (; k + 4 <= count; k += 4) {
      for (std::size_t lane = 0; lane < 4; ++lane) {
        const double difference = x[k + lane] - old[k + lane];
        lanes_[lane] += difference * difference;
      }
      if (v != nullptr) {
        for (std::size_t lane = 0; lane < 4; ++lane)
          v[k + lane] = 0.5 * (x[k + lane] + old[k + lane]);
      }
      coefficients_ += 4;
    }
    for (; k < count; ++k) one(x[k], old[k], v, k);
  }

  void one(double x, double old, double* v, std::size_t k) {
    const double difference = x - old;
    lanes_[coefficients_ % 4] += difference * difference;
    if (v != nullptr) v[k] = 0.5 * (x + old);
    ++coefficients_;
  }

  std::size_t lag_;
  std::vector<double> line_;
  std::size_t oldest_ = 0;
  std::array<double, 4> lanes_{};
  std::size_t coefficients_ = 0;
};

HaarWaveletVarianceAccumulator::HaarWaveletVarianceAccumulator(int max_level)
    : max_level_(std::max(max_level, 1)) {}

HaarWaveletVarianceAccumulator::~HaarWaveletVarianceAccumulator() = default;

void HaarWaveletVarianceAccumulator::push(std::span<const double> rate) {
  samples_ += rate.size();
  std::span<const double> in = rate;
  for (int j = 1; j <= max_level_ && !in.empty(); ++j) {
    if (levels_.size() < static_cast<std::size_t>(j)) {
      levels_.push_back(std::make_unique<Level>(std::size_t{1} << (j - 1)));
    }
    std::vector<double>& out = scratch_[j % 2];
    out.clear();
    levels_[j - 1]->push(in, j < max_level_ ? &out : nullptr);
    in = out;
  }
}

std::size_t HaarWaveletVarianceAccumulator::samples() const { return samples_; }

std::size_t HaarWaveletVarianceAccumulator::buffered_values() const {
  std::size_t total = 0;
  for (const auto& level : levels_) total += level->buffered();
  return total;
}

std::vector<WaveletVariancePoint> HaarWaveletVarianceAccumulator::result(double rate_hz) const {
  const int levels = std::min(max_level_, wavelet_variance_levels(samples_));
  std::vector<WaveletVariancePoint> points;
  for (int j = 1; j <= levels; ++j) {
    const Level& level = *levels_[j - 1];
    WaveletVariancePoint point;
    point.level = j;
    point.scale_samples = std::size_t{1} << j;
    point.scale_s = static_cast<double>(point.scale_samples) / rate_hz;
    point.coefficients = level.coefficients();
    point.variance = level.sum_of_squares() / static_cast<double>(point.coefficients);
    set_wavelet_variance_interval(point);
    points.push_back(point);
  }
  return points;
}

std::vector<WaveletVariancePoint> haar_wavelet_variance(std::span<const double> rate,
                                                        double rate_hz) {
  HaarWaveletVarianceAccumulator accumulator(wavelet_variance_levels(rate.size()));
  constexpr std::size_t kBlock = std::size_t{1} << 16;
  for (std::size_t first = 0; first < rate.size(); first += kBlock) {
    accumulator.push(rate.subspan(first, std::min(kBlock, rate.size() - first)));
  }
  return accumulator.result(rate_hz);
}

}  // namespace stochnav
