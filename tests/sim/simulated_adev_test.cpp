// The overlapping Allan deviation of simulated records against the closed forms: for each random
// term the 68.3 % chi-square interval (Stable32 EDF) must cover the closed-form deviation about
// 68 % of the time over many seeds and taus; deterministic terms must match to rounding (ramp)
// or to the estimator's finite-record error (sinusoid).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <string>
#include <vector>

#include "stochnav/model/allan_variance.hpp"
#include "stochnav/sim/flicker_bank.hpp"
#include "stochnav/sim/noise_generator.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/edf.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav {
namespace {

constexpr double kRateHz = 100.0;
constexpr double kTau0 = 1.0 / kRateHz;
constexpr int kSeeds = 60;

std::vector<DeviationPoint> octave_oadev(const std::vector<double>& rate) {
  const std::vector<double> phase = phase_from_rate(rate, kTau0);
  const auto m = averaging_factors(Deviation::kOadev, TauSpacing::kOctave, phase.size(), kTau0);
  return compute_deviation(Deviation::kOadev, phase, kTau0, m);
}

NoiseModel single_term_model(NoiseTerm term) {
  return NoiseModel{Unit::kRadPerSecond, kRateHz, {std::move(term)}};
}

struct Coverage {
  int covered = 0;
  int total = 0;
  /// Per tau: (mean over seeds of the AVAR estimate - closed form) / its standard error. The
  /// overlapping estimator is unbiased, so these are about N(0, 1): a sharper check of
  /// exactness than the coverage.
  std::vector<double> mean_z;
  double rate() const { return total == 0 ? 0.0 : static_cast<double>(covered) / total; }
};

// Pools, over kSeeds records of `samples` samples, every tau whose EDF is valid.
// `expected_avar(tau)` is the closed form to cover.
template <typename Expected>
Coverage coverage_over_seeds(const NoiseModel& model, std::size_t samples,
                             Expected expected_avar) {
  Coverage coverage;
  const double duration = static_cast<double>(samples) / kRateHz;
  std::vector<double> sum, sum2, taus;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const auto rate = simulate_noise(model, duration, kRateHz, static_cast<std::uint64_t>(seed));
    const auto points = octave_oadev(rate);
    sum.resize(points.size(), 0.0);
    sum2.resize(points.size(), 0.0);
    taus.resize(points.size(), 0.0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double avar = points[i].deviation * points[i].deviation;
      sum[i] += avar;
      sum2[i] += avar * avar;
      taus[i] = points[i].tau_s;
    }
    for (const auto& point : points) {
      if (!(point.edf > 0.0) || !std::isfinite(point.lower) || !std::isfinite(point.upper)) {
        continue;
      }
      const double expected = std::sqrt(expected_avar(point.tau_s));
      ++coverage.total;
      if (point.lower <= expected && expected <= point.upper) ++coverage.covered;
    }
  }
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double mean = sum[i] / kSeeds;
    const double variance = (sum2[i] / kSeeds - mean * mean) * kSeeds / (kSeeds - 1);
    coverage.mean_z.push_back((mean - expected_avar(taus[i])) / std::sqrt(variance / kSeeds));
  }
  return coverage;
}

// Binomially sensible band for a nominal 68.3 % over several hundred pooled points (the points
// of one record are correlated, so the band is wider than the independent-sample one).
void expect_nominal_coverage(const Coverage& coverage, const std::string& what) {
  EXPECT_GT(coverage.total, 400) << what;
  EXPECT_GE(coverage.rate(), 0.55) << what << ": " << coverage.covered << "/" << coverage.total;
  EXPECT_LE(coverage.rate(), 0.82) << what << ": " << coverage.covered << "/" << coverage.total;
  double max_z = 0.0;
  for (double z : coverage.mean_z) {
    max_z = std::max(max_z, std::abs(z));
    EXPECT_LT(std::abs(z), 4.5) << what << ": mean AVAR over seeds off by " << z << " sigma";
  }
  std::printf("[ coverage ] %-18s %4d / %4d = %.3f, max |z| of mean AVAR %.2f over %zu taus\n",
              what.c_str(), coverage.covered, coverage.total, coverage.rate(), max_z,
              coverage.mean_z.size());
}

