#pragma once
// A drilling configuration with every feature of the general path and the stand pattern: a
// hold at 20 deg inclination, then a build-and-turn section; stands of a slide and a rotate
// segment with an orientation pause; a depth-tied vibration episode across two stands.

#include "scenario_builders.hpp"

namespace stochnav::testing {

inline constexpr double kPerThirtyMetres = kDeg / 30.0;
inline constexpr double kSlideToolfaceRad = 40.0 * kDeg;

// drilling_config's rig and sensors (scenario_builders.hpp) on the general path.
inline ScenarioConfig pattern_config(double duration_s) {
  ScenarioConfig config = drilling_config(duration_s);
  DrillingConfig& d = *config.drilling;
  d.well = WellPathConfig{};
  d.well.start_inclination_rad = 20.0 * kDeg;
  d.well.start_azimuth_rad = 80.0 * kDeg;
  d.well.sections = {{45.0, 0.0, 0.0}, {400.0, 8.0 * kPerThirtyMetres, 6.0 * kPerThirtyMetres}};
  d.start_md_m = 40.0;
  d.initial_static_s = 60.0;
  d.orient_s = 20.0;
  d.vibration_episodes.clear();
  StandSegmentConfig slide;
  slide.mode = DrillMode::kSlide;
  slide.length_m = 3.0;
  slide.rop_mps = 60.0 / 3600.0;
  slide.toolface_rad = kSlideToolfaceRad;
  StandSegmentConfig rotate;
  rotate.mode = DrillMode::kRotate;
  rotate.length_m = 6.0;
  rotate.rop_mps = 120.0 / 3600.0;
  rotate.rotation_radps = 3.0 * std::numbers::pi;  // 90 rpm
  d.stand_pattern = {slide, rotate};
  d.md_vibration_episodes = {{50.0, 62.0, 2.0 * kG, 12.0}};
  return config;
}

}  // namespace stochnav::testing
