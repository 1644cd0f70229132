#include "stochnav/stats/noise_id.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fused_passes.hpp"
#include "stochnav/stats/parallel.hpp"
#include "vector_clones.hpp"

namespace stochnav {
namespace {

constexpr int kMaxDifferences = 3;
using PerDifference = std::array<double, kMaxDifferences + 1>;

/// Means of the d-th differences of z[k] = x[k m], k < points, d = 0 .. MaxD: one pass for z,
/// the sums of its differences telescope.
template <int MaxD>
PerDifference decimated_difference_means(std::span<const double> phase, std::size_t m,
                                         std::size_t points) {
  const auto z = [&](std::size_t k) { return phase[k * m]; };
  PerDifference mean{};
  for (std::size_t k = 0; k < points; ++k) mean[0] += z(k);
  mean[0] /= static_cast<double>(points);
  const std::size_t last = points - 1;
  if constexpr (MaxD >= 1) mean[1] = (z(last) - z(0)) / static_cast<double>(points - 1);
  if constexpr (MaxD >= 2) {
    mean[2] = ((z(last) - z(last - 1)) - (z(1) - z(0))) / static_cast<double>(points - 2);
  }
  if constexpr (MaxD >= 3) {
    mean[3] = ((z(last) - 2.0 * z(last - 1) + z(last - 2)) - (z(2) - 2.0 * z(1) + z(0))) /
              static_cast<double>(points - 3);
  }
  return mean;
}

/// Lag-1 autocorrelations r1[d], d = 0 .. MaxD, of the d-th differences of the decimated phase
/// z[k] = x[k m], k < points (> MaxD + 1), read on the fly (no copy of a long record): one pass
/// for the mean of z, one pass for all the sums. No trend is removed: Stable32's
/// identifications match the raw decimated phase (removing a quadratic first changes them on the
/// Cs 5071A record).
template <int MaxD>
PerDifference lag1_of_decimated_differences(std::span<const double> phase, std::size_t m,
                                            std::size_t points) {
  const auto z = [&](std::size_t k) { return phase[k * m]; };
  const PerDifference mean = decimated_difference_means<MaxD>(phase, m, points);
  PerDifference lagged{};
  PerDifference squares{};
  PerDifference previous{};
  // recent = z(k), z(k-1), z(k-2), z(k-3); the d-th difference that ends at k starts at k - d.
  std::array<double, 4> recent{};
  const auto step_to = [&](std::size_t k) {
    recent = {z(k), recent[0], recent[1], recent[2]};
    const auto& [z0, z1, z2, z3] = recent;
    return PerDifference{z0, z0 - z1, z0 - 2.0 * z1 + z2, z0 - 3.0 * z1 + 3.0 * z2 - z3};
  };
  // The first MaxD + 1 points, where the higher differences are still incomplete.
  for (std::size_t k = 0; k <= MaxD; ++k) {
    const PerDifference value = step_to(k);
    for (std::size_t d = 0; d <= k; ++d) {
      const double centred = value[d] - mean[d];
      if (k > d) lagged[d] += previous[d] * centred;
      squares[d] += centred * centred;
      previous[d] = centred;
    }
  }
  for (std::size_t k = MaxD + 1; k < points; ++k) {
    const PerDifference value = step_to(k);
    for (std::size_t d = 0; d <= MaxD; ++d) {  // unrolled: MaxD is a constant
      const double centred = value[d] - mean[d];
      lagged[d] += previous[d] * centred;
      squares[d] += centred * centred;
      previous[d] = centred;
    }
  }
  PerDifference r1{};
  for (std::size_t d = 0; d <= MaxD; ++d) r1[d] = squares[d] > 0.0 ? lagged[d] / squares[d] : 0.0;
  return r1;
}

/// z of the two-sided 95 % normal interval of a lag-1 estimate (plausible_alphas).
constexpr double kPlausibleZ = 1.96;
/// Fewest d-th differences whose lag-1 autocorrelation plausible_alphas reads.
constexpr std::size_t kMinPlausibleValues = 4;

AlphaRange widened_to(AlphaRange range, int alpha) {
  return {std::min(range.low, alpha), std::max(range.high, alpha)};
}

/// plausible_alphas from the lag-1 autocorrelation r of `values` d-th differences.
AlphaRange lag1_plausible_range(double r, int d, std::size_t values) {
  if (values < kMinPlausibleValues || !(r > -1.0)) return {};
  const double estimate = 2.0 - 2.0 * d - 2.0 * r / (1.0 + r);
  const double sd_r = std::sqrt(std::max(0.0, 1.0 - r * r) / static_cast<double>(values));
  const double spread = kPlausibleZ * 2.0 * sd_r / ((1.0 + r) * (1.0 + r));
  const auto nearest_alpha = [](double x) {
    return static_cast<int>(std::lround(std::clamp(x, -2.0, 2.0)));  // clamp first: x may be inf
  };
  return {nearest_alpha(estimate - spread), nearest_alpha(estimate + spread)};
}

/// Differences the decimated phase (`points` points) until its lag-1 autocorrelation r1[d]
/// says white, or d_max.
NoiseId noise_from_lag1(const PerDifference& r1, int max_differences, std::size_t points) {
  for (int d = 0;; ++d) {
    const double r = r1[static_cast<std::size_t>(d)];
    const double delta = r / (1.0 + r);
    if (delta < 0.25 || d >= max_differences) {
      const double alpha = 2.0 - 2.0 * d - 2.0 * delta;
      const auto rounded = std::clamp(static_cast<int>(2 - 2 * d - std::lround(2.0 * delta)), -2, 2);
      const std::size_t values = points - static_cast<std::size_t>(d);
      return {rounded, NoiseIdMethod::kLag1Autocorrelation, alpha,
              widened_to(lag1_plausible_range(r, d, values), rounded)};
    }
  }
}

std::size_t decimated_point_count(std::span<const double> phase, std::size_t m) {
  return (phase.size() - 1) / m + 1;
}

NoiseId lag1_noise_id(std::span<const double> phase, std::size_t m, int max_differences) {
  const std::size_t points = decimated_point_count(phase, m);
  const PerDifference r1 = max_differences >= 3
                               ? lag1_of_decimated_differences<3>(phase, m, points)
                               : lag1_of_decimated_differences<2>(phase, m, points);
  return noise_from_lag1(r1, max_differences, points);
}

// ---- The lag-1 statistics of many factors at once (identify_noises) ----
//
// Every factor m walks the same phase record (z[k] = x[k m]); done one factor after another,
// the small factors each stream the whole record from memory (m = 1 .. 8 touch every cache line).
// Instead the record is cut into blocks of kLag1BlockPoints phase points, and each task takes one
// block and serves every factor's decimated points inside it while the block is in cache: one
// pass over memory for orders 0 and 1 (the mean of order 0 comes out of the same pass, by the
// shifted-data correction), and one more for orders 2 and 3 of the few factors that need them.
// The block partial sums are added in block order: the same result for every thread count.

/// Phase points per block: 512 KB, the stretch of the record one task of the overlapping
/// deviation sums starts its terms in (compute_deviation runs the two passes as one).
constexpr std::size_t kLag1BlockPoints = kAlongsideBlockPoints;
/// Independent accumulators per sum: sixteen break the serial chains of additions (two AVX-512
/// or four AVX2 registers per sum).
constexpr std::size_t kLag1Lanes = 16;

/// The decimated indices k of factor m whose phase index k m lies in [first, last): [begin, end).
struct DecimatedRange {
  std::size_t begin = 0;
  std::size_t end = 0;
};
DecimatedRange decimated_range(std::size_t m, std::size_t points, std::size_t first,
                               std::size_t last) {
  const std::size_t begin = (first + m - 1) / m;
  const std::size_t end = std::min(points, (last + m - 1) / m);
  return {begin, std::max(begin, end)};
}

/// Centred lag products and squares of the d-th differences, d <= MaxD, over one range.
struct Lag1Sums {
  PerDifference lagged{};
  PerDifference squares{};
  double values = 0.0;  ///< sum of the centred values of order 0 (the shifted-data correction)
};

/// The d-th backward differences of z ending at k, d <= MaxD (only d <= k are meaningful).
template <int MaxD>
PerDifference differences_ending_at(const double* x, std::size_t m, std::size_t k) {
  const auto z = [&](std::size_t back) { return back <= k ? x[(k - back) * m] : 0.0; };
  const double z0 = z(0), z1 = z(1), z2 = z(2);
  const double z3 = MaxD >= 3 ? z(3) : 0.0;
  return PerDifference{z0, z0 - z1, z0 - 2.0 * z1 + z2, z0 - 3.0 * z1 + 3.0 * z2 - z3};
}

/// Accumulators of the centred lag products and squares: [order d][lane].
using LaneSums = std::array<std::array<double, kLag1Lanes>, kMaxDifferences + 1>;

/// Adds the centred products c(t - 1) c(t) and squares c(t)^2 of one order's differences,
/// c(t) = D(t) - mu, t = 0 .. count - 1, where D(t) is the Order-th backward difference of z
/// ending at z[t] (z[-(Order + 1)] .. z[count - 1] readable); for order 0 also the sum of c(t).
/// c(t - 1) is recomputed rather than kept: the loop has no carried value but its sums. Always
/// inlined, so it is compiled for the instruction set of its caller's clone.
template <int Order>
[[gnu::always_inline]] inline void add_order_sums(const double* z, std::size_t count, double mu,
                                                  std::array<double, kLag1Lanes>& lagged,
                                                  std::array<double, kLag1Lanes>& squares,
                                                  std::array<double, kLag1Lanes>& values) {
  const auto centred = [z, mu](std::ptrdiff_t t) {
    const double* e = z + t;
    if constexpr (Order == 0) return e[0] - mu;
    if constexpr (Order == 1) return (e[0] - e[-1]) - mu;
    if constexpr (Order == 2) return (e[0] - 2.0 * e[-1] + e[-2]) - mu;
    return (e[0] - 3.0 * e[-1] + 3.0 * e[-2] - e[-3]) - mu;
  };
  // Local copies: the references might alias each other, which would pin them in memory.
  std::array<double, kLag1Lanes> lag = lagged;
  std::array<double, kLag1Lanes> square = squares;
  std::array<double, kLag1Lanes> sum = values;
  std::size_t t = 0;
  for (; t + kLag1Lanes <= count; t += kLag1Lanes) {
    for (std::size_t lane = 0; lane < kLag1Lanes; ++lane) {
      const auto at = static_cast<std::ptrdiff_t>(t + lane);
      const double now = centred(at);
      lag[lane] += centred(at - 1) * now;
      square[lane] += now * now;
      if constexpr (Order == 0) sum[lane] += now;
    }
  }
  for (; t < count; ++t) {
    const auto at = static_cast<std::ptrdiff_t>(t);
    const double now = centred(at);
    lag[0] += centred(at - 1) * now;
    square[0] += now * now;
    if constexpr (Order == 0) sum[0] += now;
  }
  lagged = lag;
  squares = square;
  if constexpr (Order == 0) values = sum;
}

/// add_order_sums<0> and <1> in one loop: three loads per point serve both (bitwise the same
/// sums as the two loops). ZeroShift: the order-0 shift mean[0] is 0 (a phase integrated from
/// rates starts at 0), so subtracting it, exact, is left out: two additions of seven fewer.
template <bool ZeroShift>
[[gnu::always_inline]] inline void add_order_sums_0_1(const double* z, std::size_t count,
                                                      const PerDifference& mean, LaneSums& lagged,
                                                      LaneSums& squares,
                                                      std::array<double, kLag1Lanes>& values) {
  const double mu0 = ZeroShift ? 0.0 : mean[0];
  const double mu1 = mean[1];
  std::array<double, kLag1Lanes> lag0 = lagged[0];
  std::array<double, kLag1Lanes> square0 = squares[0];
  std::array<double, kLag1Lanes> sum0 = values;
  std::array<double, kLag1Lanes> lag1 = lagged[1];
  std::array<double, kLag1Lanes> square1 = squares[1];
  const auto add = [&](std::size_t t, std::size_t lane) {
    const double e0 = z[t];
    const double e1 = *(z + t - 1);
    const double e2 = *(z + t - 2);
    const double now0 = ZeroShift ? e0 : e0 - mu0;
    lag0[lane] += (ZeroShift ? e1 : e1 - mu0) * now0;
    square0[lane] += now0 * now0;
    sum0[lane] += now0;
    const double now1 = (e0 - e1) - mu1;
    lag1[lane] += ((e1 - e2) - mu1) * now1;
    square1[lane] += now1 * now1;
  };
  std::size_t t = 0;
  for (; t + kLag1Lanes <= count; t += kLag1Lanes) {
    for (std::size_t lane = 0; lane < kLag1Lanes; ++lane) add(t + lane, lane);
  }
  for (; t < count; ++t) add(t, 0);
  lagged[0] = lag0;
  squares[0] = square0;
  values = sum0;
  lagged[1] = lag1;
  squares[1] = square1;
}

/// One contiguous piece of decimated points: z[-(highest + 1) .. count - 1] readable. Adds the
/// centred products D_d(t - 1) D_d(t) and squares D_d(t)^2, t = 0 .. count - 1, for the orders
/// lowest <= d <= highest. Every loop is contiguous, so it vectorises.
STOCHNAV_WIDE_VECTOR_CLONES
void add_piece_sums(const double* z, std::size_t count, const PerDifference& mean, int lowest,
                    int highest, LaneSums& lagged, LaneSums& squares,
                    std::array<double, kLag1Lanes>& values) {
  if (lowest == 0 && highest >= 1) {
    if (mean[0] == 0.0) {
      add_order_sums_0_1<true>(z, count, mean, lagged, squares, values);
    } else {
      add_order_sums_0_1<false>(z, count, mean, lagged, squares, values);
    }
    lowest = 2;
  }
  for (int order = lowest; order <= highest; ++order) {
    const auto d = static_cast<std::size_t>(order);
    switch (order) {
      case 0:
        add_order_sums<0>(z, count, mean[d], lagged[d], squares[d], values);
        break;
      case 1:
        add_order_sums<1>(z, count, mean[d], lagged[d], squares[d], values);
        break;
      case 2:
        add_order_sums<2>(z, count, mean[d], lagged[d], squares[d], values);
        break;
      default:
        add_order_sums<3>(z, count, mean[d], lagged[d], squares[d], values);
        break;
    }
  }
}

/// z[t] = from[t m], t < count: the decimated points of one piece, made contiguous. The strides
/// 2 and 4 (the costliest after m = 1: half and a quarter of the record) are constants in their
/// loops, so they vectorise (loads and shuffles instead of one load per point).
STOCHNAV_WIDE_VECTOR_CLONES
void gather_decimated(const double* from, std::size_t m, std::size_t count, double* z) {
  switch (m) {
    case 2:
      for (std::size_t t = 0; t < count; ++t) z[t] = from[2 * t];
      break;
    case 4:
      for (std::size_t t = 0; t < count; ++t) z[t] = from[4 * t];
      break;
    default:
      for (std::size_t t = 0; t < count; ++t) z[t] = from[t * m];
      break;
  }
}

/// The sums of the orders lowest <= d <= highest (<= MaxD) over one range. Each order has its
/// own accumulators, so they come out the same whichever orders are computed together.
template <int MaxD>
Lag1Sums lag1_sums(const double* x, std::size_t m, DecimatedRange range, const PerDifference& mean,
                   int lowest, int highest) {
  Lag1Sums sums;
  std::size_t k = range.begin;
  const auto low = static_cast<std::size_t>(lowest);
  const auto high = static_cast<std::size_t>(highest);
  // The first MaxD + 1 points, where the higher differences are still incomplete.
  for (; k < range.end && k <= static_cast<std::size_t>(MaxD); ++k) {
    const PerDifference now = differences_ending_at<MaxD>(x, m, k);
    const PerDifference before = k > 0 ? differences_ending_at<MaxD>(x, m, k - 1) : PerDifference{};
    for (std::size_t d = low; d <= k && d <= high; ++d) {
      const double centred = now[d] - mean[d];
      if (k > d) sums.lagged[d] += (before[d] - mean[d]) * centred;
      sums.squares[d] += centred * centred;
      if (d == 0) sums.values += centred;
    }
  }
  // The rest in pieces: gather the piece's decimated points (and the MaxD + 1 before it) into a
  // contiguous scratch array, then add_piece_sums.
  constexpr std::size_t kPiece = 512;
  constexpr std::size_t kBack = MaxD + 1;  // points before the piece its first term needs
  std::array<double, kPiece + kBack> z;
  LaneSums lagged{};
  LaneSums squares{};
  std::array<double, kLag1Lanes> values{};
  if (m == 1 && k < range.end) {
    // The decimated points are the phase itself: no copy.
    add_piece_sums(x + k, range.end - k, mean, lowest, highest, lagged, squares, values);
    k = range.end;
  }
  while (k < range.end) {
    const std::size_t count = std::min(kPiece, range.end - k);
    const double* from = x + (k - kBack) * m;
    gather_decimated(from, m, count + kBack, z.data());
    add_piece_sums(z.data() + kBack, count, mean, lowest, highest, lagged, squares, values);
    k += count;
  }
  // Pairwise: lanes (2j, 2j + 1), then pairs of those, and so on.
  const auto reduce = [](std::array<double, kLag1Lanes> a) {
    for (std::size_t width = kLag1Lanes / 2; width >= 1; width /= 2) {
      for (std::size_t lane = 0; lane < width; ++lane) a[lane] = a[2 * lane] + a[2 * lane + 1];
    }
    return a[0];
  };
  for (std::size_t d = low; d <= high; ++d) {
    sums.lagged[d] += reduce(lagged[d]);
    sums.squares[d] += reduce(squares[d]);
  }
  sums.values += reduce(values);
  return sums;
}

/// r1[d] of many factors, as lag1_of_decimated_differences<MaxD> gives each (up to rounding),
/// in two steps: the blocks of the pass for orders 0 and 1 (add_block, any order, any thread),
/// then finish().
class Lag1OfMany {
 public:
  virtual ~Lag1OfMany() = default;
  virtual std::size_t blocks() const = 0;
  virtual void add_block(std::size_t block) = 0;
  virtual std::vector<PerDifference> finish() = 0;
};

template <int MaxD>
class Lag1OfManyOf final : public Lag1OfMany {
 public:
  Lag1OfManyOf(std::span<const double> phase, std::vector<std::size_t> m_values)
      : phase_(phase),
        m_values_(std::move(m_values)),
        factors_(m_values_.size()),
        blocks_((phase.size() + kLag1BlockPoints - 1) / kLag1BlockPoints),
        points_(factors_),
        means_(factors_),
        block_sums_(blocks_ * factors_) {
    // The means of the differences d >= 1 telescope to their end points. For d = 0 the sums are
    // taken about K = z(0) and corrected afterwards (shifted data: z(0) lies within the spread
    // of a phase record, so nothing cancels badly): one pass over the record fewer.
    for (std::size_t j = 0; j < factors_; ++j) {
      const std::size_t m = m_values_[j];
      points_[j] = (phase.size() - 1) / m + 1;
      const auto z = [&](std::size_t k) { return phase[k * m]; };
      const std::size_t last = points_[j] - 1;
      PerDifference& mean = means_[j];
      mean[0] = z(0);  // the shift K
      mean[1] = (z(last) - z(0)) / static_cast<double>(points_[j] - 1);
      mean[2] = ((z(last) - z(last - 1)) - (z(1) - z(0))) / static_cast<double>(points_[j] - 2);
      if constexpr (MaxD >= 3) {
        mean[3] = ((z(last) - 2.0 * z(last - 1) + z(last - 2)) - (z(2) - 2.0 * z(1) + z(0))) /
                  static_cast<double>(points_[j] - 3);
      }
    }
  }

