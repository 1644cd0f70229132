// The stats thread pool and the determinism contract: every parallel result of the Allan engine
// is bitwise the same with 1, 2 or 8 threads.

#include "stochnav/stats/parallel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "stochnav/stats/davar.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/noise_id.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav {
namespace {

/// Restores the default thread count when a test ends.
class ThreadCountGuard {
 public:
  ~ThreadCountGuard() { set_stats_thread_count(0); }
};

/// A gyro-like rate: bias, white noise, a slow random walk.
std::vector<double> gyro_rate(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> rate(n);
  double walk = 0.0;
  for (double& y : rate) {
    walk += 1e-3 * normal(engine);
    y = 40.0 + walk + 0.5 * normal(engine);
  }
  return rate;
}

/// Runs `compute` with 1, 2 and 8 threads and expects bitwise equal results.
template <typename Compute>
void expect_thread_count_independent(const Compute& compute) {
  ThreadCountGuard guard;
  set_stats_thread_count(1);
  const auto reference = compute();
  for (std::size_t threads : {2u, 8u}) {
    set_stats_thread_count(threads);
    const auto result = compute();
    EXPECT_TRUE(result == reference) << threads << " threads differ from 1";
  }
}

TEST(ParallelFor, RunsEveryTaskOnce) {
  ThreadCountGuard guard;
  for (std::size_t threads : {1u, 2u, 8u}) {
    set_stats_thread_count(threads);
    std::vector<std::atomic<int>> runs(1000);
    parallel_for(runs.size(), [&](std::size_t i) { ++runs[i]; });
    for (const auto& count : runs) EXPECT_EQ(count.load(), 1);
    parallel_for(0, [](std::size_t) { FAIL() << "no task expected"; });
  }
}

TEST(ParallelFor, RethrowsTheLowestFailingTaskAfterAllRan) {
  ThreadCountGuard guard;
  for (std::size_t threads : {1u, 2u, 8u}) {
    set_stats_thread_count(threads);
    std::atomic<int> ran{0};
    try {
      parallel_for(64, [&](std::size_t i) {
        ++ran;
        if (i == 7 || i == 40) throw std::runtime_error("task " + std::to_string(i));
      });
      FAIL() << "no exception";
    } catch (const std::runtime_error& error) {
      EXPECT_STREQ(error.what(), "task 7");
    }
    EXPECT_EQ(ran.load(), 64);
  }
}

TEST(ParallelFor, NestedCallsRunInline) {
  ThreadCountGuard guard;
  set_stats_thread_count(4);
  std::vector<std::atomic<int>> runs(8 * 8);
  parallel_for(8,
               [&](std::size_t i) { parallel_for(8, [&](std::size_t j) { ++runs[i * 8 + j]; }); });
  for (const auto& count : runs) EXPECT_EQ(count.load(), 1);
}

TEST(ThreadCountIndependence, PhaseFromRateInPlace) {
  const std::vector<double> rate = gyro_rate(300'001, 1);
  expect_thread_count_independent([&] {
    std::vector<double> buffer(rate.size() + 1);
    std::copy(rate.begin(), rate.end(), buffer.begin() + 1);
    phase_from_rate_in_place(buffer, 0.01);
    return buffer;
  });
}

TEST(ThreadCountIndependence, DeviationsOfEveryKindAndTauSet) {
  const std::vector<double> phase = phase_from_rate(gyro_rate(400'000, 2), 0.01);
  for (Deviation kind : {Deviation::kOadev, Deviation::kAdev, Deviation::kMdev, Deviation::kTdev,
                         Deviation::kHdev, Deviation::kOhdev}) {
    for (TauSpacing spacing :
         {TauSpacing::kOctave, TauSpacing::kDecade, TauSpacing::kDense, TauSpacing::kAll}) {
      if (is_modified(kind) && spacing == TauSpacing::kAll) continue;  // slow, nothing new
      const auto m = averaging_factors(kind, spacing, phase.size(), 0.01);
      SCOPED_TRACE(std::string(deviation_name(kind)) + " spacing " +
                   std::to_string(static_cast<int>(spacing)));
      expect_thread_count_independent([&] { return deviation_values(kind, phase, 0.01, m); });
    }
  }
}

TEST(ThreadCountIndependence, ComputeDeviationAndNoiseIds) {
  const std::vector<double> phase = phase_from_rate(gyro_rate(500'000, 3), 0.01);
  const auto m = averaging_factors(Deviation::kOadev, TauSpacing::kDense, phase.size(), 0.01);
  expect_thread_count_independent([&] {
    std::vector<double> flat;
    for (const auto& p : compute_deviation(Deviation::kOadev, phase, 0.01, m)) {
      flat.insert(flat.end(), {p.deviation, p.edf, p.lower, p.upper, static_cast<double>(p.alpha),
                               static_cast<double>(p.terms)});
    }
    return flat;
  });
  expect_thread_count_independent([&] {
    std::vector<double> statistics;
    for (const auto& id : identify_noises(Deviation::kOhdev, phase, m)) {
      statistics.push_back(id.statistic);
    }
    return statistics;
  });
}

TEST(ThreadCountIndependence, Davar) {
  Record record;
  record.values = gyro_rate(600'000, 4);
  record.rate_hz = 100.0;
  record.source = "generated";
  expect_thread_count_independent([&] {
    const DavarResult davar = dynamic_allan_deviation(record, {.window = 50'000, .step = 5'000});
    return davar.adev;
  });
}

TEST(IdentifyNoises, AgreesWithIdentifyNoiseAtEveryFactor) {
  const std::vector<double> phase = phase_from_rate(gyro_rate(200'000, 5), 0.01);
  for (Deviation kind : {Deviation::kOadev, Deviation::kOhdev, Deviation::kAdev}) {
    const auto m = averaging_factors(kind, TauSpacing::kAll, phase.size(), 0.01);
    const std::vector<NoiseId> together = identify_noises(kind, phase, m);
    ASSERT_EQ(together.size(), m.size());
    for (std::size_t j = 0; j < m.size(); ++j) {
      const NoiseId alone = identify_noise(kind, phase, m[j]);
      EXPECT_EQ(together[j].alpha, alone.alpha) << "m = " << m[j];
      EXPECT_EQ(together[j].method, alone.method) << "m = " << m[j];
      EXPECT_NEAR(together[j].statistic, alone.statistic, 1e-9 * (1.0 + std::abs(alone.statistic)))
          << "m = " << m[j];
    }
  }
  EXPECT_THROW(identify_noises(Deviation::kOadev, phase, std::vector<std::size_t>{0}),
               std::invalid_argument);
}

TEST(PhaseFromRateInPlace, AgreesWithTheSerialIntegration) {
  // Exact on a small case, a few ulps of the largest |x| on a long one with a large bias.
  std::vector<double> small = {0.0, 1.0, 3.0, 2.0, 6.0};
  phase_from_rate_in_place(small, 0.5);
  EXPECT_EQ(small, (std::vector<double>{0.0, -1.0, -1.0, -1.5, 0.0}));
  std::vector<double> rate = gyro_rate(1'000'003, 6);
  for (double& y : rate) y += 1e4;
  const std::vector<double> serial = phase_from_rate(rate, 0.01);
  std::vector<double> buffer(rate.size() + 1);
  std::copy(rate.begin(), rate.end(), buffer.begin() + 1);
  phase_from_rate_in_place(buffer, 0.01);
  double largest = 0.0;
  double worst = 0.0;
  for (std::size_t i = 0; i < serial.size(); ++i) {
    largest = std::max(largest, std::abs(serial[i]));
    worst = std::max(worst, std::abs(serial[i] - buffer[i]));
  }
  EXPECT_LT(worst, 16 * std::numeric_limits<double>::epsilon() * largest);
  std::vector<double> with_nan = {0.0, 1.0, std::nan(""), 2.0};
  phase_from_rate_in_place(with_nan, 1.0);
  EXPECT_EQ(with_nan[0], 0.0);
  EXPECT_TRUE(std::isnan(with_nan[1]) && std::isnan(with_nan[3]));
}

}  // namespace
}  // namespace stochnav
