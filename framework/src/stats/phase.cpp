#include "stochnav/stats/phase.hpp"

#include <algorithm>
#include <array>

#if defined(__linux__)
#include <sys/mman.h>
#endif
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <new>
#include <string_view>
#include <utility>

#include "stochnav/core/huge_page_buffer.hpp"
#include "stochnav/io/mapped_file.hpp"
#include "stochnav/io/sample_reader.hpp"
#include "stochnav/stats/parallel.hpp"
#include "vector_clones.hpp"

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

/// Rate samples per chunk of the two parallel passes, and chunks per task. Fixed, so the
/// result does not depend on the thread count.
constexpr std::size_t kChunk = std::size_t{1} << 14;
constexpr std::size_t kChunksPerTask = 8;
/// Tasks at the start of the record whose rates integrate() lets go after pass 1 already: 8 MB
/// of float64 rates, room for the huge pages of the phase that pass 2 writes ahead of the file
/// pages it drops.
constexpr std::size_t kEarlyDroppedTasks = 8;

/// Compensated sum of one chunk (or of a whole record): four independent lanes, so the
/// additions pipeline.
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

/// Eight doubles in one vector (the vector extension of GCC and clang): one AVX-512 register, two
/// AVX2 ones, four SSE2 ones in the default clone.
using Vector8 = double __attribute__((vector_size(64)));

// Passed by reference: a vector argument or result would change the ABI with the instruction set.
[[gnu::always_inline]] inline void load8(Vector8& v, const double* from) {
  std::memcpy(&v, from, sizeof v);
}
[[gnu::always_inline]] inline void store8(double* to, const Vector8& v) {
  std::memcpy(to, &v, sizeof v);
}

/// chunk_sum with sixteen lanes (two vectors of eight), for the parallel integration: the same
/// error bound, and the additions fill the vector units (the four scalar lanes of chunk_sum keep
/// the reference algorithm of phase_from_rate bitwise as it always was).
STOCHNAV_WIDE_VECTOR_CLONES
CompensatedSum wide_chunk_sum(const double* values, std::size_t count) {
  std::array<Vector8, 2> high{};
  std::array<Vector8, 2> low{};
  std::size_t i = 0;
  for (; i + 16 <= count; i += 16) {
    for (std::size_t half = 0; half < 2; ++half) {  // CompensatedSum::add, lane by lane
      Vector8 value;
      load8(value, values + i + 8 * half);
      const Vector8 sum = high[half] + value;
      const Vector8 value_part = sum - high[half];
      low[half] += (high[half] - (sum - value_part)) + (value - value_part);
      high[half] = sum;
    }
  }
  std::array<CompensatedSum, 16> lanes;
  for (std::size_t lane = 0; lane < 16; ++lane) {
    lanes[lane] = {high[lane / 8][lane % 8], low[lane / 8][lane % 8]};
  }
  for (; i < count; ++i) lanes[0].add(values[i]);
  for (std::size_t width = 8; width >= 1; width /= 2) {
    for (std::size_t lane = 0; lane < width; ++lane) lanes[lane].merge(lanes[lane + width]);
  }
  return lanes[0];
}

/// Transposes the 8 x 8 matrix of rows r[0..7] in place: three rounds of pairwise shuffles.
[[gnu::always_inline]] inline void transpose8(std::array<Vector8, 8>& r) {
  std::array<Vector8, 8> t;
  for (std::size_t k = 0; k < 8; k += 2) {  // 2 x 2 blocks of single elements
    t[k] = __builtin_shufflevector(r[k], r[k + 1], 0, 8, 2, 10, 4, 12, 6, 14);
    t[k + 1] = __builtin_shufflevector(r[k], r[k + 1], 1, 9, 3, 11, 5, 13, 7, 15);
  }
  for (std::size_t k = 0; k < 8; k += 4) {  // of pairs
    for (std::size_t j = 0; j < 2; ++j) {
      r[k + j] = __builtin_shufflevector(t[k + j], t[k + j + 2], 0, 1, 8, 9, 4, 5, 12, 13);
      r[k + j + 2] = __builtin_shufflevector(t[k + j], t[k + j + 2], 2, 3, 10, 11, 6, 7, 14, 15);
    }
  }
  for (std::size_t j = 0; j < 4; ++j) {  // of quadruples
    t[j] = __builtin_shufflevector(r[j], r[j + 4], 0, 1, 2, 3, 8, 9, 10, 11);
    t[j + 4] = __builtin_shufflevector(r[j], r[j + 4], 4, 5, 6, 7, 12, 13, 14, 15);
  }
  r = t;
}

