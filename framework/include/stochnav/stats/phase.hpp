#pragma once
// From a rate record (gyro rate, fractional frequency) to the phase record (angle, clock phase)
// that every Allan-family estimator works on.

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "stochnav/io/record.hpp"

namespace stochnav {

/// Integrates N rate samples y (any unit U) taken every tau0_s seconds into N + 1 phase points
/// (unit U*s):
///   x[0] = 0,  x[i + 1] = x[i] + (y[i] - mean(y)) * tau0_s.
/// The mean rate is removed first. That subtracts a straight line from the phase, which every
/// deviation of deviation.hpp annihilates (they are built from second or third differences of
/// x), so no deviation changes; but it keeps |x| small, so the differences do not lose digits to
/// cancellation against a large ramp. The mean and the running sum use compensated (Neumaier)
/// summation: the error of x[i] stays a few ulps whatever N is.
/// An empty `rate` gives {0}. tau0_s must be > 0 (not checked).
/// One running sum from the first sample to the last (serial). Cost: two passes over the data.
std::vector<double> phase_from_rate(std::span<const double> rate, double tau0_s);

/// phase_from_rate without a second array, and in parallel: on entry buffer[1 .. N] hold the N
/// rate samples (buffer[0] is ignored); on return buffer[0 .. N] hold the N + 1 phase points.
/// The running sum is cut into chunks of 16384 samples spread over the stats threads
/// (parallel.hpp), each chunk started from the exact compensated sum of the ones before it, so
/// the points agree with phase_from_rate to a few ulps (not bitwise: the rounding happens in a
/// different order) and are bitwise the same for every thread count. An empty buffer is left
/// alone. A NaN or infinite rate (or a sum that overflows) makes every point but the first NaN.
void phase_from_rate_in_place(std::span<double> buffer, double tau0_s);

/// phase_from_rate_in_place's integration from `rate` (N samples, left unchanged) into a new
/// array of N + 1 phase points, advised into transparent huge pages (core/huge_page_buffer.hpp):
/// the points of phase_from_rate_in_place on a copy of `rate`, bitwise, without the copy. For
/// records already in memory (the Python module's numpy arrays). Returns nullptr when a sample
/// is NaN or infinite (or the sum overflows), and for an empty `rate`.
std::shared_ptr<double[]> phase_array_from_rate(std::span<const double> rate, double tau0_s);

/// A record file read straight into its phase: one array of the data in memory.
class PhaseRecord {
 public:
  Record record;            ///< everything but `values`, which is left empty
  std::size_t samples = 0;  ///< samples in the file's column
  /// N + 1 points for rate data (as phase_from_rate), N for phase data. Valid while this
  /// object lives (moving it keeps the data where it is).
  std::span<const double> phase() const { return phase_; }

 private:
  friend PhaseRecord read_phase_record(const ReadOptions& options);
  std::vector<double> vector_;
  std::shared_ptr<double[]> array_;
  std::span<const double> phase_;
};

/// Reads options.path as read_record does (same checks, same messages) and integrates rate data
/// in place (phase_from_rate_in_place). A single-channel raw float64 rate file is memory-mapped
/// and integrated straight into the phase array, its pages released as they are consumed.
PhaseRecord read_phase_record(const ReadOptions& options);

}  // namespace stochnav