  std::size_t blocks() const override { return blocks_; }

  /// The centred lag products and squares of orders 0 and 1, every factor, one block.
  void add_block(std::size_t block) override {
    add_orders_in_block(block, 0, 1, all(), block_sums_);
  }

  /// Orders 0 and 1 from the block sums; then the higher orders for the factors whose
  /// differences still look correlated (usually a few long taus with few points), in a pass of
  /// their own. noise_from_lag1 reads no order beyond the one it stops at.
  std::vector<PerDifference> finish() override {
    std::vector<PerDifference> r1(factors_);
    const std::vector<std::size_t> every = all();
    add_totals(0, 1, every, block_sums_, r1);
    std::vector<std::size_t> correlated;
    const auto white = [](double r) { return r / (1.0 + r) < 0.25; };  // as noise_from_lag1
    for (std::size_t j = 0; j < factors_; ++j) {
      if (!white(r1[j][0]) && !white(r1[j][1])) correlated.push_back(j);
    }
    if (!correlated.empty()) {
      std::vector<Lag1Sums> sums(blocks_ * correlated.size());
      parallel_for(blocks_, [&](std::size_t block) {
        add_orders_in_block(block, 2, MaxD, correlated, sums);
      });
      add_totals(2, MaxD, correlated, sums, r1);
    }
    return r1;
  }

