#include "stochnav/model/noise_model_json.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/model/allan_variance.hpp"

namespace stochnav {
namespace {

using nlohmann::json;

json every_term_model() {
  return json::parse(R"({
    "units": "deg/h", "rate_hz": 100,
    "terms": [
      {"type": "quantization", "Q": 0.2},
      {"type": "angle_random_walk", "N": 0.05},
      {"type": "bias_instability", "B": 0.03},
      {"type": "rate_random_walk", "K": 0.3},
      {"type": "rate_ramp", "R": -0.01},
      {"type": "gauss_markov", "sigma": 0.1, "tau_c": 100},
      {"type": "sinusoid", "amplitude": 1.5, "frequency_hz": 2},
      {"type": "sinusoid", "amplitude": 1, "frequency_hz": 0.25, "phase_rad": 0.5},
      {"type": "nonstationary", "segments": [{"start": 10, "end": 20, "scale": 8},
                                             {"start": 20, "end": 25.5, "scale": 0}]}
    ]})");
}

TEST(NoiseModelJson, RoundTripPreservesTheDocumentAndTheModel) {
  const json document = every_term_model();
  const NoiseModel model = noise_model_from_json(document);
  EXPECT_EQ(model.unit, Unit::kDegPerHour);
  EXPECT_EQ(model.rate_hz, 100.0);
  ASSERT_EQ(model.terms.size(), 9u);
  EXPECT_EQ(to_json(model), document) << to_json(model).dump(2);
  EXPECT_TRUE(equals(noise_model_from_json(to_json(model)), model, 1e-15));
}

TEST(NoiseModelJson, ParsesIntoNaturalUnits) {
  const NoiseModel model = noise_model_from_json(every_term_model());
  EXPECT_DOUBLE_EQ(std::get<QuantizationTerm>(model.terms[0]).q, 0.2 * kRadPerDeg / 3600);
  EXPECT_DOUBLE_EQ(std::get<AngleRandomWalkTerm>(model.terms[1]).n, 0.05 * kRadPerDeg / 60);
  EXPECT_DOUBLE_EQ(std::get<BiasInstabilityTerm>(model.terms[2]).b, 0.03 * kRadPerDeg / 3600);
  EXPECT_DOUBLE_EQ(std::get<RateRandomWalkTerm>(model.terms[3]).k,
                   0.3 * kRadPerDeg / 3600 / 60);
  EXPECT_DOUBLE_EQ(std::get<RateRampTerm>(model.terms[4]).r, -0.01 * kRadPerDeg / 3600 / 3600);
  const auto& gm = std::get<GaussMarkovTerm>(model.terms[5]);
  EXPECT_DOUBLE_EQ(gm.sigma, 0.1 * kRadPerDeg / 3600);
  EXPECT_DOUBLE_EQ(gm.tau_c, 100.0);
  EXPECT_FALSE(std::get<SinusoidTerm>(model.terms[6]).phase_rad.has_value());
  EXPECT_DOUBLE_EQ(*std::get<SinusoidTerm>(model.terms[7]).phase_rad, 0.5);
  const auto& segments = std::get<NonstationaryTerm>(model.terms[8]).segments;
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[1].end_s, 25.5);
  EXPECT_EQ(segments[1].scale, 0.0);
}

TEST(NoiseModelJson, SignalUnitDoesNotChangeTheReportingUnits) {
  json document = every_term_model();
  const NoiseModel deg_h = noise_model_from_json(document);
  document["units"] = "rad/s";
  const NoiseModel rad_s = noise_model_from_json(document);
  EXPECT_EQ(rad_s.unit, Unit::kRadPerSecond);
  for (double tau : {0.1, 10.0}) {
    EXPECT_DOUBLE_EQ(allan_variance(deg_h, tau), allan_variance(rad_s, tau));
  }
  document["units"] = "m/s^2";
  const NoiseModel accel = noise_model_from_json(document);
  EXPECT_DOUBLE_EQ(std::get<AngleRandomWalkTerm>(accel.terms[1]).n, 0.05 / 60);
  document["units"] = "plain";
  const NoiseModel plain = noise_model_from_json(document);
  EXPECT_DOUBLE_EQ(std::get<AngleRandomWalkTerm>(plain.terms[1]).n, 0.05);
}

