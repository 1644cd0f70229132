#include "stochnav/stats/deviation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "power_law_noise.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav {
namespace {

constexpr Deviation kAllKinds[] = {Deviation::kAdev,  Deviation::kOadev, Deviation::kMdev,
                                   Deviation::kTdev,  Deviation::kHdev,  Deviation::kOhdev,
                                   Deviation::kTotdev};

TEST(DeviationNames, RoundTripAndRejectUnknown) {
  for (Deviation kind : kAllKinds) {
    EXPECT_EQ(deviation_from_name(deviation_name(kind)), kind);
    EXPECT_EQ(parse_deviation(deviation_name(kind)), kind);
  }
  EXPECT_EQ(deviation_name(Deviation::kOhdev), "ohdev");
  EXPECT_FALSE(deviation_from_name("OADEV").has_value());
  EXPECT_EQ(deviation_name(Deviation::kTotdev), "totdev");
  EXPECT_THROW(parse_deviation("totvar"), ConfigError);
}

TEST(TermCount, Stable32Counts) {
  const std::size_t n = 1001;  // PHASE.DAT
  EXPECT_EQ(term_count(Deviation::kOadev, 8, n), 985u);
  EXPECT_EQ(term_count(Deviation::kAdev, 8, n), 124u);
  EXPECT_EQ(term_count(Deviation::kMdev, 8, n), 978u);
  EXPECT_EQ(term_count(Deviation::kTdev, 8, n), 978u);
  EXPECT_EQ(term_count(Deviation::kHdev, 8, n), 123u);
  EXPECT_EQ(term_count(Deviation::kOhdev, 8, n), 977u);
  EXPECT_EQ(term_count(Deviation::kOadev, 0, n), 0u);
  EXPECT_EQ(term_count(Deviation::kOadev, 500, n), 1u);
  EXPECT_EQ(term_count(Deviation::kOadev, 501, n), 0u);
  EXPECT_EQ(term_count(Deviation::kHdev, 400, n), 0u);
  // TOTDEV: N - 2 at every m the reflected record covers.
  EXPECT_EQ(term_count(Deviation::kTotdev, 1, n), 999u);
  EXPECT_EQ(term_count(Deviation::kTotdev, 499, n), 999u);
  EXPECT_EQ(term_count(Deviation::kTotdev, 999, n), 999u);
  EXPECT_EQ(term_count(Deviation::kTotdev, 1000, n), 0u);
  EXPECT_EQ(term_count(Deviation::kTotdev, 1, 2), 0u);
}

TEST(AveragingFactors, OctaveAndDecadeStopAtStable32sLimit) {
  // PHASE.DAT: ADEV stops at m = 197 (5m < N - 1), OADEV at 247 (4m < N - 1).
  EXPECT_EQ(max_averaging_factor(Deviation::kAdev, 1001), 199u);
  EXPECT_EQ(max_averaging_factor(Deviation::kOadev, 1001), 249u);
  // TOTDEV stops at 499 (2m < N - 1).
  EXPECT_EQ(max_averaging_factor(Deviation::kTotdev, 1001), 499u);
  EXPECT_EQ(averaging_factors(Deviation::kTotdev, TauSpacing::kOctave, 1001).back(), 256u);
  EXPECT_EQ(averaging_factors(Deviation::kOadev, TauSpacing::kOctave, 1001),
            (std::vector<std::size_t>{1, 2, 4, 8, 16, 32, 64, 128}));
  EXPECT_EQ(averaging_factors(Deviation::kAdev, TauSpacing::kDecade, 241218),
            (std::vector<std::size_t>{1, 2, 4, 10, 20, 40, 100, 200, 400, 1000, 2000, 4000, 10000,
                                      20000, 40000}));
  EXPECT_TRUE(averaging_factors(Deviation::kOadev, TauSpacing::kOctave, 5).empty());
  EXPECT_EQ(averaging_factors(Deviation::kOadev, TauSpacing::kOctave, 6),
            (std::vector<std::size_t>{1}));
}

TEST(AveragingFactors, DenseIsAboutTenPerDecade) {
  const auto m = averaging_factors(Deviation::kOadev, TauSpacing::kDense, 4'000'002);
  ASSERT_FALSE(m.empty());
  EXPECT_EQ(m.front(), 1u);
  EXPECT_LE(m.back(), 1'000'000u);
  for (std::size_t i = 1; i < m.size(); ++i) EXPECT_LT(m[i - 1], m[i]);
  const auto per_decade = [&](std::size_t from, std::size_t to) {
    return std::count_if(m.begin(), m.end(), [&](std::size_t k) { return k >= from && k < to; });
  };
  EXPECT_EQ(per_decade(1000, 10000), 10);
  EXPECT_EQ(per_decade(100000, 1000000), 10);
  EXPECT_GE(per_decade(1, 10), 7);  // 1, 2, 3, 4, 5, 6, 8: small integers merge
}

TEST(AveragingFactors, AllTauSpacingGrowsWithTheDecadesSpanned) {
  // 3 decades of tau: steps of m / 71 + 1 (PHASE.DAT); 6 decades: m / 35 + 1 (Cs 5071A).
  const auto short_record = averaging_factors(Deviation::kAdev, TauSpacing::kAll, 1001);
  EXPECT_EQ(short_record.size(), 125u);
  EXPECT_EQ(short_record.back(), 197u);
  const auto long_record = averaging_factors(Deviation::kOadev, TauSpacing::kAll, 556990);
  EXPECT_EQ(long_record.size(), 314u);
  EXPECT_EQ(long_record.back(), 138921u);
  // tau0 shifts the decades: 10 000 points at tau0 = 42 s span 1e1 .. 1e5 s for ADEV.
  const auto slow = averaging_factors(Deviation::kAdev, TauSpacing::kAll, 10001, 42.0);
  EXPECT_EQ(slow.size(), 225u);
}

TEST(Deviations, ConstantRateGivesZero) {
  const std::vector<double> rate(1000, 3.7);
  const std::vector<double> phase = phase_from_rate(rate, 0.01);
  for (Deviation kind : kAllKinds) {  // 0 up to the rounding of the mean (1 ulp of 3.7)
    EXPECT_LT(deviation_value(kind, phase, 0.01, 1), 1e-15) << deviation_name(kind);
    EXPECT_LT(deviation_value(kind, phase, 0.01, 64), 1e-15) << deviation_name(kind);
  }
  // A phase ramp (constant rate given as phase) cancels in every difference up to rounding.
  std::vector<double> ramp(1000);
  for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = 3.7 * 0.01 * static_cast<double>(i);
  for (Deviation kind : kAllKinds) {
    EXPECT_LT(deviation_value(kind, ramp, 0.01, 16), 1e-12) << deviation_name(kind);
  }
}

TEST(Deviations, InvariantToAConstantRate) {
  const std::vector<double> noise = stats_test::white_noise(5000, 11);
  std::vector<double> shifted = noise;
  for (double& y : shifted) y += 250.0;
  const auto phase = phase_from_rate(noise, 0.01);
  const auto shifted_phase = phase_from_rate(shifted, 0.01);
  // And as phase: a ramp added to the phase.
  std::vector<double> ramped = phase;
  for (std::size_t i = 0; i < ramped.size(); ++i) ramped[i] += 0.37 * static_cast<double>(i);
  for (Deviation kind : kAllKinds) {
    for (std::size_t m : {1u, 7u, 100u, 900u}) {
      const double reference = deviation_value(kind, phase, 0.01, m);
      EXPECT_NEAR(deviation_value(kind, shifted_phase, 0.01, m) / reference, 1.0, 1e-9)
          << deviation_name(kind) << " m " << m;
      EXPECT_NEAR(deviation_value(kind, ramped, 0.01, m) / reference, 1.0, 1e-9)
          << deviation_name(kind) << " m " << m;
    }
  }
}

TEST(Deviations, EstimatorIdentities) {
  const std::vector<double> phase = stats_test::power_law_phase(0, 3000, 5);
  const double tau0 = 0.5;
  // At m = 1 the overlapping and modified estimators are the plain ones.
  const double adev1 = deviation_value(Deviation::kAdev, phase, tau0, 1);
  EXPECT_NEAR(deviation_value(Deviation::kOadev, phase, tau0, 1), adev1, 1e-14 * adev1);
  EXPECT_NEAR(deviation_value(Deviation::kMdev, phase, tau0, 1), adev1, 1e-14 * adev1);
  const double hdev1 = deviation_value(Deviation::kHdev, phase, tau0, 1);
  EXPECT_NEAR(deviation_value(Deviation::kOhdev, phase, tau0, 1), hdev1, 1e-14 * hdev1);
  // TDEV = tau MDEV / sqrt(3).
  for (std::size_t m : {1u, 5u, 50u}) {
    const double tau = static_cast<double>(m) * tau0;
    EXPECT_NEAR(deviation_value(Deviation::kTdev, phase, tau0, m),
                tau * deviation_value(Deviation::kMdev, phase, tau0, m) / std::sqrt(3.0),
                1e-12 * tau);
  }
}

// The fast paths against the definitions, on a record long enough for factors >= 65536, which
// the overlapping sums walk row by row (multiples of the smallest) or along the record.
TEST(Deviations, FastSumsEqualAPlainLoop) {
  const std::vector<double> phase = stats_test::power_law_phase(0, 400'000, 9);
  const std::vector<std::size_t> m_values = {1, 3, 7, 64, 333, 65536, 70001, 131072};
  const auto plain = [&](int d, std::size_t m) {
    double sum = 0.0;
    const std::size_t terms = phase.size() - static_cast<std::size_t>(d) * m;
    for (std::size_t i = 0; i < terms; ++i) {
      const double diff =
          d == 2 ? phase[i + 2 * m] - 2 * phase[i + m] + phase[i]
                 : phase[i + 3 * m] - 3 * phase[i + 2 * m] + 3 * phase[i + m] - phase[i];
      sum += diff * diff;
    }
    const double tau = static_cast<double>(m);
    return std::sqrt(sum / ((d == 2 ? 2.0 : 6.0) * tau * tau * static_cast<double>(terms)));
  };
  const auto plain_modified = [&](std::size_t m) {
    double sum = 0.0;
    const std::size_t terms = phase.size() + 1 - 3 * m;
    for (std::size_t j = 0; j < terms; ++j) {
      double inner = 0.0;
      for (std::size_t i = j; i < j + m; ++i) {
        inner += phase[i + 2 * m] - 2 * phase[i + m] + phase[i];
      }
      sum += inner * inner;
    }
    const double md = static_cast<double>(m);
    return std::sqrt(sum / (2.0 * md * md * md * md * static_cast<double>(terms)));
  };
  const auto oadev = deviation_values(Deviation::kOadev, phase, 1.0, m_values);
  const auto ohdev = deviation_values(Deviation::kOhdev, phase, 1.0, m_values);
  for (std::size_t k = 0; k < m_values.size(); ++k) {
    const std::size_t m = m_values[k];
    EXPECT_NEAR(oadev[k] / plain(2, m), 1.0, 1e-12) << "m " << m;
    EXPECT_NEAR(ohdev[k] / plain(3, m), 1.0, 1e-12) << "m " << m;
    if (m < 1000) {  // the plain modified sum is O(N m)
      EXPECT_NEAR(deviation_value(Deviation::kMdev, phase, 1.0, m) / plain_modified(m), 1.0, 1e-10);
    }
  }
}

// TOTDEV against its definition: the record extended by odd reflection to 3N - 4 points.
TEST(Deviations, TotdevEqualsTheReflectedRecordsDefinition) {
  const std::vector<double> phase = stats_test::power_law_phase(-1, 3001, 17);
  const std::size_t n = phase.size();
  std::vector<double> extended;  // x*[-(N-2)] .. x*[2N-3], x*[j] at extended[j + N - 2]
  for (std::size_t j = n - 2; j >= 1; --j) extended.push_back(2 * phase[0] - phase[j]);
  extended.insert(extended.end(), phase.begin(), phase.end());
  for (std::size_t j = 1; j <= n - 2; ++j) extended.push_back(2 * phase[n - 1] - phase[n - 1 - j]);
  ASSERT_EQ(extended.size(), 3 * n - 4);
  const double tau0 = 0.25;
  for (std::size_t m : {1u, 2u, 7u, 100u, 1499u, 1500u, 1501u, 2999u}) {
    double sum = 0.0;
    for (std::size_t i = 1; i <= n - 2; ++i) {
      const std::size_t c = i + n - 2;
      const double diff = extended[c - m] - 2 * extended[c] + extended[c + m];
      sum += diff * diff;
    }
    const double tau = tau0 * static_cast<double>(m);
    const double expected = std::sqrt(sum / (2 * tau * tau * static_cast<double>(n - 2)));
    EXPECT_NEAR(deviation_value(Deviation::kTotdev, phase, tau0, m) / expected, 1.0, 1e-12)
        << "m " << m;
  }
  // At m = 1 no point is reflected: TOTDEV is OADEV (both N - 2 terms).
  EXPECT_NEAR(deviation_value(Deviation::kTotdev, phase, tau0, 1) /
                  deviation_value(Deviation::kOadev, phase, tau0, 1),
              1.0, 1e-14);
}

TEST(Deviations, RejectFactorsWithoutTerms) {
  const std::vector<double> phase(100, 1.0);
  EXPECT_THROW(deviation_value(Deviation::kOadev, phase, 1.0, 0), std::invalid_argument);
  EXPECT_THROW(deviation_value(Deviation::kOadev, phase, 1.0, 50), std::invalid_argument);
  EXPECT_THROW(deviation_value(Deviation::kHdev, phase, 1.0, 40), std::invalid_argument);
  EXPECT_THROW(deviation_value(Deviation::kTotdev, phase, 1.0, 99), std::invalid_argument);
  const std::size_t m_values[] = {1, 60};
  EXPECT_THROW(compute_deviation(Deviation::kMdev, phase, 1.0, m_values), std::invalid_argument);
}

TEST(ComputeDeviation, WhiteFmPointsAreConsistent) {
  const std::vector<double> phase = phase_from_rate(stats_test::white_noise(20000, 21), 0.01);
  const auto m_values = averaging_factors(Deviation::kOadev, TauSpacing::kOctave, phase.size());
  const auto points = compute_deviation(Deviation::kOadev, phase, 0.01, m_values);
  ASSERT_EQ(points.size(), m_values.size());
  for (const auto& p : points) {
    EXPECT_DOUBLE_EQ(p.tau_s, 0.01 * static_cast<double>(p.m));
    EXPECT_EQ(p.terms, phase.size() - 2 * p.m);
    EXPECT_LT(p.lower, p.deviation);
    EXPECT_GT(p.upper, p.deviation);
    EXPECT_GT(p.edf, 0.0);
    // White FM: sigma(tau) = sigma_y sqrt(tau0 / tau), inside a generous 4-sigma band.
    const double expected = std::sqrt(0.01 / p.tau_s);
    EXPECT_NEAR(p.deviation / expected, 1.0, 4.0 * (p.upper / p.deviation - 1.0) + 1e-3)
        << "m " << p.m;
  }
  // Where the lag-1 method has at least 150 decimated points: white FM, and fewer degrees of
  // freedom at each longer tau.
  for (std::size_t k = 0; k < points.size() && points[k].m <= 128; ++k) {
    EXPECT_EQ(points[k].alpha, 0) << "m " << points[k].m;
    if (k > 0) {
      EXPECT_LT(points[k].edf, points[k - 1].edf);
    }
  }
}

}  // namespace
}  // namespace stochnav