/// The running sums of eight whole chunks at once, chunk L in vector lane L: per chunk the same
/// operations in the same order as CompensatedSum::add one sample after another, so the phase is
/// bitwise the same, but eight chains of additions advance in one instruction each. Blocks of
/// 8 x 8 samples are transposed in registers on the way in and out. No contraction of the
/// multiply-subtract into a fused one: the clones must round as the default code does.
/// rate and x point at the first sample of the first chunk; start_high/low: the compensated
/// sums before each chunk; first_position: the 1-based index of the first sample.
STOCHNAV_WIDE_VECTOR_CLONES __attribute__((optimize("fp-contract=off"))) void
running_sums_of_eight_chunks(const double* rate, double* x, const double* start_high,
                             const double* start_low, double first_position, double mean_high,
                             double mean_low, double tau0_s) {
  Vector8 high;
  Vector8 low;
  load8(high, start_high);
  load8(low, start_low);
  Vector8 position;
  for (std::size_t lane = 0; lane < 8; ++lane) {
    position[lane] = first_position + static_cast<double>(lane * kChunk);
  }
  std::array<Vector8, 8> block;
  for (std::size_t i = 0; i < kChunk; i += 8) {
    for (std::size_t lane = 0; lane < 8; ++lane) load8(block[lane], rate + lane * kChunk + i);
    transpose8(block);  // block[j]: sample i + j of every chunk
    for (std::size_t j = 0; j < 8; ++j) {
      const Vector8 value = block[j] - mean_high;
      const Vector8 sum = high + value;
      const Vector8 value_part = sum - high;
      low += (high - (sum - value_part)) + (value - value_part);
      high = sum;
      block[j] = ((high + low) - position * mean_low) * tau0_s;
      position += 1.0;
    }
    transpose8(block);
    for (std::size_t lane = 0; lane < 8; ++lane) store8(x + lane * kChunk + i, block[lane]);
  }
}

