#pragma once
// Upper bounds on the work one request may ask for. Every command's work is bounded by its
// inputs (records are read once; analyses are linear or n log n in their length); these limits
// bound what is not an input but a number typed in: simulated lengths, seeds, iterations.
// A request beyond a limit is refused up front with a ConfigError (CLI exit code 2) naming the
// option, the limit and what to change. docs/reliability.md ("Limits on work") lists them.

#include <cstdint>

namespace stochnav::limits {

/// Samples per axis of one `simulate noise` record (duration x rate): 1e9, 200 h at 1.4 kHz,
/// about 20 GB of CSV per axis.
inline constexpr double kMaxSimulatedSamples = 1e9;
/// Highest simulated sampling rate (Hz), above any inertial sensor's output rate.
inline constexpr double kMaxSimulatedRateHz = 1e6;
/// IMU epochs of one simulated scenario (duration_s x imu.rate_hz): 1e9, 115 days at 100 Hz.
inline constexpr double kMaxScenarioEpochs = 1e9;
/// Monte-Carlo seeds of one comparison (each a simulated scenario on disk).
inline constexpr std::uint64_t kMaxCompareSeeds = 1000;
/// Filter runs of one comparison (variants x seeds).
inline constexpr std::uint64_t kMaxCompareRuns = 20000;
/// Simulated records per model assessment in diagnose (--seeds).
inline constexpr int kMaxDiagnoseSeeds = 1000;
/// Terms diagnose may add (--max-iterations): more than the vocabulary has types.
inline constexpr int kMaxDiagnoseIterations = 32;
/// Windows of diagnose's stationarity test (--windows).
inline constexpr std::uint64_t kMaxStationarityWindows = 100000;

}  // namespace stochnav::limits