TEST(SimulatedAdev, WhiteRateNoiseCoversClosedForm) {
  const auto model = single_term_model(AngleRandomWalkTerm{1e-3});
  expect_nominal_coverage(coverage_over_seeds(model, 1 << 15,
                                              [&](double tau) { return allan_variance(model, tau); }),
                          "angle_random_walk");
}

TEST(SimulatedAdev, QuantizationCoversClosedForm) {
  const auto model = single_term_model(QuantizationTerm{1e-4});
  expect_nominal_coverage(coverage_over_seeds(model, 1 << 15,
                                              [&](double tau) { return allan_variance(model, tau); }),
                          "quantization");
}

TEST(SimulatedAdev, RateRandomWalkCoversClosedForm) {
  const auto model = single_term_model(RateRandomWalkTerm{1e-3});
  expect_nominal_coverage(coverage_over_seeds(model, 1 << 15,
                                              [&](double tau) { return allan_variance(model, tau); }),
                          "rate_random_walk");
}

TEST(SimulatedAdev, GaussMarkovCoversClosedForm) {
  // tau_c inside the tau range, so the curve rises, peaks and falls within the record.
  const auto model = single_term_model(GaussMarkovTerm{1e-3, 2.0});
  expect_nominal_coverage(coverage_over_seeds(model, 1 << 15,
                                              [&](double tau) { return allan_variance(model, tau); }),
                          "gauss_markov");
}

TEST(SimulatedAdev, GaussMarkovShorterThanSampleCoversClosedForm) {
  // tau_c below the sampling interval: the interval means are nearly white.
  const auto model = single_term_model(GaussMarkovTerm{1e-3, 0.3 * kTau0});
  expect_nominal_coverage(coverage_over_seeds(model, 1 << 14,
                                              [&](double tau) { return allan_variance(model, tau); }),
                          "gauss_markov_fast");
}

TEST(SimulatedAdev, BiasInstabilityCoversFlatFloor) {
  const auto model = single_term_model(BiasInstabilityTerm{1e-3});
  expect_nominal_coverage(coverage_over_seeds(model, 1 << 15,
                                              [&](double tau) { return allan_variance(model, tau); }),
                          "bias_instability");
}

TEST(SimulatedAdev, CombinedModelCoversSumOfClosedForms) {
  const NoiseModel model{Unit::kRadPerSecond,
                         kRateHz,
                         {QuantizationTerm{2e-5}, AngleRandomWalkTerm{1e-3},
                          BiasInstabilityTerm{2e-4}, RateRandomWalkTerm{1e-4},
                          GaussMarkovTerm{5e-4, 5.0}}};
  expect_nominal_coverage(coverage_over_seeds(model, 1 << 15,
                                              [&](double tau) { return allan_variance(model, tau); }),
                          "combined");
}