TEST(NoiseModelJson, ReadsTheShippedExampleConfig) {
  std::ifstream file(std::string(STOCHNAV_SOURCE_DIR) + "/configs/noise/fog_vibration_example.json");
  ASSERT_TRUE(file) << "example config missing";
  const NoiseModel model = noise_model_from_json(json::parse(file));
  EXPECT_EQ(model.terms.size(), 5u);
  EXPECT_FALSE(describe(model).empty());
}

TEST(NoiseModelJson, AcceptsAFitResultWithUncertaintiesAndDiagnostics) {
  const json fit = json::parse(R"({
    "units": "deg/h", "rate_hz": 100,
    "terms": [{"type": "angle_random_walk", "N": 0.05, "N_sigma": 0.001},
              {"type": "gauss_markov", "sigma": 0.1, "sigma_sigma": null, "tau_c": 3,
               "tau_c_sigma": 0.5}],
    "diagnostics": {"cost": 1.0}})");
  const NoiseModel model = noise_model_from_json(fit);
  EXPECT_EQ(model.terms.size(), 2u);
}

struct BadCase {
  std::string name;
  std::string document;
  std::string pointer;  // expected at the start of the message
  std::string problem;  // expected somewhere in the message
};

class NoiseModelJsonErrors : public ::testing::TestWithParam<BadCase> {};

std::string model_with_terms(const std::string& terms) {
  return R"({"units": "deg/h", "rate_hz": 100, "terms": [)" + terms + "]}";
}