 private:
  std::vector<std::size_t> all() const {
    std::vector<std::size_t> every(factors_);
    for (std::size_t j = 0; j < factors_; ++j) every[j] = j;
    return every;
  }

  /// sums[block * which.size() + i]: orders lowest .. highest of factor which[i] in the block.
  void add_orders_in_block(std::size_t block, int lowest, int highest,
                           const std::vector<std::size_t>& which,
                           std::vector<Lag1Sums>& sums) const {
    const std::size_t first = block * kLag1BlockPoints;
    const std::size_t last = std::min(phase_.size(), first + kLag1BlockPoints);
    for (std::size_t i = 0; i < which.size(); ++i) {
      const std::size_t j = which[i];
      const DecimatedRange range = decimated_range(m_values_[j], points_[j], first, last);
      if (range.begin < range.end) {
        sums[block * which.size() + i] =
            lag1_sums<MaxD>(phase_.data(), m_values_[j], range, means_[j], lowest, highest);
      }
    }
  }

  /// The block sums added in block order (the same for every thread count), into r1.
  void add_totals(int lowest, int highest, const std::vector<std::size_t>& which,
                  const std::vector<Lag1Sums>& sums, std::vector<PerDifference>& r1) const {
    const std::size_t count = which.size();
    for (std::size_t i = 0; i < count; ++i) {
      Lag1Sums total;
      for (std::size_t block = 0; block < blocks_; ++block) {
        const Lag1Sums& part = sums[block * count + i];
        for (auto d = static_cast<std::size_t>(lowest); d <= static_cast<std::size_t>(highest);
             ++d) {
          total.lagged[d] += part.lagged[d];
          total.squares[d] += part.squares[d];
        }
        total.values += part.values;
      }
      const std::size_t j = which[i];
      if (lowest == 0) {
        // From sums about K to sums about the mean: u = z - K, S = sum u, c = S / n = mean - K,
        // u(0) = 0. sum (u - c)^2 = Q - S c; sum over pairs (u_(k-1) - c)(u_k - c)
        // = L - c (2 S - u(n-1)) + (n - 1) c^2.
        const double n = static_cast<double>(points_[j]);
        const double shift_sum = total.values;
        const double c = shift_sum / n;
        const double u_last = phase_[(points_[j] - 1) * m_values_[j]] - means_[j][0];
        total.squares[0] -= shift_sum * c;
        total.lagged[0] += -c * (2.0 * shift_sum - u_last) + (n - 1.0) * c * c;
      }
      for (auto d = static_cast<std::size_t>(lowest); d <= static_cast<std::size_t>(highest); ++d) {
        r1[j][d] = total.squares[d] > 0.0 ? total.lagged[d] / total.squares[d] : 0.0;
      }
    }
  }

