// ParamTable: one declaration per parameter gives reading with unit conversion, writing,
// describing, comparing and documentation.

#include "stochnav/plugin/param_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "stochnav/core/errors.hpp"

namespace stochnav::plugin {
namespace {

using Axes = std::array<double, 3>;

struct ExampleParams {
  Axes sigma{};      ///< rad/s or m/s^2
  double tau_c = 0;  ///< s
  double n = 0;      ///< rad/sqrt(s) or m/s/sqrt(s)
  bool white = false;
};

const ParamTable<ExampleParams> kTable{
    per_axis(&ExampleParams::sigma, "sigma", ParamUnit::of(ParameterDimension::kRate),
             Bound::kPositive, kRequired, "stationary standard deviation"),
    scalar(&ExampleParams::tau_c, "tau_c", ParamUnit::fixed("s"), Bound::kPositive, 10.0,
           "correlation time"),
    scalar(&ExampleParams::n, "N", ParamUnit::of(ParameterDimension::kAnglePerRootTime),
           Bound::kNonNegative, kDerived, "angle random walk"),
    flag(&ExampleParams::white, "white", true, "add white noise"),
};

constexpr double kRadPerSecondPerDegPerHour = std::numbers::pi / 180.0 / 3600.0;

std::string error_of(const nlohmann::json& json) {
  try {
    kTable.parse(json, "/p", Quantity::kAngularRate);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "(accepted)";
}

TEST(ParamTable, ReadsReportingUnitsIntoNaturalUnitsWithDefaults) {
  const nlohmann::json json = {{"sigma", {1.0, 2.0, 3.0}}};
  const ExampleParams gyro = kTable.parse(json, "/p", Quantity::kAngularRate);
  EXPECT_DOUBLE_EQ(gyro.sigma[1], 2.0 * kRadPerSecondPerDegPerHour);
  EXPECT_EQ(gyro.tau_c, 10.0);
  EXPECT_TRUE(std::isnan(gyro.n));  // derived by the factory
  EXPECT_TRUE(gyro.white);
  const ExampleParams accel = kTable.parse(json, "/p", Quantity::kSpecificForce);
  EXPECT_DOUBLE_EQ(accel.sigma[2], 3.0 / 3600.0);  // m/s/h -> m/s^2
}

TEST(ParamTable, WritesWhatItReadsAndComparesWithinTolerance) {
  const nlohmann::json json = {{"sigma", 0.5}, {"tau_c", 20}, {"N", 0.05}, {"white", false}};
  const ExampleParams params = kTable.parse(json, "/p", Quantity::kAngularRate);
  const nlohmann::json written = kTable.to_json(params, Quantity::kAngularRate);
  EXPECT_EQ(written["sigma"].size(), 3u);
  EXPECT_NEAR(written["sigma"][0].get<double>(), 0.5, 1e-15);
  EXPECT_EQ(written["white"], false);
  const ExampleParams again = kTable.parse(written, "/p", Quantity::kAngularRate);
  EXPECT_TRUE(kTable.equal(params, again, 1e-12));
  ExampleParams other = params;
  other.sigma[2] *= 1.001;
  EXPECT_FALSE(kTable.equal(params, other, 1e-6));
  EXPECT_TRUE(kTable.equal(params, other, 1e-2));
  other = params;
  other.white = true;
  EXPECT_FALSE(kTable.equal(params, other, 1.0));
  EXPECT_EQ(kTable.describe(params, Quantity::kAngularRate),
            "sigma = 0.5 deg/h, tau_c = 20 s, N = 0.05 deg/sqrt(h), white = false");
}

TEST(ParamTable, ErrorsNameThePointerTheUnitAndTypos) {
  EXPECT_EQ(error_of({{"tau_c", 1}}).rfind("/p/sigma: missing; expected a number > 0 (deg/h)", 0),
            0u);
  EXPECT_EQ(error_of({{"sigma", 1}, {"tau_c", 0}}), "/p/tau_c: found 0; expected a number > 0 (s)");
  EXPECT_EQ(error_of({{"sigam", 1}}), "/p/sigam: unknown key 'sigam'; did you mean 'sigma'?");
  EXPECT_EQ(error_of({{"sigma", 1}, {"colour", 1}}),
            "/p/colour: unknown key; expected only N, sigma, tau_c, white");
}

TEST(ParamTable, DocumentsEachParameter) {
  const auto lines = kTable.documentation(Quantity::kAngularRate);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0],
            "sigma: stationary standard deviation; a number > 0 (deg/h), per axis (a number or "
            "[x, y, z]), required");
  EXPECT_EQ(lines[1], "tau_c: correlation time; a number > 0 (s), default 10 s");
  EXPECT_EQ(lines[3], "white: add white noise; true or false, default true");
}

}  // namespace
}  // namespace stochnav::plugin
