// Two effects behind one model (issue #16, the named failure): a rate random walk and a slow
// sinusoid hidden behind a white-noise-only FOG model in 4-hour gyro records. The issue saw the
// first step name the sinusoid (gap about 70 -> 3) and the workflow stop there without the
// random walk. Here the gap starts at 60-70 and is about 5 after the first step; the workflow
// must go on and end with both effects in the model (the random walk found by the Allan
// candidates, by the time-domain test, or by the final model selection when a Gauss-Markov
// term of long correlation time stood in for it), and a consistent model. Six seeds; one in
// sanitized builds (sanitized_build.hpp).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "diagnose_support.hpp"
#include "sanitized_build.hpp"
#include "stochnav/diagnose/diagnose.hpp"

namespace stochnav {
namespace {

using diagnose_testing::natural;
using diagnose_testing::simulated_record;

bool has_type(const NoiseModel& model, TermType type) {
  return std::any_of(model.terms.begin(), model.terms.end(),
                     [&](const NoiseTerm& term) { return term_type(term) == type; });
}

TEST(DiagnoseTwoEffects, RateRandomWalkAndSlowSinusoidAreBothNamed) {
  // 4 h at 10 Hz; STOCHNAV_TWO_EFFECTS_RATE=100 runs the rate (ten times the cost).
  double rate_hz = 10.0;
  if (const char* text = std::getenv("STOCHNAV_TWO_EFFECTS_RATE")) rate_hz = std::atof(text);
  ASSERT_GT(rate_hz, 0.0);
  const auto samples = static_cast<std::size_t>(4.0 * 3600.0 * rate_hz);
  const int seeds = stochnav::testing::study_size(6, 1);  // every seed must be consistent
  // A FOG with 0.05 deg/sqrt(h) white noise; hidden: K = 0.3 deg/h/sqrt(h) and a 1.3 deg/h
  // sinusoid at a 600-s period.
  const NoiseModel base{
      Unit::kDegPerHour,
      rate_hz,
      {AngleRandomWalkTerm{natural(ParameterDimension::kAnglePerRootTime, 0.05)}}};
  NoiseModel truth = base;
  truth.terms.push_back(RateRandomWalkTerm{natural(ParameterDimension::kRatePerRootTime, 0.3)});
  truth.terms.push_back(SinusoidTerm{natural(ParameterDimension::kRate, 1.3), 1.0 / 600.0, {}});
  DiagnoseOptions options;
  options.seeds = 0;
  int both = 0;
  int consistent = 0;
  for (int k = 0; k < seeds; ++k) {
    const Record record = simulated_record(truth, samples, rate_hz, 7000 + k);
    const DiagnoseResult result = diagnose(record, base, options);
    const NoiseModel final_model = result.final_model();
    const bool found = has_type(final_model, TermType::kRateRandomWalk) &&
                       has_type(final_model, TermType::kSinusoid);
    if (found) ++both;
    if (result.consistent) ++consistent;
    std::string steps;
    for (const auto& step : result.iterations) {
      steps += (steps.empty() ? "" : ", ") + std::string(term_type_name(step.effect));
    }
    std::printf("[ two effects ] seed %d  gap %.3g -> %.3g  steps: %s%s\n", 7000 + k,
                result.initial.gap.value, result.final_assessment().gap.value, steps.c_str(),
                found ? "" : "  (random walk or sinusoid missing from the final model)");
    EXPECT_GT(result.initial.gap.value, 30.0) << "seed " << 7000 + k;
  }
  EXPECT_GE(both, std::max(seeds - 1, 1));
  EXPECT_EQ(consistent, seeds);
}

}  // namespace
}  // namespace stochnav
