#pragma once
// The property tests every noise-model plugin must pass (plugin/noise_model_checks.hpp says
// what each checks), as GoogleTest TEST_Ps of the fixture NoiseModelProperties
// (noise_model_case.hpp). Include this header in exactly one source file of a test executable
// (the TEST_Ps are defined here) and instantiate the suite for your cases in any of them:
//
//   #include "stochnav/testing/noise_model_properties.hpp"
//   using stochnav::testing::NoiseModelCase;
//   using stochnav::testing::NoiseModelProperties;
//   INSTANTIATE_TEST_SUITE_P(MyPlugin, NoiseModelProperties,
//                            ::testing::Values(NoiseModelCase{"my_type", {{"sigma", 0.5}}}),
//                            stochnav::testing::noise_model_case_name);
//
// `stochnav plugins check LIB --params JSON` runs the same checks without GoogleTest.

#include "stochnav/testing/noise_model_case.hpp"

namespace stochnav::testing {

TEST_P(NoiseModelProperties, CovariancesAreSymmetricPositiveSemiDefinite) {
  const auto failures = plugin::check_covariances(model(), checks());
  EXPECT_TRUE(failures.empty()) << failure_lines(failures);
}

TEST_P(NoiseModelProperties, ZeroStepGivesZeroNoiseAndIdentityTransition) {
  const auto failures = plugin::check_zero_step(model(), checks());
  EXPECT_TRUE(failures.empty()) << failure_lines(failures);
}

TEST_P(NoiseModelProperties, ConsecutiveStepsComposeIntoOne) {
  const auto failures = plugin::check_composition(model(), checks());
  EXPECT_TRUE(failures.empty()) << failure_lines(failures);
}

TEST_P(NoiseModelProperties, StationaryCovarianceIsPreservedOverManySteps) {
  if (model().augmented_size() == 0) GTEST_SKIP() << "no augmented states";
  const auto failures = plugin::check_stationarity(model(), checks());
  EXPECT_TRUE(failures.empty()) << failure_lines(failures);
}

TEST_P(NoiseModelProperties, ParamsRebuildAnEqualModel) {
  const auto failures = plugin::check_params_round_trip(model(), rebuild(), checks());
  EXPECT_TRUE(failures.empty()) << failure_lines(failures) << model().describe();
}

}  // namespace stochnav::testing
