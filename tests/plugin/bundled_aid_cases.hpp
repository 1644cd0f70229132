#pragma once
// The bundled aids at one epoch each, with aid data that are what a tool at the true state
// measures (plugin/aid_checks.hpp): the cases of the aid property suite and of the aid checks.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "stochnav/core/angles.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/testing/aid_case.hpp"

namespace stochnav::plugin::bundled_aid_cases {

inline constexpr double kLatitudeDeg = 30.0;
inline constexpr double kLongitudeDeg = 100.0;
inline constexpr double kHeightM = 50.0;

/// A tool at 30 deg N, 100 deg E, 50 m, inclined 60 deg towards azimuth 45 deg, toolface 30
/// deg, moving along its axis at speed_mps.
inline NavState inclined_tool(double speed_mps) {
  NavState state;
  state.latitude_rad = kLatitudeDeg * kRadPerDeg;
  state.longitude_rad = kLongitudeDeg * kRadPerDeg;
  state.height_m = kHeightM;
  state.q_nb = quaternion_from_mwd({60.0 * kRadPerDeg, 30.0 * kRadPerDeg, 45.0 * kRadPerDeg});
  state.v_n = state.q_nb * Eigen::Vector3d::UnitZ() * speed_mps;
  return state;
}

inline constexpr double kRopMph = 20.0;
inline constexpr double kDrillingSpeedMps = kRopMph / 3600.0;

inline stochnav::testing::AidCase bundled(std::string type, nlohmann::json params) {
  stochnav::testing::AidCase c{std::move(type), std::move(params)};
  c.truth = inclined_tool(0.0);
  c.search_path = {bundled_plugin_dir()};
  return c;
}

/// Every bundled aid, each source or variant once.
inline std::vector<stochnav::testing::AidCase> all() {
  std::vector<stochnav::testing::AidCase> cases;
  // At rest on the site (the default site is the run's initial position, the truth).
  cases.push_back(bundled("static_position", nlohmann::json::object()));
  cases.push_back(bundled("static_position", {{"zero_velocity", false}, {"rate_hz", 2.0}}));

  auto zupt = bundled("zupt", {{"sigma_velocity_mps", 0.002}});
  zupt.data = AidData("aids.csv", {"t", "zupt"}, {{0.0, 1.0, 2.0}, {1.0, 1.0, 0.0}});
  cases.push_back(zupt);
  cases.push_back(bundled("zupt", {{"source", "detector"}}));  // at rest: the detector fires

  // Drilling along the axis at 20 m/h, the rig's rate on every row.
  auto rop = bundled("rop", {{"sigma_displacement_m", 0.01}});
  rop.truth = inclined_tool(kDrillingSpeedMps);
  rop.data = AidData("aids.csv", {"t", "rop_mph"}, {{0.0, 1.0, 2.0}, {kRopMph, kRopMph, kRopMph}});
  rop.interval_s = 1.0;
  cases.push_back(rop);

  auto pipe = bundled("pipe_length", {{"sigma_random_m", 0.02}});
  pipe.truth = inclined_tool(kDrillingSpeedMps);
  pipe.data = AidData(
      "aids.csv", {"t", "measured_depth_m"},
      {{0.0, 1.0, 2.0}, {1000.0, 1000.0 + kDrillingSpeedMps, 1000.0 + 2.0 * kDrillingSpeedMps}});
  pipe.interval_s = 1.0;
  cases.push_back(pipe);

  // A fix at the true position on the second row only.
  auto fix = bundled("position_fix", nlohmann::json::object());
  fix.data = AidData("aids.csv",
                     {"t", "fix_latitude_deg", "fix_longitude_deg", "fix_height_m",
                      "fix_sigma_east_m", "fix_sigma_north_m", "fix_sigma_up_m"},
                     {{0.0, 1.0},
                      {0.0, kLatitudeDeg},
                      {0.0, kLongitudeDeg},
                      {0.0, kHeightM},
                      {0.0, 1.5},
                      {0.0, 1.0},
                      {0.0, 3.0}});
  cases.push_back(fix);
  return cases;
}

}  // namespace stochnav::plugin::bundled_aid_cases