/// x[i + 1] = (sum_{j <= i} (y[j] - mean)) tau0 for the n rates y; x may be y (in place).
/// `done(first, count)` is called when a pass has read the rates [first, first + count) for the
/// last time for a while: after pass 2, and after pass 1 for the first kEarlyDroppedTasks tasks
/// (which pass 2, running backwards, reaches last). A mapped file's pages can be dropped then:
/// pass 2 writes the phase as it drops the file, so the file's resident pages and the phase
/// array never add up to much more than one copy of the data (the stretch dropped early makes
/// room for the huge pages of the phase, which run ahead of the pages dropped). Dropping every
/// page after pass 1 as well cost mapping the file twice: about 5 % of an OADEV run's CPU time.
/// Returns false, having written nothing, when the rates do not sum to a finite number (a NaN
/// or infinite sample, or overflow).
bool integrate(const double* rate, double* x_after_first, std::size_t n, double tau0_s,
               const std::function<void(std::size_t, std::size_t)>& done) {
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  const std::size_t tasks = (chunks + kChunksPerTask - 1) / kChunksPerTask;
  const auto chunk_size = [&](std::size_t c) { return std::min(kChunk, n - c * kChunk); };

  // Pass 1: the chunk sums, hence the mean and the running sum at every chunk start.
  std::vector<CompensatedSum> sums(chunks);
  parallel_for(tasks, [&](std::size_t task) {
    const std::size_t last = std::min(chunks, (task + 1) * kChunksPerTask);
    for (std::size_t c = task * kChunksPerTask; c < last; ++c) {
      sums[c] = wide_chunk_sum(rate + c * kChunk, chunk_size(c));
    }
    if (done && task < kEarlyDroppedTasks) {
      done(task * kChunksPerTask * kChunk, (last - task * kChunksPerTask) * kChunk);
    }
  });
  CompensatedSum total;
  for (const auto& sum : sums) total.merge(sum);
  if (!std::isfinite(total.value())) return false;
  const double count = static_cast<double>(n);
  SplitMean mean;
  mean.high = total.value() / count;
  // The remainder of the division, exact up to one rounding: sum - n * high.
  mean.low = (std::fma(-count, mean.high, total.high()) + total.low()) / count;
  // starts[c] = sum of (y - mean.high) before chunk c: the prefix of the chunk sums minus
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

  // Pass 2: the running sums, each chunk from its exact start. A task runs its eight chunks
  // side by side in vector lanes (running_sums_of_eight_chunks), the same operations as one by
  // one; a last, shorter task goes one chunk after another.
  static_assert(kChunksPerTask == 8, "running_sums_of_eight_chunks takes eight chunks");
  // Locals, not captures by reference: the stores to x could alias those, which would reload
  // them from memory at every step. The index goes through int64_t: a signed conversion is one
  // instruction, an unsigned one a branch (the same value: i + 1 < 2^53).
  const double mean_high = mean.high;
  const double mean_low = mean.low;
  const auto step = [rate, x_after_first, mean_high, mean_low, tau0_s](CompensatedSum& running,
                                                                       std::size_t i) {
    running.add(rate[i] - mean_high);
    const auto position = static_cast<double>(static_cast<std::int64_t>(i + 1));
    x_after_first[i] = (running.value() - position * mean_low) * tau0_s;
  };
  // The tasks run from the end of the record back to its start: the stretch pass 1 read last
  // is then still in the last-level cache, and so, afterwards, is the start of the phase, where
  // the deviation sums begin. The tasks are independent: the same result in any order.
  parallel_for(tasks, [&](std::size_t from_end) {
    const std::size_t task = tasks - 1 - from_end;
    const std::size_t first = task * kChunksPerTask;
    const std::size_t last = std::min(chunks, first + kChunksPerTask);
    if (last - first == kChunksPerTask && chunk_size(last - 1) == kChunk) {
      std::array<double, kChunksPerTask> high;
      std::array<double, kChunksPerTask> low;
      for (std::size_t lane = 0; lane < kChunksPerTask; ++lane) {
        high[lane] = starts[first + lane].high();
        low[lane] = starts[first + lane].low();
      }
      running_sums_of_eight_chunks(
          rate + first * kChunk, x_after_first + first * kChunk, high.data(), low.data(),
          static_cast<double>(static_cast<std::int64_t>(first * kChunk + 1)), mean_high, mean_low,
          tau0_s);
    } else {
      for (std::size_t c = first; c < last; ++c) {
        CompensatedSum running = starts[c];
        for (std::size_t i = 0; i < chunk_size(c); ++i) step(running, c * kChunk + i);
      }
    }
    if (done) done(first * kChunk, (last - first) * kChunk);
  });
  return true;
}

}  // namespace

void phase_from_rate_in_place(std::span<double> buffer, double tau0_s) {
  if (buffer.empty()) return;
  buffer[0] = 0.0;
  if (buffer.size() < 2) return;
  if (!integrate(buffer.data() + 1, buffer.data() + 1, buffer.size() - 1, tau0_s, {})) {
    // A NaN or infinite sample (or overflow): no phase point is meaningful.
    std::fill(buffer.begin() + 1, buffer.end(), std::numeric_limits<double>::quiet_NaN());
  }
}

std::vector<double> phase_from_rate(std::span<const double> rate, double tau0_s) {
  // The reference algorithm, one running sum from the start: bitwise what stochnav has always
  // given (diagnose and fit results rest on it).
  std::vector<double> phase = huge_page_buffer(rate.size() + 1);
  phase.resize(rate.size() + 1);
  phase[0] = 0.0;
  if (rate.empty()) return phase;
  const CompensatedSum total = chunk_sum(rate.data(), rate.size());
  const double n = static_cast<double>(rate.size());
  const double mean_high = total.value() / n;
  // The remainder of the division, exact up to one rounding: sum - n * high.
  const double mean_low = (std::fma(-n, mean_high, total.high()) + total.low()) / n;
  CompensatedSum running;
  for (std::size_t i = 0; i < rate.size(); ++i) {
    running.add(rate[i] - mean_high);
    phase[i + 1] = (running.value() - static_cast<double>(i + 1) * mean_low) * tau0_s;
  }
  return phase;
}