  std::span<const double> phase_;
  std::vector<std::size_t> m_values_;
  std::size_t factors_;
  std::size_t blocks_;
  std::vector<std::size_t> points_;
  std::vector<PerDifference> means_;
  std::vector<Lag1Sums> block_sums_;  // orders 0 and 1: [block * factors + j]
};

std::unique_ptr<Lag1OfMany> make_lag1_of_many(int max_differences, std::span<const double> phase,
                                              std::vector<std::size_t> m_values) {
  if (max_differences >= 3) return std::make_unique<Lag1OfManyOf<3>>(phase, std::move(m_values));
  return std::make_unique<Lag1OfManyOf<2>>(phase, std::move(m_values));
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
  const double flicker_pm =
      3.0 * std::log(256.0 / 27.0) / (2.0 * (1.038 + 3.0 * std::log(std::numbers::pi * md)));
  return ratio < std::sqrt(white_pm * flicker_pm) ? 2 : 1;
}

NoiseId b1_and_rn_noise_id(Deviation kind, std::span<const double> phase, std::size_t m) {
  // Stable32 evaluates the expected ratios at the estimator's term count (its `#` column), not
  // at the number of averages: that is what reproduces its tables (Cs 5071A, all taus). Fewer
  // than 2 makes every expectation 1 (no information) rather than undefined.
  const double n = static_cast<double>(std::max<std::size_t>(term_count(kind, m, phase.size()), 2));
  const double ratio = b1_ratio(phase, m);
  int mu = -2;
  while (mu < 2 && ratio >= std::sqrt(b1_expected(n, mu) * b1_expected(n, mu + 1))) ++mu;
  if (mu != -2) return {alpha_from_mu(mu), NoiseIdMethod::kB1Ratio, ratio};
  // R(n) needs one MDEV term: N >= 3m.
  if (term_count(Deviation::kMdev, m, phase.size()) == 0) {
    return {1, NoiseIdMethod::kB1Ratio, ratio};
  }
  return {white_or_flicker_pm(phase, m), NoiseIdMethod::kB1AndRn, ratio};
}

/// Stable32's small-sample identification (B1 ratio, then R(n)), with its plausible range.
NoiseId b1_noise_id(Deviation kind, std::span<const double> phase, std::size_t m) {
  NoiseId id = b1_and_rn_noise_id(kind, phase, m);
  id.plausible = widened_to(plausible_alphas(kind, phase, m), id.alpha);
  return id;
}

}  // namespace

AlphaRange plausible_alphas(Deviation kind, std::span<const double> phase, std::size_t m) {
  if (m == 0) throw std::invalid_argument("plausible_alphas: m must be at least 1");
  if (phase.size() < 2) return {};
  const int max_differences = difference_order(kind);
  const std::size_t points = decimated_point_count(phase, m);
  if (points < static_cast<std::size_t>(max_differences) + kMinPlausibleValues) return {};
  return lag1_noise_id(phase, m, max_differences).plausible;
}

double lag1_autocorrelation(std::span<const double> series) {
  if (series.size() < 2) return 0.0;
  return lag1_of_decimated_differences<0>(series, 1, series.size())[0];
}

double b1_expected(double n, int mu) {
  if (mu == 0) return n * std::log(n) / (2.0 * (n - 1.0) * std::numbers::ln2);
  const double p = static_cast<double>(mu);
  return n * (1.0 - std::pow(n, p)) / (2.0 * (n - 1.0) * (1.0 - std::pow(2.0, p)));
}

bool keeps_previous_noise_type(Deviation kind, std::size_t m, std::size_t phase_count) {
  if (m == 0 || phase_count < 2) return false;
  const std::size_t averages = (phase_count - 1) / m;
  if (averages + 1 >= kMinLag1Points) return false;
  return averages < (is_overlapping(kind) ? 8u : 10u);
}

namespace {
void require_identifiable(std::span<const double> phase, std::size_t m) {
  if (m == 0 || phase.size() < 2 * m + 2) {
    throw std::invalid_argument("identify_noise: m = " + std::to_string(m) + " needs more than " +
                                std::to_string(2 * m + 1) + " phase points, got " +
                                std::to_string(phase.size()));
  }
}
}  // namespace

NoiseId identify_noise(Deviation kind, std::span<const double> phase, std::size_t m) {
  require_identifiable(phase, m);
  const std::size_t decimated_points = (phase.size() - 1) / m + 1;
  if (decimated_points >= kMinLag1Points) {
    return lag1_noise_id(phase, m, difference_order(kind));
  }
  return b1_noise_id(kind, phase, m);
}

}  // namespace stochnav

