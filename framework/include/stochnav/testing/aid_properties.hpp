#pragma once
// The property tests every aid plugin must pass (plugin/aid_checks.hpp says what each checks),
// as GoogleTest TEST_Ps of the fixture AidProperties (aid_case.hpp). Include this header in
// exactly one source file of a test executable (the TEST_Ps are defined here) and instantiate
// the suite for your cases in any of them (aid_case.hpp shows how).
//
// `stochnav plugins check LIB --params JSON --aid-data CSV --state JSON --at T` runs the same
// checks without GoogleTest.

#include "stochnav/testing/aid_case.hpp"

namespace stochnav::testing {

TEST_P(AidProperties, MeasureWritesEveryEntryOfItsSizes) {
  const auto failures = plugin::check_aid_sizes(aid(), epoch());
  EXPECT_TRUE(failures.empty()) << failure_lines(failures);
}

TEST_P(AidProperties, CovarianceIsSymmetricPositiveDefinite) {
  const auto failures = plugin::check_aid_covariance(aid(), epoch(), checks());
  EXPECT_TRUE(failures.empty()) << failure_lines(failures);
}

TEST_P(AidProperties, ResidualVanishesAtTheTruth) {
  const auto failures = plugin::check_aid_residual_at_truth(aid(), epoch(), checks());
  EXPECT_TRUE(failures.empty()) << failure_lines(failures);
}

TEST_P(AidProperties, JacobianIsTheDerivativeUnderTheNavigatorsErrorInjection) {
  const auto failures = plugin::check_aid_jacobian(aid(), epoch(), checks());
  EXPECT_TRUE(failures.empty()) << failure_lines(failures);
}

TEST_P(AidProperties, ParamsRebuildAnEqualAid) {
  const auto failures = plugin::check_aid_round_trip(aid(), rebuild(), params(), epoch());
  EXPECT_TRUE(failures.empty()) << failure_lines(failures) << aid().describe();
}

}  // namespace stochnav::testing
