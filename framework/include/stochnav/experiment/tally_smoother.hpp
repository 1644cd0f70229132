#pragma once
// The measured depth of a survey station from the depth aid's readings over its connection.
//
// A pipe tally reads the BIT's measured depth; the survey sensor sits sensor_to_bit_m behind
// the bit, so each reading is first taken to the sensor: md_sensor = tally - sensor_to_bit_m
// (the caller does this; "survey/sensor_to_bit_m" of the run config, plugin/run_config.hpp).
//
// Smoother: the station's MD is the MEAN of the n sensor-depth readings of its stationary span
// (the connection's ZUPT epochs that carry a reading). The tool does not move along the hole
// while stationary, so the mean is the least-squares estimate of the one depth they all read.
//
// Its 1-sigma, relative to the tie-on (the origin of the listing's positions), from the depth
// aid's stated error model MD_read = (1 + s) MD + e (plugins/aiding/pipe_length: s ~ N(0,
// sigma_scale^2) once per run, e ~ N(0, sigma_random_m^2) per reading):
//   md_sigma_m = sqrt(sigma_random_m^2 / n + (sigma_scale (MD - MD_tie_on))^2)   (m)
// The 1/n assumes independent readings, as the aid model does; a tally that repeats one value
// at rest has one independent reading, and its sigma is then sqrt(n) times larger.

#include <cstddef>

namespace stochnav {

/// The depth aid's stated 1-sigmas (the pipe_length aid's params).
struct DepthReadingSigma {
  double random_m = 0.0;  ///< per reading (m), >= 0
  double scale = 0.0;     ///< relative scale error of the depth measurement, >= 0
};

/// The mean of one stationary span's sensor-depth readings (m).
class StationaryDepthMean final {
 public:
  /// Adds one reading (m, sensor depth). Non-finite readings are ignored.
  void add(double md_m);
  /// Forgets every reading: a new span starts.
  void reset();
  /// Readings since the last reset().
  std::size_t count() const { return count_; }
  /// Their mean (m); NaN without readings.
  double mean_m() const;
  /// 1-sigma of mean_m() relative to the tie-on at tie_on_md_m (see above); NaN without
  /// readings.
  double sigma_m(const DepthReadingSigma& sigma, double tie_on_md_m) const;

 private:
  std::size_t count_ = 0;
  double first_m_ = 0.0;           ///< the span's first reading: sums are taken about it
  double sum_of_offsets_m_ = 0.0;  ///< sum of (reading - first_m_)
};

}  // namespace stochnav