namespace stochnav {

struct NoiseIdentification::Impl {
  Deviation kind;
  std::span<const double> phase;
  std::span<const std::size_t> m_values;
  std::vector<std::size_t> lag1_slots;   // places in m_values of the factors of the lag-1 method
  std::vector<std::size_t> other_slots;  // the others (B1 ratio)
  std::unique_ptr<Lag1OfMany> lag1;      // null without lag-1 factors
};

NoiseIdentification::NoiseIdentification(Deviation kind, std::span<const double> phase,
                                         std::span<const std::size_t> m_values)
    : impl_(std::make_unique<Impl>()) {
  for (std::size_t m : m_values) require_identifiable(phase, m);
  impl_->kind = kind;
  impl_->phase = phase;
  impl_->m_values = m_values;
  std::vector<std::size_t> lag1_factors;
  for (std::size_t j = 0; j < m_values.size(); ++j) {
    if ((phase.size() - 1) / m_values[j] + 1 >= kMinLag1Points) {
      lag1_factors.push_back(m_values[j]);
      impl_->lag1_slots.push_back(j);
    } else {
      impl_->other_slots.push_back(j);
    }
  }
  if (!lag1_factors.empty()) {
    impl_->lag1 = make_lag1_of_many(difference_order(kind), phase, std::move(lag1_factors));
  }
}

NoiseIdentification::~NoiseIdentification() = default;

AlongsideJob NoiseIdentification::lag1_job() {
  static_assert(kLag1BlockPoints == kAlongsideBlockPoints, "lag-1 blocks are job blocks");
  if (!impl_->lag1) return {};
  Lag1OfMany* lag1 = impl_->lag1.get();
  return {lag1->blocks(), [lag1](std::size_t block) { lag1->add_block(block); }};
}

std::vector<NoiseId> NoiseIdentification::finish() {
  const Impl& plan = *impl_;
  std::vector<NoiseId> ids(plan.m_values.size());
  // The B1 identifications: few averages each, one task per factor.
  parallel_for(plan.other_slots.size(), [&](std::size_t i) {
    const std::size_t slot = plan.other_slots[i];
    ids[slot] = identify_noise(plan.kind, plan.phase, plan.m_values[slot]);
  });
  if (plan.lag1) {
    const int max_differences = difference_order(plan.kind);
    const std::vector<PerDifference> r1 = plan.lag1->finish();
    for (std::size_t i = 0; i < plan.lag1_slots.size(); ++i) {
      const std::size_t slot = plan.lag1_slots[i];
      ids[slot] = noise_from_lag1(r1[i], max_differences,
                                  decimated_point_count(plan.phase, plan.m_values[slot]));
    }
  }
  return ids;
}

std::vector<NoiseId> identify_noises(Deviation kind, std::span<const double> phase,
                                     std::span<const std::size_t> m_values) {
  NoiseIdentification identification(kind, phase, m_values);
  const AlongsideJob job = identification.lag1_job();
  parallel_for(job.blocks, [&job](std::size_t block) { job.run(block); });
  return identification.finish();
}

}  // namespace stochnav
