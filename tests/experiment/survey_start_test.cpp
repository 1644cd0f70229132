// The survey's start in a run (run/survey_start.hpp): the tally at the start, the tie-on MD
// checked against it, the sensor-to-bit offset, and the depth aid's stated sigma.

#include "run/survey_start.hpp"

#include <gtest/gtest.h>

#include <string>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

plugin::RunConfig config_with_tie_on_md(std::optional<double> md_m, double sensor_to_bit_m = 0.0) {
  plugin::RunConfig config;
  config.initial_state = plugin::InitialStateConfig{};
  config.initial_state->tie_on.measured_depth_m = md_m;
  config.survey.sensor_to_bit_m = sensor_to_bit_m;
  return config;
}

// Three readings at rest (zupt 1), then drilling: the start is their mean, not the first one.
plugin::AidData tally_with_rest() {
  return plugin::AidData("aids.csv", {"t", "measured_depth_m", "zupt"},
                         {{0, 1, 2, 3}, {500.06, 499.97, 499.97, 503.0}, {1, 1, 1, 0}});
}

TEST(SurveyStart, TallyAtTheStartIsTheMeanOfTheLeadingReadingsAtRest) {
  EXPECT_NEAR(*tally_md_at_start_m(tally_with_rest()), 500.0, 1e-12);
  // Without a zupt column: the first reading; without readings: none.
  const plugin::AidData no_flags("aids.csv", {"t", "measured_depth_m"}, {{0, 1}, {12.5, 13.0}});
  EXPECT_EQ(*tally_md_at_start_m(no_flags), 12.5);
  EXPECT_FALSE(tally_md_at_start_m(plugin::AidData()).has_value());
  const plugin::AidData moving("aids.csv", {"t", "measured_depth_m", "zupt"},
                               {{0, 1}, {12.5, 13.0}, {0, 1}});
  EXPECT_EQ(*tally_md_at_start_m(moving), 12.5);
}

TEST(SurveyStart, TieOnMdFarFromTheTallyNamesThePointerAndBothValues) {
  EXPECT_NO_THROW(check_tie_on_against_tally(config_with_tie_on_md(496.0), 500.0));
  try {
    check_tie_on_against_tally(config_with_tie_on_md(494.0), 500.0);
    FAIL() << "6 m off with the default 5 m tolerance";
  } catch (const ConfigError& error) {
    const std::string message = error.what();
    EXPECT_TRUE(message.starts_with("/initial_state/tie_on/measured_depth_m: 494 m")) << message;
    EXPECT_NE(message.find("500.000"), std::string::npos) << message;
    EXPECT_NE(message.find("/survey/tie_on_md_tolerance_m 5"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  // The sensor 6 m behind the bit: the tally's 500 m is the sensor's 494 m.
  EXPECT_NO_THROW(check_tie_on_against_tally(config_with_tie_on_md(494.0, 6.0), 500.0));
  plugin::RunConfig wide = config_with_tie_on_md(494.0);
  wide.survey.tie_on_md_tolerance_m = 10.0;
  EXPECT_NO_THROW(check_tie_on_against_tally(wide, 500.0));
  // Nothing to check without a configured MD or a tally.
  EXPECT_NO_THROW(check_tie_on_against_tally(config_with_tie_on_md(std::nullopt), 500.0));
  EXPECT_NO_THROW(check_tie_on_against_tally(config_with_tie_on_md(100.0), std::nullopt));
}

TEST(SurveyStart, TieOnMdFromTheTallyTakenToTheSensor) {
  const NavState start;
  EXPECT_NEAR(survey_tie_on(config_with_tie_on_md(std::nullopt, 12.5), start, start, 500.0)
                  .measured_depth_m,
              487.5, 1e-12);
  EXPECT_EQ(survey_tie_on(config_with_tie_on_md(480.0, 12.5), start, start, 500.0).measured_depth_m,
            480.0);
  EXPECT_EQ(survey_tie_on(plugin::RunConfig{}, start, start, std::nullopt).measured_depth_m, 0.0);
  EXPECT_EQ(sensor_md_m(config_with_tie_on_md(std::nullopt, 12.5), 1000.0), 987.5);
}

TEST(SurveyStart, StatedDepthSigmaIsThePipeLengthAids) {
  plugin::RunConfig config;
  EXPECT_FALSE(stated_depth_sigma(config).has_value());
  config.aids.push_back({"zupt", nlohmann::json::object(), "/aids/0"});
  config.aids.push_back({"pipe_length", {{"sigma_random_m", 0.02}}, "/aids/1"});
  const auto sigma = stated_depth_sigma(config);
  ASSERT_TRUE(sigma.has_value());
  EXPECT_EQ(sigma->random_m, 0.02);
  EXPECT_EQ(sigma->scale, 1e-3) << "the plugin's default (docs/config-reference.md)";
}

}  // namespace
}  // namespace stochnav
