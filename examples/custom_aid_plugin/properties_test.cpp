// The plugin's property tests: the suite every stochnav aid must pass (installed with stochnav),
// run on this plugin as the build folder holds it, with aid data that are what the tool at the
// true state measures.
//   ctest --test-dir build     (or build/inclination_survey_properties)

#include <numbers>

#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/testing/aid_properties.hpp"

namespace {

using stochnav::testing::AidCase;
using stochnav::testing::AidProperties;

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// A tool at 30 deg N inclined inclination_deg towards azimuth 45 deg, toolface 30 deg, and the
// survey of that inclination at t = 0 and 1 s.
AidCase survey_case(double inclination_deg, nlohmann::json params) {
  AidCase c{"inclination_survey", std::move(params)};
  c.truth.latitude_rad = 30.0 * kRadPerDeg;
  c.truth.q_nb = stochnav::quaternion_from_mwd(
      {inclination_deg * kRadPerDeg, 30.0 * kRadPerDeg, 45.0 * kRadPerDeg});
  c.data = stochnav::plugin::AidData("survey.csv", {"t", "inc"},
                                     {{0.0, 1.0}, {inclination_deg, inclination_deg}});
  c.search_path = {PLUGIN_DIR};
  return c;
}

INSTANTIATE_TEST_SUITE_P(InclinationSurvey, AidProperties,
                         ::testing::Values(survey_case(60.0, {{"column", "inc"}}),
                                           survey_case(3.0, {{"column", "inc"},
                                                             {"sigma_deg", 0.05}})),
                         stochnav::testing::aid_case_name);

}  // namespace
