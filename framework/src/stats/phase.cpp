#include "stochnav/stats/phase.hpp"

#include <array>
#include <cmath>
#include <utility>

#include "stochnav/core/huge_page_buffer.hpp"
#include "stochnav/stats/parallel.hpp"

namespace stochnav {
namespace {

/// Compensated running sum (Neumaier's method, with Knuth's branch-free TwoSum for the rounding
/// error of each addition): the error stays a few ulps of the result whatever the length, and
/// the only serial dependency is one addition per term.
class CompensatedSum {
 public:
  CompensatedSum() = default;
  CompensatedSum(double high, double low) : sum_(high), compensation_(low) {}
  void add(double value) {
    const double sum = sum_ + value;
    const double value_part = sum - sum_;
    compensation_ += (sum_ - (sum - value_part)) + (value - value_part);
    sum_ = sum;
  }
  double value() const { return sum_ + compensation_; }
  double high() const { return sum_; }
  double low() const { return compensation_; }
  void merge(const CompensatedSum& other) {
    add(other.sum_);
    compensation_ += other.compensation_;
  }

 private:
  double sum_ = 0.0;
  double compensation_ = 0.0;
};

/// The mean as an unevaluated sum high + low: `high` alone, rounded to a double, would leave
/// an error of up to half an ulp that the running sum multiplies by the record length.
struct SplitMean {
  double high = 0.0;
  double low = 0.0;
};

/// Rate samples per task of the two parallel passes. Fixed, so the result does not depend on
/// the thread count.
constexpr std::size_t kChunk = std::size_t{1} << 16;

/// Compensated sum of one chunk: four independent lanes, so the additions pipeline.
CompensatedSum chunk_sum(const double* values, std::size_t count) {
  std::array<CompensatedSum, 4> lanes;
  std::size_t i = 0;
  for (; i + 4 <= count; i += 4) {
    for (std::size_t lane = 0; lane < 4; ++lane) lanes[lane].add(values[i + lane]);
  }
  for (; i < count; ++i) lanes[0].add(values[i]);
  lanes[0].merge(lanes[1]);
  lanes[2].merge(lanes[3]);
  lanes[0].merge(lanes[2]);
  return lanes[0];
}

}  // namespace

void phase_from_rate_in_place(std::span<double> buffer, double tau0_s) {
  if (buffer.empty()) return;
  buffer[0] = 0.0;
  double* rate = buffer.data() + 1;  // rate[i] is read, then phase x[i + 1] written in its place
  const std::size_t n = buffer.size() - 1;
  if (n == 0) return;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  const auto chunk_size = [&](std::size_t c) { return std::min(kChunk, n - c * kChunk); };

  // Pass 1: the chunk sums, hence the mean and the running sum at every chunk start.
  std::vector<CompensatedSum> sums(chunks);
  parallel_for(chunks, [&](std::size_t c) { sums[c] = chunk_sum(rate + c * kChunk, chunk_size(c)); });
  CompensatedSum total;
  for (const auto& sum : sums) total.merge(sum);
  const double count = static_cast<double>(n);
  SplitMean mean;
  mean.high = total.value() / count;
  // The remainder of the division, exact up to one rounding: sum - n * high.
  mean.low = (std::fma(-count, mean.high, total.high()) + total.low()) / count;
  // starts[c] = sum of (y - mean.high) before chunk c: prefix of the chunk sums minus
  // c kChunk mean.high, that product split exactly into p + e (fma).
  std::vector<CompensatedSum> starts(chunks);
  CompensatedSum prefix;
  for (std::size_t c = 0; c < chunks; ++c) {
    const double before = static_cast<double>(c * kChunk);
    const double product = before * mean.high;
    CompensatedSum start = prefix;
    start.add(-product);
    start.add(-std::fma(before, mean.high, -product));
    starts[c] = CompensatedSum(start.high(), start.low());
    prefix.merge(sums[c]);
  }

  // Pass 2: the running sums, chunk by chunk from their exact starts.
  parallel_for(chunks, [&](std::size_t c) {
    CompensatedSum running = starts[c];
    double* values = rate + c * kChunk;
    const std::size_t size = chunk_size(c);
    const std::size_t first = c * kChunk;
    for (std::size_t i = 0; i < size; ++i) {
      running.add(values[i] - mean.high);
      values[i] = (running.value() - static_cast<double>(first + i + 1) * mean.low) * tau0_s;
    }
  });
}

std::vector<double> phase_from_rate(std::span<const double> rate, double tau0_s) {
  std::vector<double> phase = huge_page_buffer(rate.size() + 1);
  phase.push_back(0.0);
  phase.insert(phase.end(), rate.begin(), rate.end());
  phase_from_rate_in_place(phase, tau0_s);
  return phase;
}

PhaseRecord read_phase_record(const ReadOptions& options) {
  PhaseRecord result;
  result.record = read_record(options, options.kind == DataKind::kRate ? 1 : 0);
  result.phase = std::move(result.record.values);
  result.record.values.clear();
  result.samples = result.phase.size() - (options.kind == DataKind::kRate ? 1 : 0);
  if (options.kind == DataKind::kRate) phase_from_rate_in_place(result.phase, result.record.tau0());
  return result;
}

}  // namespace stochnav