namespace {

bool is_single_float64_channel(const ReadOptions& options) {
  const std::string_view path = options.path;
  return options.binary_channels == 1 && path.size() > 4 && path.substr(path.size() - 4) == ".f64";
}

}  // namespace

/// Uninitialised storage for n doubles in transparent huge pages where the kernel allows: the
/// pages are first touched, and zeroed, by the threads that fill them. Only whole huge pages
/// inside the data are advised: the tail stays in small pages, so the resident memory is the
/// data's size, not up to one huge page (2 MB) more.
std::shared_ptr<double[]> huge_page_array(std::size_t n) {
  constexpr std::size_t kHugePage = std::size_t{1} << 21;
  constexpr std::size_t kPage = std::size_t{1} << 12;
  const std::size_t bytes = (n * sizeof(double) + kPage - 1) / kPage * kPage;
  // posix_memalign: the size need not be a multiple of the alignment (aligned_alloc's rule).
  void* memory = nullptr;
  if (::posix_memalign(&memory, kHugePage, bytes) != 0) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::size_t whole_huge_pages = n * sizeof(double) / kHugePage * kHugePage;
  if (whole_huge_pages > 0) ::madvise(memory, whole_huge_pages, MADV_HUGEPAGE);  // a hint only
#endif
  return std::shared_ptr<double[]>(static_cast<double*>(memory), [](double* p) { std::free(p); });
}

std::shared_ptr<double[]> phase_array_from_rate(std::span<const double> rate, double tau0_s) {
  if (rate.empty()) return nullptr;
  std::shared_ptr<double[]> phase = huge_page_array(rate.size() + 1);
  phase[0] = 0.0;
  if (!integrate(rate.data(), phase.get() + 1, rate.size(), tau0_s, {})) return nullptr;
  return phase;
}

PhaseRecord read_phase_record(const ReadOptions& options) {
  PhaseRecord result;
  if (options.kind == DataKind::kRate && is_single_float64_channel(options)) {
    // Raw float64 rates: integrated straight from the mapped file into the phase array, the
    // file's pages released as they are consumed: memory holds about one copy of the data.
    const SampleReader reader(options);  // the checks and messages of read_record
    const MappedFile file(options.path);
    const std::size_t n = file.bytes().size() / sizeof(double);
    const auto* rate = reinterpret_cast<const double*>(file.bytes().data());
    if (n >= 2) {
      std::shared_ptr<double[]> phase = huge_page_array(n + 1);
      phase[0] = 0.0;
      const bool finite = integrate(rate, phase.get() + 1, n, 1.0 / reader.rate_hz(),
                                    [&file, &options](std::size_t first, std::size_t count) {
                                      file.release(first * sizeof(double), count * sizeof(double));
                                      // Progress: each rate is reported done once, after
                                      // pass 2, the first stretch also after pass 1 (the bar
                                      // reaches its end those few MB early; it clamps at 100 %).
                                      if (options.bytes_read != nullptr) {
                                        options.bytes_read->fetch_add(count * sizeof(double));
                                      }
                                    });
      if (finite) {
        result.record.rate_hz = reader.rate_hz();
        result.record.start_time_s = reader.start_time_s();
        result.record.kind = options.kind;
        result.record.unit = options.unit;
        result.record.source = options.path;
        result.record.column = reader.column_name();
        result.samples = n;
        result.array_ = std::move(phase);
        result.phase_ = std::span<const double>(result.array_.get(), n + 1);
        return result;
      }
    }
    // Too short, or not finite: read_record says what is wrong (or reproduces the old result).
  }
  result.record = read_record(options, options.kind == DataKind::kRate ? 1 : 0);
  result.vector_ = std::move(result.record.values);
  result.record.values.clear();
  result.samples = result.vector_.size() - (options.kind == DataKind::kRate ? 1 : 0);
  if (options.kind == DataKind::kRate)
    phase_from_rate_in_place(result.vector_, result.record.tau0());
  result.phase_ = result.vector_;
  return result;
}

}  // namespace stochnav
