#include "stochnav/fit/fit_noise_terms.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>

#include "fit_support.hpp"
#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

using fit_testing::closed_form_fit_data;
using fit_testing::PullStatistics;
using fit_testing::simulated_fit_data;

constexpr double kRateHz = 100.0;

// Pulls (fit - truth) / sigma of every parameter over `seeds` records.
std::map<std::string, PullStatistics> pulls_over_seeds(const NoiseModel& truth,
                                                       const FitOptions& options,
                                                       std::size_t samples, int seeds) {
  std::map<std::string, PullStatistics> pulls;
  for (int seed = 1; seed <= seeds; ++seed) {
    const FitData data =
        simulated_fit_data(truth, samples, kRateHz, static_cast<std::uint64_t>(seed));
    const FitResult result = fit_noise_terms(data, options);
    EXPECT_EQ(result.model.terms.size(), truth.terms.size());
    for (std::size_t i = 0; i < truth.terms.size() && i < result.model.terms.size(); ++i) {
      const TermType type = term_type(truth.terms[i]);
      EXPECT_EQ(term_type(result.model.terms[i]), type);
      const auto specs = parameter_specs(type);
      for (std::size_t k = 0; k < specs.size(); ++k) {
        const auto t = parameter_value(truth.terms[i], k);
        const auto f = parameter_value(result.model.terms[i], k);
        const auto s = parameter_value(result.sigma[i], k);
        if (!t || !f || !s) continue;
        pulls[std::string(term_type_name(type)) + "." + std::string(specs[k].name)]
            .pulls.push_back((*f - *t) / *s);
      }
    }
  }
  return pulls;
}

void expect_sensible_pulls(const std::map<std::string, PullStatistics>& pulls,
                           const std::string& what) {
  for (const auto& [name, stats] : pulls) {
    std::printf("[ pulls ] %-10s %-24s n=%zu mean=%+.3f std=%.3f |pull|<=1: %.2f\n", what.c_str(),
                name.c_str(), stats.pulls.size(), stats.mean(), stats.standard_deviation(),
                stats.within_one());
    EXPECT_LT(std::abs(stats.mean()), 0.5) << what << " " << name;
    EXPECT_GT(stats.standard_deviation(), 0.6) << what << " " << name;
    EXPECT_LT(stats.standard_deviation(), 1.6) << what << " " << name;
  }
}

TEST(FitNoiseTerms, QuantizationWhiteRandomWalkPullsAreStandardNormal) {
  // Q dominates below 0.1 s, N from 0.1 s to 30 s, K above.
  const NoiseModel truth{Unit::kRadPerSecond,
                         kRateHz,
                         {QuantizationTerm{1.8e-4}, AngleRandomWalkTerm{1e-3},
                          RateRandomWalkTerm{5.8e-5}}};
  FitOptions options;
  options.terms = {TermType::kQuantization, TermType::kAngleRandomWalk,
                   TermType::kRateRandomWalk};
  expect_sensible_pulls(pulls_over_seeds(truth, options, 100000, 60), "Q+N+K");
}

TEST(FitNoiseTerms, WhiteGaussMarkovPullsAreStandardNormal) {
  const NoiseModel truth{Unit::kRadPerSecond,
                         kRateHz,
                         {AngleRandomWalkTerm{1e-3}, GaussMarkovTerm{1.6e-3, 5.0}}};
  FitOptions options;
  options.terms = {TermType::kAngleRandomWalk, TermType::kGaussMarkov};
  expect_sensible_pulls(pulls_over_seeds(truth, options, 100000, 60), "N+GM");
}

}  // namespace
}  // namespace stochnav
