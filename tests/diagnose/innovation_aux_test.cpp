// diagnose --run --aux: innovations that drift with a temperature channel are reported; white
// innovations are not.

#include "stochnav/diagnose/innovation_aux.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "stochnav/sim/normal_generator.hpp"

namespace stochnav {
namespace {

// 1-Hz updates of a two-component aid over 3600 s; u = white + slope * (temperature - 25).
std::vector<AidInnovations> innovations(double slope, const TimedChannel& temperature,
                                        std::uint64_t seed) {
  NormalGenerator normal(seed);
  AidInnovations aid;
  aid.aid_index = 0;
  aid.type = "static_position";
  for (int k = 0; k < 3600; ++k) {
    InnovationSample s;
    s.t_s = k;
    const double drift = slope * (temperature.values[static_cast<std::size_t>(k)] - 25.0);
    s.z = {0.1 * (normal() + drift), 0.1 * normal()};
    s.sigma = {0.1, 0.1};
    aid.samples.push_back(s);
  }
  return {aid};
}

TimedChannel temperature() {
  TimedChannel channel{"temperature_c", 0.0, 1.0, {}};
  for (int k = 0; k < 3600; ++k) {
    channel.values.push_back(25.0 + 10.0 * k / 3600.0 +
                             2.0 * std::sin(2.0 * std::numbers::pi * k / 1800.0));
  }
  return channel;
}

InnovationAnalysis names_only() {
  InnovationAnalysis analysis;
  AidAnalysis aid;
  aid.components.resize(2);
  aid.components[0].name = "position N (m)";
  aid.components[1].name = "position E (m)";
  analysis.aids.push_back(aid);
  return analysis;
}

TEST(InnovationAux, DriftWithTemperatureIsReportedOnItsComponent) {
  const TimedChannel channel = temperature();
  int found = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto findings =
        innovation_aux_findings(innovations(0.3, channel, seed), names_only(), {channel}, 0.01);
    if (findings.size() == 1 && findings[0].component == "position N (m)" &&
        findings[0].column == "temperature_c") {
      ++found;
      EXPECT_NEAR(findings[0].slope, 0.3, 4.0 * findings[0].slope_sigma);
    }
  }
  EXPECT_GE(found, 4);
}

TEST(InnovationAux, NoFindingOnWhiteInnovations) {
  const TimedChannel channel = temperature();
  int alarms = 0;
  for (std::uint64_t seed = 11; seed <= 30; ++seed) {
    alarms += static_cast<int>(
        innovation_aux_findings(innovations(0.0, channel, seed), names_only(), {channel}, 0.01)
            .size());
  }
  EXPECT_LE(alarms, 1);
}

}  // namespace
}  // namespace stochnav