// Issue #26: at long tau the noise identification rests on few decimated points, and on a rate
// record (frequency-type noise, alpha <= 0) it slipped to white or flicker PM (alpha 2 or 1),
// whose EDF grows with the number of overlapping terms, not with N / m: 3 of 20 seeds had edf
// 29,303 at N / m = 29, a 95 % interval 25x too narrow. Over 48 records of white rate noise,
// alone and with a rate random walk that takes over at tau ~ 20 s, 600 s at 100 Hz (N / m from
// 60,000 down to 3.7), every octave tau:
//  - the 95 % interval covers the closed-form deviation on 93 % to 99 % of the (seed, tau) cells
//    (nominal 95 %; the EDF may only err on the conservative side);
//  - no cell's EDF exceeds the white-FM EDF at its m (about 1.5 N / m: the largest any frequency
//    noise gives the overlapping Allan variance) by more than 1 %.
TEST(SimulatedAdev, IdentificationSlipsKeepTheEdfSaneAndTheCoverageNominal) {
  constexpr std::size_t kSamples = 60000;
  constexpr int kSlipSeeds = 24;
  const NoiseModel white = single_term_model(AngleRandomWalkTerm{1e-3});
  const NoiseModel white_and_walk{
      Unit::kRadPerSecond, kRateHz, {AngleRandomWalkTerm{1e-3}, RateRandomWalkTerm{8.7e-5}}};
  int covered = 0;
  int cells = 0;
  int above_bound = 0;
  double worst_ratio = 0.0;  // largest edf / white-FM edf
  for (const NoiseModel* model : {&white, &white_and_walk}) {
    for (int seed = 1; seed <= kSlipSeeds; ++seed) {
      const auto rate = simulate_noise(*model, static_cast<double>(kSamples) / kRateHz, kRateHz,
                                       static_cast<std::uint64_t>(seed));
      const std::vector<double> phase = phase_from_rate(rate, kTau0);
      const auto m_values =
          averaging_factors(Deviation::kOadev, TauSpacing::kOctave, phase.size(), kTau0);
      const auto points = compute_deviation(Deviation::kOadev, phase, kTau0, m_values, 0.95);
      for (const auto& point : points) {
        ASSERT_TRUE(std::isfinite(point.lower) && std::isfinite(point.upper)) << point.m;
        const double white_fm_edf = greenhall_edf({.alpha = 0,
                                                   .d = 2,
                                                   .m = point.m,
                                                   .phase_count = phase.size(),
                                                   .overlapping = true,
                                                   .modified = false});
        const double ratio = point.edf / white_fm_edf;
        worst_ratio = std::max(worst_ratio, ratio);
        if (ratio > 1.01) {
          ++above_bound;
          ADD_FAILURE() << "seed " << seed << " m " << point.m << " (N/m "
                        << static_cast<double>(kSamples) / static_cast<double>(point.m)
                        << "): alpha " << point.alpha << ", edf " << point.edf
                        << " above the white-FM edf " << white_fm_edf;
        }
        const double truth = std::sqrt(allan_variance(*model, point.tau_s));
        ++cells;
        if (point.lower <= truth && truth <= point.upper) ++covered;
      }
    }
  }
  const double coverage = static_cast<double>(covered) / cells;
  std::printf("[ coverage ] 95 %% intervals after identification: %d / %d = %.3f; %d cells above "
              "the white-FM edf, worst edf / white-FM edf %.3g\n",
              covered, cells, coverage, above_bound, worst_ratio);
  EXPECT_GE(coverage, 0.93);
  EXPECT_LE(coverage, 0.99);
}

TEST(SimulatedAdev, RampMatchesClosedFormExactly) {
  const auto model = single_term_model(RateRampTerm{3e-4});
  const auto rate = simulate_noise(model, 100.0, kRateHz, 7);
  for (const auto& point : octave_oadev(rate)) {
    EXPECT_NEAR(point.deviation, std::sqrt(allan_variance(model, point.tau_s)),
                1e-9 * point.deviation)
        << "tau " << point.tau_s;
  }
}

TEST(SimulatedAdev, SinusoidMatchesClosedFormOverManyPeriods) {
  // 200 s at 100 Hz holds 2000 periods of 10 Hz and 60 of 0.3 Hz; the overlapping estimator's
  // departure from the time-averaged closed form shrinks as (periods in the record)^-1.
  for (double frequency : {10.0, 0.3}) {
    const auto model = single_term_model(SinusoidTerm{1e-3, frequency, std::nullopt});
    for (std::uint64_t seed : {1, 2, 3}) {
      const auto rate = simulate_noise(model, 200.0, kRateHz, seed);
      for (const auto& point : octave_oadev(rate)) {
        const double expected = std::sqrt(allan_variance(model, point.tau_s));
        if (point.tau_s * frequency > 3.0) continue;  // few independent periods per window
        // Away from the nulls (tau = k / f) compare relatively, near them absolutely.
        EXPECT_NEAR(point.deviation, expected, 0.03 * expected + 0.01 * 1e-3)
            << "f " << frequency << " tau " << point.tau_s << " seed " << seed;
      }
    }
  }
}

TEST(SimulatedAdev, FlickerBankIsFlatOverItsBand) {
  for (double band_max : {0.5, 100.0, 7.2e5}) {
    const FlickerBank bank = design_flicker_bank(1.0, kTau0, band_max);
    EXPECT_LT(bank.max_relative_ripple, 1e-3) << band_max;
    EXPECT_LT(bank.tau_c_s.size(), 2 * std::log10(300.0 * band_max / kTau0) + 3);
    const double floor = allan_variance(BiasInstabilityTerm{1.0}, 1.0);
    EXPECT_NEAR(std::sqrt(floor), 0.6643, 1e-4);
    EXPECT_NEAR(flicker_bank_allan_variance(bank, kTau0), floor, 1e-3 * floor);
    EXPECT_NEAR(flicker_bank_allan_variance(bank, band_max), floor, 1e-3 * floor);
  }
}

}  // namespace
}  // namespace stochnav
