#pragma once
// The time schedule of a drilling scenario (private to the scenario domain): alignment, stands
// drilled segment by segment (scenario_config.hpp stand_pattern; without it one segment per
// stand), orientation pauses before slide segments, connections; and the time spans of the
// depth-tied vibration episodes. Times in s, depths in m, angles in rad.

#include <vector>

#include "stochnav/scenario/scenario_config.hpp"

namespace stochnav::scenario_detail {

enum class SegmentKind { kStatic, kConnection, kDrill, kOrient };

struct DrillSegment {
  double start_s = 0.0;
  double end_s = 0.0;  // cut at the scenario end
  SegmentKind kind = SegmentKind::kStatic;
  double start_md_m = 0.0;
  double start_toolface_rad = 0.0;
  // kDrill: md = start + rop_mps * position(tau), toolface = start + rotation_radps *
  // position(tau), position the unit-speed raised-cosine ramp profile over profile_s.
  double rop_mps = 0.0;
  double rotation_radps = 0.0;
  double profile_s = 0.0;  // kDrill: length / rop + ramp; kOrient: the pause (s)
  // kOrient: toolface = start + change (1 - cos(pi tau / profile_s)) / 2, md still.
  double toolface_change_rad = 0.0;
  int pattern_index = -1;  // index in stand_pattern (-1: no pattern)
};

struct DrillSchedule {
  std::vector<DrillSegment> segments;  // in time order, covering [0, duration_s)
  std::vector<double> breakpoints;     // ascending, where the motion is not smooth
  double max_rotation_radps = 0.0;     // largest |rotation rate| of any drilled segment
  bool orients = false;                // some segment is an orientation pause
};

/// Unit-speed raised-cosine profile at tau in [0, duration] with ramps of `ramp` (s) at both
/// ends (ramp 0: no ramp): position (s of unit speed), speed (1), acceleration (1/s).
struct RampProfile {
  double position = 0.0;
  double speed = 0.0;
  double acceleration = 0.0;
};
RampProfile ramp_profile(double tau, double duration, double ramp);

DrillSchedule drill_schedule(const DrillingConfig& config);

/// The time episodes the depth-tied episodes give on this schedule: per episode, the spans of
/// drilling (kDrill segments; adjacent segments joined) during which the drilled depth (without
/// vibration) is in [start_md_m, end_md_m]; spans under 1 ms are dropped. Sorted by start.
std::vector<VibrationEpisodeConfig> md_episode_spans(const DrillingConfig& config,
                                                     const std::vector<DrillSegment>& segments);

}  // namespace stochnav::scenario_detail
