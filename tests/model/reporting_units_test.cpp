// Unit conversions between natural SI coefficients and the IEEE 952 reporting units, checked
// against the DESIGN.md table written in reporting units (sigma in deg/h, tau in s).

#include "stochnav/model/reporting_units.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "stochnav/core/angles.hpp"
#include "stochnav/model/allan_variance.hpp"

namespace stochnav {
namespace {

using D = ParameterDimension;

constexpr double kDegPerHourInRadPerSecond = kRadPerDeg / 3600.0;

// Allan variance of a one-term gyro model given in reporting units, in (deg/h)^2.
double gyro_avar_deg_per_hour(NoiseTerm term, double tau) {
  return allan_variance(term, tau) / (kDegPerHourInRadPerSecond * kDegPerHourInRadPerSecond);
}

NoiseTerm natural_term(TermType type, std::initializer_list<double> reported,
                       Quantity quantity = Quantity::kAngularRate) {
  NoiseTerm term = make_term(type);
  const auto specs = parameter_specs(type);
  std::size_t j = 0;
  for (double value : reported) {
    set_parameter_value(term, j, to_natural(quantity, specs[j].dimension, value));
    ++j;
  }
  return term;
}

TEST(ReportingUnits, GyroTermsMatchTheDesignTableInDegPerHour) {
  for (double tau : {0.01, 1.0, 37.0, 1e4}) {
    const double q = 0.2, n = 0.05, b = 0.03, k = 0.3, r = 0.7, s = 0.1, t = 50.0, a = 2.0,
                 f = 0.4;
    EXPECT_NEAR(gyro_avar_deg_per_hour(natural_term(TermType::kQuantization, {q}), tau),
                3 * q * q / (tau * tau), 1e-12 * 3 * q * q / (tau * tau));
    EXPECT_NEAR(gyro_avar_deg_per_hour(natural_term(TermType::kAngleRandomWalk, {n}), tau),
                (60 * n) * (60 * n) / tau, 1e-12 * 3600 * n * n / tau);
    EXPECT_NEAR(std::sqrt(gyro_avar_deg_per_hour(natural_term(TermType::kBiasInstability, {b}),
                                                 tau)),
                0.6643 * b, 1e-4 * b);
    EXPECT_NEAR(gyro_avar_deg_per_hour(natural_term(TermType::kRateRandomWalk, {k}), tau),
                k * k * tau / 10800, 1e-12 * k * k * tau / 10800);
    EXPECT_NEAR(gyro_avar_deg_per_hour(natural_term(TermType::kRateRamp, {r}), tau),
                r * r * tau * tau / (2 * 3600.0 * 3600.0), 1e-12 * r * r * tau * tau / 2.6e7);
    // The table's expression cancels for tau << T: evaluate it in long double.
    const long double x = static_cast<long double>(tau) / t;
    const double gm = static_cast<double>(
        (2 * s * s * t / static_cast<long double>(tau)) *
        (1 - (t / (2 * static_cast<long double>(tau))) * (3 - 4 * std::exp(-x) + std::exp(-2 * x))));
    EXPECT_NEAR(gyro_avar_deg_per_hour(natural_term(TermType::kGaussMarkov, {s, t}), tau), gm,
                1e-8 * gm + 1e-20);
    const double y = std::numbers::pi * f * tau;
    const double sine = a * a * std::pow(std::sin(y), 4) / (y * y);
    EXPECT_NEAR(gyro_avar_deg_per_hour(natural_term(TermType::kSinusoid, {a, f}), tau), sine,
                1e-9 * sine + 1e-20);
  }
}

TEST(ReportingUnits, GyroFactors) {
  const auto q = Quantity::kAngularRate;
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kAngle), kRadPerDeg / 3600.0);  // arcsec
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kAnglePerRootTime), kRadPerDeg / 60.0);
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kRate), kRadPerDeg / 3600.0);
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kRatePerRootTime), kRadPerDeg / 216000.0);
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kRatePerTime), kRadPerDeg / 12960000.0);
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kTime), 1.0);
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kFrequency), 1.0);
  EXPECT_EQ(reported_unit_name(q, D::kAngle), "arcsec");
  EXPECT_EQ(reported_unit_name(q, D::kAnglePerRootTime), "deg/sqrt(h)");
  EXPECT_EQ(reported_unit_name(q, D::kRate), "deg/h");
  EXPECT_EQ(reported_unit_name(q, D::kRatePerRootTime), "deg/h/sqrt(h)");
  EXPECT_EQ(reported_unit_name(q, D::kRatePerTime), "deg/h^2");
}

TEST(ReportingUnits, AccelerometerUsesMetresPerSecondInPlaceOfDegrees) {
  const auto q = Quantity::kSpecificForce;
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kAngle), 1.0);  // m/s
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kAnglePerRootTime), 1.0 / 60.0);
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kRate), 1.0 / 3600.0);
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kRatePerRootTime), 1.0 / 216000.0);
  EXPECT_DOUBLE_EQ(natural_per_reported(q, D::kRatePerTime), 1.0 / 12960000.0);
  EXPECT_EQ(reported_unit_name(q, D::kAnglePerRootTime), "m/s/sqrt(h)");
  EXPECT_EQ(reported_unit_name(q, D::kRate), "m/s/h");
  EXPECT_EQ(reported_unit_name(q, D::kAngle), "m/s");
  // VRW 0.06 m/s/sqrt(h) = 1 mm/s/sqrt(s): AVAR (1e-3 m/s^2)^2 at tau = 1 s.
  const NoiseTerm vrw = natural_term(TermType::kAngleRandomWalk, {0.06}, q);
  EXPECT_NEAR(allan_variance(vrw, 1.0), 1e-6, 1e-18);
}

TEST(ReportingUnits, PlainSignalsUseNaturalUnits) {
  for (auto d : {D::kAngle, D::kAnglePerRootTime, D::kRate, D::kRatePerRootTime, D::kRatePerTime,
                 D::kTime, D::kFrequency, D::kPhase}) {
    EXPECT_EQ(natural_per_reported(Quantity::kPlain, d), 1.0);
  }
  EXPECT_EQ(reported_unit_name(Quantity::kPlain, D::kAnglePerRootTime), "signal*sqrt(s)");
}

TEST(ReportingUnits, RoundTrip) {
  for (auto q : {Quantity::kAngularRate, Quantity::kSpecificForce, Quantity::kPlain}) {
    for (auto d : {D::kAngle, D::kAnglePerRootTime, D::kRate, D::kRatePerRootTime,
                   D::kRatePerTime}) {
      EXPECT_NEAR(to_reported(q, d, to_natural(q, d, 0.123)), 0.123, 1e-15);
    }
  }
}

}  // namespace
}  // namespace stochnav
