// Fits a user can steer through the noise plugins' fit options (issue #30 item 3): "method",
// "start", "fix" and "bound" (plugin/fit_steering.hpp) reach the fit, bad entries are refused
// naming their JSON pointer, and the SDK entry point third-party fitters use,
// fit_calibration_axes, holds a correlation time of a white + two Gauss-Markov model.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>

#include "fit_recovery.hpp"
#include "noise_plugin_support.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/model/noise_model.hpp"
#include "stochnav/plugin/calibration_fit.hpp"

namespace stochnav::plugin {
namespace {

using testing::context_for;
using testing::kDegPerHour;
using testing::kDegPerRootHour;
using testing::registry;
using testing::simulated_record;

NoiseModel white_and_gauss_markov() {
  return {Unit::kRadPerSecond,
          100.0,
          {AngleRandomWalkTerm{0.05 * kDegPerRootHour}, GaussMarkovTerm{10.0 * kDegPerHour, 5.0}}};
}

std::shared_ptr<NoiseModelPlugin> fit(const std::string& type, const nlohmann::json& params,
                                      const NoiseModel& truth = white_and_gauss_markov()) {
  return registry().fit_noise_model(type, simulated_record(truth, 600.0, 21), params,
                                    context_for(SensorGroup::kGyro), "/noise/gyro/plugin");
}

// The message of the ConfigError a fit with `params` throws ("no error" without one).
std::string refusal(const std::string& type, const nlohmann::json& params) {
  try {
    fit(type, params);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "no error";
}

TEST(FitSteeringPlugins, GaussMarkovHoldsAFixedCorrelationTimeWithEitherMethod) {
  for (const char* method : {"avar", "gmwm"}) {
    const auto model =
        fit("gauss_markov", {{"method", method}, {"fix", {{"gauss_markov.tau_c", 7.5}}}});
    const nlohmann::json params = model->params();
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(params["tau_c"][axis].get<double>(), 7.5) << method;
      EXPECT_NEAR(params["sigma"][axis].get<double>(), 10.0, 3.0) << method;
    }
    EXPECT_EQ(model->fit_quality()["x"]["estimator"], method);
  }
}

TEST(FitSteeringPlugins, BoundsAndStartsReachTheFit) {
  const auto bounded = fit("augmented", {{"terms", {"angle_random_walk", "gauss_markov"}},
                                         {"bound", {{"gauss_markov.tau_c", {8.0, 20.0}}}}});
  const nlohmann::json params = bounded->params();  // a range-for would not keep it alive
  for (const auto& model : params["models"]) {
    const double tau_c = model["terms"][1]["tau_c"].get<double>();
    EXPECT_GE(tau_c, 8.0);
    EXPECT_LE(tau_c, 20.0);
  }
  const auto white =
      fit("white", {{"method", "gmwm"}, {"start", {{"angle_random_walk.N", 0.1}}}},
          NoiseModel{Unit::kRadPerSecond, 100.0, {AngleRandomWalkTerm{0.2 * kDegPerRootHour}}});
  EXPECT_NEAR(white->params()["N"][0].get<double>(), 0.2, 0.01);
  EXPECT_EQ(white->fit_quality()["x"]["estimator"], "gmwm");
}

// The third-party case: a fitter of white noise and two Gauss-Markov terms through the
// SDK entry point, one correlation time held and the other bounded (FitOptions::controls, natural
// SI units). Every axis keeps the held value exactly (sigma 0), keeps the other within its bound,
// and recovers the truth's short term.
TEST(FitSteeringPlugins, ThirdPartyFitterHoldsAndBoundsCorrelationTimes) {
  const NoiseModel truth{Unit::kRadPerSecond,
                         100.0,
                         {AngleRandomWalkTerm{0.05 * kDegPerRootHour},
                          GaussMarkovTerm{10.0 * kDegPerHour, 1.0},
                          GaussMarkovTerm{5.0 * kDegPerHour, 100.0}}};
  FitOptions options;
  options.terms = {TermType::kAngleRandomWalk, TermType::kGaussMarkov, TermType::kGaussMarkov};
  options.controls = {{.term = 1, .parameter = 1, .lower = 0.2, .upper = 5.0},
                      {.term = 2, .parameter = 1, .fixed = 100.0}};
  const auto fits = fit_calibration_axes(simulated_record(truth, 1000.0, 31), options,
                                         CalibrationEstimator::kAllanVariance);
  for (const FitResult& fit : fits) {
    ASSERT_EQ(fit.model.terms.size(), 3u) << fit.diagnostics.failure();
    const auto& short_term = std::get<GaussMarkovTerm>(fit.model.terms[1]);
    EXPECT_GE(short_term.tau_c, 0.2);
    EXPECT_LE(short_term.tau_c, 5.0);
    EXPECT_NEAR(short_term.tau_c, 1.0, 0.5);
    EXPECT_EQ(std::get<GaussMarkovTerm>(fit.model.terms[2]).tau_c, 100.0);
    EXPECT_EQ(std::get<GaussMarkovTerm>(fit.sigma[2]).tau_c, 0.0);
    EXPECT_FALSE(fit.diagnostics.failed()) << fit.diagnostics.failure();
  }
}

// davar: the steering reaches its whole-record N + K fit (the windows' fit is linear). On white
// noise K goes to the lower bound given, which is not a failed fit (no floor-matched fallback).
TEST(FitSteeringPlugins, DavarSteersItsRateRandomWalkFit) {
  const auto model =
      fit("davar",
          {{"rate_random_walk", true},
           {"method", "gmwm"},
           {"bound", {{"rate_random_walk.K", {0.01, 0.02}}}}},
          NoiseModel{Unit::kRadPerSecond, 100.0, {AngleRandomWalkTerm{0.05 * kDegPerRootHour}}});
  const nlohmann::json quality = model->fit_quality()["rate_random_walk_fit"];
  EXPECT_EQ(quality["x"]["estimator"], "gmwm") << quality.dump();
  for (int axis = 0; axis < 3; ++axis) {
    const double k = model->params()["K"][axis].get<double>();
    EXPECT_GE(k, 0.01 * (1 - 1e-9));
    EXPECT_LE(k, 0.02 * (1 + 1e-9));
  }
}

TEST(FitSteeringPlugins, BadEntriesNameTheirJsonPointer) {
  const std::string at = "/noise/gyro/params/";
  EXPECT_EQ(
      refusal("gauss_markov", {{"fix", {{"gauss_markov.beta", 1.0}}}}),
      at + "fix/gauss_markov.beta: gauss_markov has no parameter 'beta'; it has sigma, tau_c");
  EXPECT_EQ(refusal("gauss_markov", {{"start", {{"drift.tau_c", 1.0}}}}),
            at + "start/drift.tau_c: unknown term 'drift'; name a term of the model's terms");
  EXPECT_EQ(
      refusal("gauss_markov", {{"start", {{"rate_random_walk.K", 1.0}}}})
          .rfind(at + "start/rate_random_walk.K: the model has 0 rate_random_walk term(s)", 0),
      0u);
  EXPECT_EQ(refusal("gauss_markov", {{"bound", {{"gauss_markov.tau_c", {10.0, 1.0}}}}}),
            at + "bound/gauss_markov.tau_c: LOW is not below HIGH; give LOW < HIGH");
  EXPECT_EQ(refusal("gauss_markov", {{"fix", {{"gauss_markov.tau_c", 50.0}}},
                                     {"bound", {{"gauss_markov.tau_c", {1.0, 10.0}}}}}),
            at + "fix/gauss_markov.tau_c: is outside its bound; give a value within LOW:HIGH");
  EXPECT_EQ(refusal("white", {{"fix", {{"angle_random_walk.N", 0.1}}}}),
            at + "fix: every parameter of the model is fixed, nothing is left to fit; leave at "
                 "least one free");
  EXPECT_EQ(refusal("gauss_markov", {{"fix", {{"gauss_markov.tau_c", -1.0}}}}),
            at + "fix/gauss_markov.tau_c: found -1.0; expected a number > 0 in reporting units");
  EXPECT_EQ(refusal("gauss_markov", {{"bound", {{"gauss_markov.tau_c", 3.0}}}}),
            at + "bound/gauss_markov.tau_c: found 3.0; expected [LOW, HIGH], two numbers > 0 in "
                 "reporting units");
  EXPECT_EQ(refusal("gauss_markov", {{"fix", 3.0}}),
            at + "fix: found 3.0; expected an object {\"TERM[#K].PARAM\": VALUE}");
  EXPECT_EQ(refusal("gauss_markov", {{"method", "ols"}}).rfind(at + "method: found \"ols\"", 0),
            0u);
  EXPECT_EQ(refusal("davar", {{"method", "gmwm"}}),
            at + "method: steers the whole-record N + K fit; add \"rate_random_walk\": true, or "
                 "remove it (the windows' Eq. 7 fit takes neither)");
  EXPECT_EQ(refusal("augmented", {{"fix", {{"gauss_markov.tau_c", 1.0}}}})
                .rfind(at + "terms: missing", 0),
            0u);
}

}  // namespace
}  // namespace stochnav::plugin
