#pragma once
// Internal to the stats domain: the noise identification's pass over the phase record run
// inside the pass of the overlapping deviation sums (compute_deviation), so each stretch of the
// record comes from memory once for both, not once for each.

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/noise_id.hpp"

namespace stochnav {

/// Phase points per block of an AlongsideJob: the start indices of one task of the overlapping
/// sums (estimators.cpp), so block b can run right after the sums of task b, on the same
/// thread, while that stretch of the record is still in cache.
inline constexpr std::size_t kAlongsideBlockPoints = std::size_t{1} << 16;

/// Work on the phase record cut into blocks of kAlongsideBlockPoints points.
struct AlongsideJob {
  std::size_t blocks = 0;
  std::function<void(std::size_t block)> run;  ///< safe to call for distinct blocks at once
};

/// Throws deviation_values' std::invalid_argument when m leaves no terms on the record.
void require_deviation_terms(Deviation kind, std::size_t m, std::size_t phase_count);

/// deviation_values, with every block of `job` run once in the same parallel pass (for the
/// overlapping estimators each right after the sums over its stretch; for the others in a pass
/// of its own). The deviations are bitwise those of deviation_values.
std::vector<double> deviation_values_alongside(Deviation kind, std::span<const double> phase,
                                               double tau0_s, std::span<const std::size_t> m_values,
                                               const AlongsideJob& job);

/// identify_noises in two steps around a pass over the record: the constructor checks the
/// factors and plans; lag1_job() is the lag-1 pass (orders 0 and 1 of every factor the lag-1
/// method identifies); finish(), after every block of that job has run, does the rest (the
/// B1 identifications, the higher orders of the factors that need them) and returns what
/// identify_noises(kind, phase, m_values) returns. `phase` and `m_values` must outlive this.
class NoiseIdentification {
 public:
  NoiseIdentification(Deviation kind, std::span<const double> phase,
                      std::span<const std::size_t> m_values);
  ~NoiseIdentification();
  NoiseIdentification(const NoiseIdentification&) = delete;
  NoiseIdentification& operator=(const NoiseIdentification&) = delete;

  AlongsideJob lag1_job();
  std::vector<NoiseId> finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stochnav
