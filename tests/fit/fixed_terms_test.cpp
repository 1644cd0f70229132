// FitOptions::fixed_terms: terms held at their values beside the fitted ones (used by diagnose).

#include <gtest/gtest.h>

#include <variant>

#include "fit_support.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/fit/fit_noise_terms.hpp"

namespace stochnav {
namespace {

TEST(FitFixedTerms, FitsOnlyTheFreeTermBesideTheHeldOnes) {
  const NoiseModel truth{Unit::kRadPerSecond,
                         100.0,
                         {AngleRandomWalkTerm{1e-3}, GaussMarkovTerm{1.6e-3, 5.0},
                          RateRandomWalkTerm{5.8e-5}}};
  const FitData like = fit_testing::simulated_fit_data(truth, 100000, 100.0, 3);
  FitData data = fit_testing::closed_form_fit_data(truth, like);
  data.phase_count = 0;
  FitOptions options;
  options.terms = {TermType::kGaussMarkov};
  options.fixed_terms = {AngleRandomWalkTerm{1e-3}, RateRandomWalkTerm{5.8e-5}};
  const FitResult result = fit_noise_terms(data, options);
  ASSERT_EQ(result.model.terms.size(), 1u);  // held terms are not part of the result
  const auto* gm = std::get_if<GaussMarkovTerm>(&result.model.terms[0]);
  ASSERT_NE(gm, nullptr);
  // Noiseless input, but the fit removes the expected log bias of a noisy estimate (about
  // -1/edf per point), so it lands within a few per cent, not exactly.
  EXPECT_NEAR(gm->sigma, 1.6e-3, 0.05 * 1.6e-3);
  EXPECT_NEAR(gm->tau_c, 5.0, 0.05 * 5.0);
}

TEST(FitFixedTerms, RejectsAHeldNonstationaryTerm) {
  FitOptions options;
  options.fixed_terms = {NonstationaryTerm{{{0.0, 1.0, 2.0}}}};
  EXPECT_NE(options.validate().find("fixed_terms"), std::string::npos);
}

}  // namespace
}  // namespace stochnav