TEST_P(NoiseModelJsonErrors, NamesThePointerTheProblemAndTheExpectedForm) {
  const BadCase& c = GetParam();
  for (const std::string prefix : {"", "/sensors/2/noise"}) {
    try {
      noise_model_from_json(json::parse(c.document), prefix);
      FAIL() << c.name << ": no error";
    } catch (const ConfigError& error) {
      const std::string message = error.what();
      const std::string pointer = c.pointer.empty() ? (prefix.empty() ? "(root)" : prefix)
                                                    : prefix + c.pointer;
      EXPECT_EQ(message.rfind(pointer + ": ", 0), 0u) << c.name << ": " << message;
      EXPECT_NE(message.find(c.problem), std::string::npos) << c.name << ": " << message;
      EXPECT_NE(message.find("; expected "), std::string::npos) << c.name << ": " << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << c.name << ": " << message;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    EveryRule, NoiseModelJsonErrors,
    ::testing::Values(
        BadCase{"RootNotObject", "[1, 2]", "", "is an array, not an object"},
        BadCase{"UnknownTopKey", R"({"units": "deg/h", "rate_hz": 1, "terms": [], "name": 1})",
                "/name", "unknown key"},
        BadCase{"MissingUnits", R"({"rate_hz": 1, "terms": []})", "/units", "is missing"},
        BadCase{"UnitsNotString", R"({"units": 3, "rate_hz": 1, "terms": []})", "/units",
                "is a number, not a string"},
        BadCase{"UnknownUnit", R"({"units": "furlong/fortnight", "rate_hz": 1, "terms": []})",
                "/units", "unknown unit \"furlong/fortnight\""},
        BadCase{"MissingRate", R"({"units": "deg/h", "terms": []})", "/rate_hz", "is missing"},
        BadCase{"RateNotNumber", R"({"units": "deg/h", "rate_hz": "100", "terms": []})",
                "/rate_hz", "is a string, not a number"},
        BadCase{"RateZero", R"({"units": "deg/h", "rate_hz": 0, "terms": []})", "/rate_hz",
                "0 is not positive"},
        BadCase{"RateNegative", R"({"units": "deg/h", "rate_hz": -5, "terms": []})", "/rate_hz",
                "-5 is not positive"},
        BadCase{"MissingTerms", R"({"units": "deg/h", "rate_hz": 1})", "/terms", "is missing"},
        BadCase{"TermsNotArray", R"({"units": "deg/h", "rate_hz": 1, "terms": {}})", "/terms",
                "is an object, not an array"},
        BadCase{"TermNotObject", model_with_terms("5"), "/terms/0", "not an object"},
        BadCase{"TermWithoutType", model_with_terms(R"({"N": 1})"), "/terms/0/type",
                "is missing"},
        BadCase{"TypeNotString", model_with_terms(R"({"type": 1})"), "/terms/0/type",
                "not a string"},
        BadCase{"UnknownType", model_with_terms(R"({"type": "pink_noise"})"), "/terms/0/type",
                "unknown term type \"pink_noise\""},
        BadCase{"UnknownTermKey", model_with_terms(R"({"type": "angle_random_walk", "N": 1, "M": 2})"),
                "/terms/0/M", "unknown key"},
        BadCase{"TypoOfTermKey",
                model_with_terms(R"({"type": "gauss_markov", "sigma": 1, "tua_c": 2})"),
                "/terms/0/tua_c", "is an unknown key (did you mean 'tau_c'?)"},
        BadCase{"MissingParameter", model_with_terms(R"({"type": "angle_random_walk"})"),
                "/terms/0/N", "is missing"},
        BadCase{"ParameterNotNumber",
                model_with_terms(R"({"type": "angle_random_walk", "N": "0.1"})"), "/terms/0/N",
                "is a string, not a number"},
        BadCase{"ParameterBoolean", model_with_terms(R"({"type": "quantization", "Q": true})"),
                "/terms/0/Q", "is a boolean, not a number"},
        BadCase{"NegativeCoefficient",
                model_with_terms(R"({"type": "angle_random_walk", "N": 0.1},
                                    {"type": "rate_random_walk", "K": -0.3})"),
                "/terms/1/K", "-0.3 is out of range"},
        BadCase{"ZeroCorrelationTime",
                model_with_terms(R"({"type": "gauss_markov", "sigma": 1, "tau_c": 0})"),
                "/terms/0/tau_c", "0 is out of range"},
        BadCase{"ZeroFrequency",
                model_with_terms(R"({"type": "sinusoid", "amplitude": 1, "frequency_hz": 0})"),
                "/terms/0/frequency_hz", "out of range"},
        BadCase{"NegativeSigmaOfFit",
                model_with_terms(R"({"type": "angle_random_walk", "N": 1, "N_sigma": -1})"),
                "/terms/0/N_sigma", "is negative"},
        BadCase{"SigmaOfUnknownParameter",
                model_with_terms(R"({"type": "angle_random_walk", "N": 1, "K_sigma": 1})"),
                "/terms/0/K_sigma", "unknown key"},
        BadCase{"SegmentsMissing", model_with_terms(R"({"type": "nonstationary"})"),
                "/terms/0/segments", "is missing"},
        BadCase{"SegmentsNotArray",
                model_with_terms(R"({"type": "nonstationary", "segments": 3})"),
                "/terms/0/segments", "not an array"},
        BadCase{"SegmentsEmpty", model_with_terms(R"({"type": "nonstationary", "segments": []})"),
                "/terms/0/segments", "no segments"},
        BadCase{"SegmentUnknownKey",
                model_with_terms(
                    R"({"type": "nonstationary", "segments": [{"start": 0, "end": 1, "scale": 2, "gain": 1}]})"),
                "/terms/0/segments/0/gain", "unknown key"},
        BadCase{"SegmentEndBeforeStart",
                model_with_terms(
                    R"({"type": "nonstationary", "segments": [{"start": 5, "end": 1, "scale": 2}]})"),
                "/terms/0/segments/0/end", "is not after start"},
        BadCase{"SegmentNegativeScale",
                model_with_terms(
                    R"({"type": "nonstationary", "segments": [{"start": 0, "end": 1, "scale": -2}]})"),
                "/terms/0/segments/0/scale", "-2 is invalid"},
        BadCase{"SegmentsOverlap",
                model_with_terms(R"({"type": "nonstationary", "segments": [
                    {"start": 0, "end": 10, "scale": 2}, {"start": 5, "end": 20, "scale": 3}]})"),
                "/terms/0/segments/1/start", "overlaps"},
        BadCase{"SecondNonstationary",
                model_with_terms(
                    R"({"type": "nonstationary", "segments": [{"start": 0, "end": 1, "scale": 2}]},
                       {"type": "nonstationary", "segments": [{"start": 3, "end": 4, "scale": 2}]})"),
                "/terms/1", "second nonstationary term"},
        BadCase{"DiagnosticsNotObject",
                R"({"units": "deg/h", "rate_hz": 1, "terms": [], "diagnostics": 3})",
                "/diagnostics", "not an object"}),
    [](const ::testing::TestParamInfo<BadCase>& param_info) { return param_info.param.name; });

