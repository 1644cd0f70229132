#include "drilling_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stochnav::scenario_detail {
namespace {

constexpr double kShortestSpan = 1e-3;  // s

// One segment per stand from rop_mps and rotation_radps (the form before stand patterns).
std::vector<StandSegmentConfig> effective_pattern(const DrillingConfig& config) {
  if (!config.stand_pattern.empty()) return config.stand_pattern;
  StandSegmentConfig single;
  single.mode = DrillMode::kRotate;
  single.length_m = config.stand_length_m;
  single.rop_mps = config.rop_mps;
  single.rotation_radps = config.rotation_radps;
  return {single};
}

// tau in [lo, hi] where the profile position is `position` (it is increasing there).
double invert_profile(double position, double lo, double hi, double duration, double ramp) {
  for (int i = 0; i < 200 && hi - lo > 0.0; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (ramp_profile(mid, duration, ramp).position < position ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The time at which the drill segment reaches depth md (clamped to the segment's profile).
double time_at_depth(const DrillSegment& s, double md, double ramp) {
  const double position = (md - s.start_md_m) / s.rop_mps;
  const double total = ramp > 0.0 ? s.profile_s - ramp : s.profile_s;
  if (position <= 0.0) return s.start_s;
  if (position >= total) return s.start_s + s.profile_s;
  if (ramp <= 0.0) return s.start_s + position;
  if (position < 0.5 * ramp)
    return s.start_s + invert_profile(position, 0.0, ramp, s.profile_s, ramp);
  if (position > total - 0.5 * ramp) {
    return s.start_s + invert_profile(position, s.profile_s - ramp, s.profile_s, s.profile_s, ramp);
  }
  return s.start_s + ramp + (position - 0.5 * ramp);
}

}  // namespace

RampProfile ramp_profile(double tau, double duration, double ramp) {
  RampProfile p;
  if (ramp <= 0.0) {
    p.position = tau;
    p.speed = 1.0;
    p.acceleration = 0.0;
    return p;
  }
  const double from_end = duration - tau;
  if (tau < ramp) {
    const double arg = std::numbers::pi * tau / ramp;
    p.position = 0.5 * tau - ramp / (2.0 * std::numbers::pi) * std::sin(arg);
    p.speed = 0.5 * (1.0 - std::cos(arg));
    p.acceleration = 0.5 * std::numbers::pi / ramp * std::sin(arg);
  } else if (from_end < ramp) {
    const double arg = std::numbers::pi * from_end / ramp;
    const double total = duration - ramp;  // unit-speed length: duration - 2 ramp + 2 ramp / 2
    p.position = total - (0.5 * from_end - ramp / (2.0 * std::numbers::pi) * std::sin(arg));
    p.speed = 0.5 * (1.0 - std::cos(arg));
    p.acceleration = -0.5 * std::numbers::pi / ramp * std::sin(arg);
  } else {
    p.position = 0.5 * ramp + (tau - ramp);
    p.speed = 1.0;
    p.acceleration = 0.0;
  }
  return p;
}

DrillSchedule drill_schedule(const DrillingConfig& config) {
  DrillSchedule schedule;
  auto& segments = schedule.segments;
  auto& breakpoints = schedule.breakpoints;
  const std::vector<StandSegmentConfig> pattern = effective_pattern(config);
  for (const auto& p : pattern) {
    schedule.max_rotation_radps = std::max(schedule.max_rotation_radps, std::abs(p.rotation_radps));
  }
  const int pattern_index = config.stand_pattern.empty() ? -1 : 0;
  double t = 0.0;
  double md = config.start_md_m;
  double toolface = config.initial_toolface_rad;
  const double end = config.duration_s;
  if (config.initial_static_s > 0.0) {
    DrillSegment s;
    s.end_s = std::min(config.initial_static_s, end);
    s.start_md_m = md;
    s.start_toolface_rad = toolface;
    segments.push_back(s);
    t = s.end_s;
  }
  while (t < end) {
    for (std::size_t j = 0; j < pattern.size() && t < end; ++j) {
      const StandSegmentConfig& p = pattern[j];
      const int index = pattern_index < 0 ? -1 : static_cast<int>(j);
      if (p.mode == DrillMode::kSlide) {
        DrillSegment orient;
        orient.start_s = t;
        orient.end_s = std::min(t + config.orient_s, end);
        orient.kind = SegmentKind::kOrient;
        orient.start_md_m = md;
        orient.start_toolface_rad = toolface;
        orient.profile_s = config.orient_s;
        orient.toolface_change_rad =
            std::remainder(p.toolface_rad - toolface, 2.0 * std::numbers::pi);
        orient.pattern_index = index;
        segments.push_back(orient);
        breakpoints.push_back(t);
        schedule.orients = true;
        t += config.orient_s;
        toolface += orient.toolface_change_rad;
        if (t >= end) break;
      }
      const double duration = p.length_m / p.rop_mps + config.ramp_s;
      DrillSegment drill;
      drill.start_s = t;
      drill.end_s = std::min(t + duration, end);
      drill.kind = SegmentKind::kDrill;
      drill.start_md_m = md;
      drill.start_toolface_rad = toolface;
      drill.rop_mps = p.rop_mps;
      drill.rotation_radps = p.rotation_radps;
      drill.profile_s = duration;
      drill.pattern_index = index;
      segments.push_back(drill);
      breakpoints.push_back(t);
      breakpoints.push_back(t + config.ramp_s);
      breakpoints.push_back(t + duration - config.ramp_s);
      t += duration;
      md += p.length_m;
      toolface += p.rotation_radps / p.rop_mps * p.length_m;
    }
    if (t >= end) break;
    DrillSegment connection;
    connection.start_s = t;
    connection.end_s = std::min(t + config.connection_s, end);
    connection.kind = SegmentKind::kConnection;
    connection.start_md_m = md;
    connection.start_toolface_rad = toolface;
    segments.push_back(connection);
    breakpoints.push_back(t);
    t += config.connection_s;
  }
  return schedule;
}

std::vector<VibrationEpisodeConfig> md_episode_spans(const DrillingConfig& config,
                                                     const std::vector<DrillSegment>& segments) {
  std::vector<VibrationEpisodeConfig> spans;
  for (const auto& episode : config.md_vibration_episodes) {
    bool joinable = false;  // the previous segment was drilled and ended in a span
    for (const auto& s : segments) {
      if (s.kind != SegmentKind::kDrill) {
        joinable = false;
        continue;
      }
      const double a = std::min(time_at_depth(s, episode.start_md_m, config.ramp_s), s.end_s);
      const double b = std::min(time_at_depth(s, episode.end_md_m, config.ramp_s), s.end_s);
      if (!(b > a)) {
        joinable = false;
        continue;
      }
      if (joinable && a == s.start_s) {
        spans.back().end_s = b;
      } else {
        spans.push_back({a, b, episode.axial_amplitude_mps2, episode.frequency_hz});
      }
      joinable = b == s.end_s;
    }
  }
  spans.erase(std::remove_if(spans.begin(), spans.end(),
                             [](const VibrationEpisodeConfig& e) {
                               return e.end_s - e.start_s < kShortestSpan;
                             }),
              spans.end());
  std::sort(spans.begin(), spans.end(),
            [](const auto& x, const auto& y) { return x.start_s < y.start_s; });
  return spans;
}

}  // namespace stochnav::scenario_detail
