#include "stochnav/stats/edf.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace stochnav {
namespace {

EdfQuery oadev(int alpha, std::size_t m, std::size_t n) {
  return {.alpha = alpha, .d = 2, .m = m, .phase_count = n, .overlapping = true};
}

TEST(GreenhallEdf, WhitePmUnmodifiedClosedForm) {
  // Case 4 with r = M / S > d: 1/edf = (1/M) (a0 - a1 / r), a0 = C(4d,2d) / C(2d,d)^2, a1 = d/2.
  const std::size_t n = 10001;
  const std::size_t m = 16;
  const double terms = static_cast<double>(n - 2 * m);  // M
  const double r = terms / static_cast<double>(m);
  const double a0 = 70.0 / 36.0;
  EXPECT_NEAR(greenhall_edf(oadev(2, m, n)), 1.0 / ((a0 - 1.0 / r) / terms), 1e-9);
  // Non-overlapping ADEV (S = 1): r = M.
  const double adev_terms = static_cast<double>((n - 1) / m - 1);
  EXPECT_NEAR(greenhall_edf({.alpha = 2, .d = 2, .m = m, .phase_count = n}),
              1.0 / ((a0 - 1.0 / adev_terms) / adev_terms), 1e-9);
}

// edf * m / M, which tends to a constant (1 / a0 of the tables) for long records.
double normalised_edf(EdfQuery query) {
  const double terms = static_cast<double>(query.phase_count) -
                       static_cast<double>(query.d) * static_cast<double>(query.m);
  return greenhall_edf(query) * static_cast<double>(query.m) / terms;
}

TEST(GreenhallEdf, ExactSumMeetsTheAsymptoticTable) {
  // Overlapping estimators: J = (d + 1) m terms are summed exactly while J <= 100, the tables
  // take over after. They meet smoothly, except for the unmodified variances with alpha <= 0,
  // where the exact sum still uses the finite filter factor F = m and the table its m -> inf
  // limit: a step of about 3 % for white FM, in the paper's algorithm as in Stable32's output.
  const std::size_t n = 100000;
  const auto step = [](EdfQuery below, std::size_t m_above) {
    EdfQuery above = below;
    above.m = m_above;
    return normalised_edf(above) / normalised_edf(below) - 1.0;
  };
  EXPECT_NEAR(step(oadev(0, 33, n), 34), 0.03, 0.005);
  EXPECT_NEAR(step(oadev(-1, 33, n), 34), 0.0, 0.005);
  EXPECT_NEAR(
      step({.alpha = -1, .d = 2, .m = 33, .phase_count = n, .overlapping = true, .modified = true},
           34),
      0.0, 0.005);
  EXPECT_NEAR(
      step({.alpha = 1, .d = 2, .m = 33, .phase_count = n, .overlapping = true, .modified = true},
           34),
      0.0, 0.005);
  EXPECT_NEAR(step({.alpha = -2, .d = 3, .m = 25, .phase_count = n, .overlapping = true}, 26), 0.0,
              0.005);
  // Far from the switch the tables' constants hold: white FM OADEV 1 / a0 = 3/2.
  EXPECT_NEAR(normalised_edf(oadev(0, 1000, 10'000'000)), 1.5, 0.002);
}

TEST(GreenhallEdf, MoreDataMoreFreedomLongerTauLess) {
  for (int alpha : {2, 1, 0, -1, -2}) {
    EXPECT_GT(greenhall_edf(oadev(alpha, 8, 20000)), greenhall_edf(oadev(alpha, 8, 2000)));
    EXPECT_GT(greenhall_edf(oadev(alpha, 8, 20000)), greenhall_edf(oadev(alpha, 64, 20000)));
    // Overlapping estimates carry at least as much information as non-overlapping ones.
    EdfQuery adev = oadev(alpha, 8, 20000);
    adev.overlapping = false;
    EXPECT_GE(greenhall_edf(oadev(alpha, 8, 20000)), greenhall_edf(adev) * 0.999);
  }
}

TEST(GreenhallEdf, OneTermIsAboutOneDegreeOfFreedom) {
  // A single squared difference of Gaussian noise is chi-square with one degree of freedom.
  EXPECT_NEAR(greenhall_edf({.alpha = 0, .d = 2, .m = 1, .phase_count = 3}), 1.0, 1e-9);
  EXPECT_NEAR(greenhall_edf({.alpha = 2, .d = 3, .m = 10, .phase_count = 31}), 1.0, 1e-9);
}

TEST(GreenhallEdf, OutsideTheDomainIsNaN) {
  EXPECT_TRUE(std::isnan(greenhall_edf(oadev(3, 1, 100))));
  EXPECT_TRUE(std::isnan(greenhall_edf(oadev(-3, 1, 100))));  // alpha + 2d <= 1
  EXPECT_TRUE(std::isnan(greenhall_edf(oadev(0, 0, 100))));
  EXPECT_TRUE(std::isnan(greenhall_edf(oadev(0, 60, 100))));  // no term
  EXPECT_FALSE(std::isnan(greenhall_edf({.alpha = -3, .d = 3, .m = 1, .phase_count = 100})));
}

}  // namespace
}  // namespace stochnav