TEST(NoiseModelJson, MessageQuotesTheReportingUnit) {
  try {
    noise_model_from_json(json::parse(model_with_terms(R"({"type": "angle_random_walk", "N": -1})")));
    FAIL();
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("deg/sqrt(h)"), std::string::npos) << error.what();
  }
}

TEST(NoiseModel, EqualsComparesWithinRelativeTolerance) {
  const NoiseModel a = noise_model_from_json(every_term_model());
  NoiseModel b = a;
  EXPECT_TRUE(equals(a, b));
  std::get<AngleRandomWalkTerm>(b.terms[1]).n *= 1.0 + 1e-6;
  EXPECT_FALSE(equals(a, b, 1e-9));
  EXPECT_TRUE(equals(a, b, 1e-5));
  b = a;
  std::get<SinusoidTerm>(b.terms[6]).phase_rad = 0.0;
  EXPECT_FALSE(equals(a, b));
  b = a;
  std::get<NonstationaryTerm>(b.terms[8]).segments.pop_back();
  EXPECT_FALSE(equals(a, b));
  b = a;
  b.unit = Unit::kRadPerSecond;
  EXPECT_FALSE(equals(a, b));
  b = a;
  std::swap(b.terms[0], b.terms[1]);
  EXPECT_FALSE(equals(a, b));
}

TEST(NoiseModel, DescribeListsTermsInReportingUnits) {
  const std::string text = describe(noise_model_from_json(every_term_model()));
  EXPECT_NE(text.find("noise model: deg/h at 100 Hz, 9 terms"), std::string::npos) << text;
  EXPECT_NE(text.find("angle_random_walk: N = 0.05 deg/sqrt(h)"), std::string::npos) << text;
  EXPECT_NE(text.find("quantization: Q = 0.2 arcsec"), std::string::npos) << text;
  EXPECT_NE(text.find("gauss_markov: sigma = 0.1 deg/h, tau_c = 100 s"), std::string::npos)
      << text;
  EXPECT_NE(text.find("nonstationary: x8 over [10, 20) s"), std::string::npos) << text;
  const NoiseTerm sigma = AngleRandomWalkTerm{0.001 * kRadPerDeg / 60};
  const NoiseTerm term = AngleRandomWalkTerm{0.05 * kRadPerDeg / 60};
  EXPECT_EQ(describe(term, Quantity::kAngularRate, &sigma),
            "angle_random_walk: N = 0.05 +/- 0.001 deg/sqrt(h)");
}

TEST(NoiseModel, FindModelIssueChecksProgrammaticModels) {
  NoiseModel model{Unit::kRadPerSecond, 0.0, {}};
  ASSERT_TRUE(find_model_issue(model).has_value());
  EXPECT_EQ(find_model_issue(model)->pointer, "/rate_hz");
  model.rate_hz = 10.0;
  EXPECT_FALSE(find_model_issue(model).has_value());
  model.terms.push_back(SinusoidTerm{1.0, 1.0, std::numeric_limits<double>::infinity()});
  ASSERT_TRUE(find_model_issue(model).has_value());
  EXPECT_EQ(find_model_issue(model)->pointer, "/terms/0/phase_rad");
}

}  // namespace
}  // namespace stochnav
