// Drilling: a well path (scenario/well_path.hpp: vertical / circular build / hold, or general
// sections of constant build and turn rates), drilled stand by stand (drilling_schedule.hpp:
// segments of rotary drilling or sliding at their own ROP and rotation, raised-cosine ramps of
// ROP and rotation, raised-cosine toolface orientation before each slide), pipe connections
// (stationary), and axial vibration episodes by time or by drilled depth (the tool oscillates
// along the hole).
//
// Truth: the path is parameterised by measured depth md in a local-level frame at the wellhead
// (E, N, U offsets p(md)); the tool sits at md(t) = md_drill(t) + x_vib(t). The geodetic position
// is lat = lat0 + p_N / (R_M0 + h0), lon = lon0 + p_E / ((R_N0 + h0) cos lat0), h = h0 + p_U, and
// v_n, a_n are its exact time derivatives (so horizontal path length differs from md by
// (R + h) / (R + h0) - 1 < 5e-4 at 3 km depth). With the tangent t(I, A), the high side h and
// r = t x h = (cos A, -sin A, 0): dp/dt = t md', d2p/dt2 = t md'' + (I' h + A' sin I r) md'^2
// (I', A' the build and turn rates per metre). Attitude: inclination and azimuth of the path at
// md(t), toolface TF = initial toolface + integral of the rotation rate (+ orientation changes);
// omega_nb_b = (I' md' sin TF - A' md' sin I cos TF, I' md' cos TF + A' md' sin I sin TF,
// TF' + A' md' cos I) (ins/mwd_attitude.hpp mwd_angular_velocity_b).
//
// Increments: Gauss-Legendre quadrature (3 nodes) on sub-intervals split at every ramp, segment,
// orientation and episode boundary and short enough that the fastest local rate (rotation,
// vibration, ramps, orientation) turns by at most 0.15 rad, which bounds the relative error by
// ~1e-11. Earth rate, radii and transport-rate factors are taken once per sub-interval at its
// midpoint (they change by < 1e-9 relative across it and their linear change integrates
// exactly); gravity follows each node's height through its gradient. Not split: the curvature
// steps of the path (kickoff, end of build, section boundaries, all in md); the single interval
// that crosses one carries an error of about |kappa| ROP dt in its angle increment (~1e-9 rad).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "motion_models.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"

namespace stochnav::scenario_detail {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMaxTurnPerSubinterval = 0.15;  // rad

struct AxialVibration {
  double displacement = 0.0;
  double velocity = 0.0;
  double acceleration = 0.0;
};

// x(t) = -(A / w^2) e(tau) sin(w tau), e a raised-cosine envelope rising and falling over
// `ramp` (at most half the episode), so x and its first two derivatives are continuous.
AxialVibration axial_vibration(const VibrationEpisodeConfig& episode, double ramp, double t_s) {
  AxialVibration v;
  if (t_s <= episode.start_s || t_s >= episode.end_s) return v;
  const double tau = t_s - episode.start_s;
  const double length = episode.end_s - episode.start_s;
  const double w = 2.0 * kPi * episode.frequency_hz;
  double e = 1.0;
  double de = 0.0;
  double d2e = 0.0;
  const double from_edge = std::min(tau, length - tau);
  if (from_edge < ramp) {
    const double sign = tau < length - tau ? 1.0 : -1.0;
    const double arg = kPi * from_edge / ramp;
    e = 0.5 * (1.0 - std::cos(arg));
    de = sign * 0.5 * kPi / ramp * std::sin(arg);
    d2e = 0.5 * kPi * kPi / (ramp * ramp) * std::cos(arg);
  }
  const double k = -episode.axial_amplitude_mps2 / (w * w);
  const double s = std::sin(w * tau);
  const double c = std::cos(w * tau);
  v.displacement = k * e * s;
  v.velocity = k * (de * s + e * w * c);
  v.acceleration = k * (d2e * s + 2.0 * de * w * c - e * w * w * s);
  return v;
}

double episode_ramp(const VibrationEpisodeConfig& episode, double ramp_s) {
  return std::min(ramp_s, 0.5 * (episode.end_s - episode.start_s));
}

}  // namespace

DrillingMotion::DrillingMotion(const ScenarioConfig& config)
    : config_(*config.drilling), site_(config.site), path_(config_.well) {
  const EarthRadii radii = earth_radii(site_.latitude_rad);
  meridian0_plus_h_ = radii.meridian_m + site_.height_m;
  transverse0_plus_h_cos_ = (radii.transverse_m + site_.height_m) * std::cos(site_.latitude_rad);
  schedule_ = drill_schedule(config_);
  const double end = config_.duration_s;

  episodes_ = config_.vibration_episodes;
  time_episodes_ = episodes_.size();
  for (const auto& span : md_episode_spans(config_, schedule_.segments)) episodes_.push_back(span);
  for (std::size_t i = 1; i < episodes_.size(); ++i) {
    if (i != time_episodes_ && episodes_[i].start_s < episodes_[i - 1].end_s) {
      episode_groups_disjoint_ = false;  // (validated configurations never are)
    }
  }
  auto& breakpoints = schedule_.breakpoints;
  for (const auto& episode : episodes_) {
    const double ramp = episode_ramp(episode, config_.ramp_s);
    for (double b :
         {episode.start_s, episode.start_s + ramp, episode.end_s - ramp, episode.end_s}) {
      breakpoints.push_back(b);
    }
  }
  std::sort(breakpoints.begin(), breakpoints.end());

  // Phases: the segments cut by the vibration episodes.
  std::vector<double> cuts = {0.0, end};
  for (const auto& s : schedule_.segments) cuts.push_back(s.start_s);
  for (const auto& e : episodes_) {
    cuts.push_back(std::clamp(e.start_s, 0.0, end));
    cuts.push_back(std::clamp(e.end_s, 0.0, end));
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i];
    const double b = cuts[i + 1];
    const double mid = 0.5 * (a + b);
    bool vibrating = false;
    for (const auto& e : episodes_) {
      vibrating = vibrating || (mid >= e.start_s && mid < e.end_s);
    }
    const DrillSegment& segment = segment_at(mid);
    const bool still =
        segment.kind == SegmentKind::kStatic || segment.kind == SegmentKind::kConnection;
    ScenarioPhase phase;
    phase.start_s = a;
    phase.end_s = b;
    const NoiseScales* scales = &config_.static_noise;
    if (vibrating) {
      phase.name = "vibration";
      scales = &config_.vibration_noise;
    } else if (!still) {
      phase.name = segment.kind == SegmentKind::kOrient ? "orienting" : "drilling";
      scales = &config_.drilling_noise;
    } else {
      phase.name = segment.kind == SegmentKind::kStatic ? "static" : "connection";
    }
    phase.stationary = !vibrating && still;
    phase.gyro_noise_scale = scales->gyro;
    phase.accel_noise_scale = scales->accel;
    if (!phases_.empty() && phases_.back().name == phase.name) {
      phases_.back().end_s = b;  // merge equal neighbours
    } else {
      phases_.push_back(phase);
    }
  }
  segment_cursor_ = 0;
}

const DrillSegment& DrillingMotion::segment_at(double t_s) const {
  const auto& segments = schedule_.segments;
  std::size_t i = std::min(segment_cursor_, segments.size() - 1);
  if (t_s >= segments[i].start_s && t_s < segments[i].end_s) return segments[i];
  if (i + 1 < segments.size() && t_s >= segments[i + 1].start_s && t_s < segments[i + 1].end_s) {
    segment_cursor_ = i + 1;
    return segments[i + 1];
  }
  const auto it = std::upper_bound(segments.begin(), segments.end(), t_s,
                                   [](double t, const DrillSegment& s) { return t < s.start_s; });
  i = it == segments.begin() ? 0 : static_cast<std::size_t>(it - segments.begin()) - 1;
  segment_cursor_ = i;
  return segments[i];
}

template <typename F>
void DrillingMotion::for_episodes_in(double t0_s, double t1_s, F&& f) const {
  const auto overlaps = [&](const VibrationEpisodeConfig& e) {
    return t1_s > e.start_s && t0_s < e.end_s;
  };
  const auto groups = {std::pair<std::size_t, std::size_t>{0, time_episodes_},
                       std::pair<std::size_t, std::size_t>{time_episodes_, episodes_.size()}};
  for (const auto& [first, last] : groups) {
    const auto begin = episodes_.begin() + static_cast<std::ptrdiff_t>(first);
    const auto end = episodes_.begin() + static_cast<std::ptrdiff_t>(last);
    if (!episode_groups_disjoint_) {
      for (auto it = begin; it != end; ++it) {
        if (overlaps(*it)) f(*it);
      }
      continue;
    }
    // Ascending and disjoint: the ends ascend too; start at the first ending after t0_s.
    auto it = std::upper_bound(
        begin, end, t0_s, [](double t, const VibrationEpisodeConfig& e) { return t < e.end_s; });
    for (; it != end && it->start_s < t1_s; ++it) {
      if (overlaps(*it)) f(*it);
    }
  }
}

DrillingMotion::EarthFactors DrillingMotion::earth_factors(double latitude_rad, double height_m) {
  EarthFactors f;
  f.sin_lat = std::sin(latitude_rad);
  f.cos_lat = std::cos(latitude_rad);
  f.height_m = height_m;
  f.radii = earth_radii(latitude_rad);
  f.radii_rate = earth_radii_derivative(latitude_rad);
  f.omega_ie_n = earth_rate_n(latitude_rad);
  f.gravity_mps2 = normal_gravity(latitude_rad, height_m);
  f.gravity_per_height = normal_gravity_height_gradient(latitude_rad, height_m);
  return f;
}

DrillingMotion::Kinematics DrillingMotion::kinematics(double t_s) const {
  return kinematics(t_s, nullptr);
}

DrillingMotion::Kinematics DrillingMotion::kinematics(double t_s, const EarthFactors* earth,
                                                      EarthFactors* computed) const {
  const DrillSegment& segment = segment_at(t_s);
  double md = segment.start_md_m;
  double md_rate = 0.0;
  double md_acceleration = 0.0;
  double toolface = segment.start_toolface_rad;
  double toolface_rate = 0.0;
  Kinematics k;
  if (segment.kind == SegmentKind::kDrill) {
    const RampProfile profile =
        ramp_profile(t_s - segment.start_s, segment.profile_s, config_.ramp_s);
    md += segment.rop_mps * profile.position;
    md_rate = segment.rop_mps * profile.speed;
    md_acceleration = segment.rop_mps * profile.acceleration;
    toolface += segment.rotation_radps * profile.position;
    toolface_rate = segment.rotation_radps * profile.speed;
    k.rop_mps = md_rate;
  } else if (segment.kind == SegmentKind::kOrient) {
    const double arg = kPi * (t_s - segment.start_s) / segment.profile_s;
    toolface += segment.toolface_change_rad * 0.5 * (1.0 - std::cos(arg));
    toolface_rate = segment.toolface_change_rad * 0.5 * kPi / segment.profile_s * std::sin(arg);
  }
  // (An inactive episode would add exact zeros: skipping it changes no bit.)
  for_episodes_in(t_s, t_s, [&](const VibrationEpisodeConfig& episode) {
    const AxialVibration v = axial_vibration(episode, episode_ramp(episode, config_.ramp_s), t_s);
    md += v.displacement;
    md_rate += v.velocity;
    md_acceleration += v.acceleration;
  });
  k.measured_depth_m = md;

  // Path point at md: local offsets p, tangent, high side, inclination, build and turn rates.
  const WellPathPoint point = path_.at(md);
  const double sin_a = std::sin(point.azimuth_rad);
  const double cos_a = std::cos(point.azimuth_rad);
  const double inclination = point.inclination_rad;
  const double curvature = point.build_rate_rad_per_m;
  const double turn = point.turn_rate_rad_per_m;
  const Eigen::Vector3d& p = point.offset_enu_m;
  const double sin_i = std::sin(inclination);
  const double cos_i = std::cos(inclination);
  const Eigen::Vector3d tangent(sin_i * sin_a, sin_i * cos_a, -cos_i);
  const Eigen::Vector3d high_side(cos_i * sin_a, cos_i * cos_a, sin_i);
  const Eigen::Vector3d right(cos_a, -sin_a, 0.0);
  const Eigen::Vector3d p_dot = tangent * md_rate;
  Eigen::Vector3d p_ddot = tangent * md_acceleration + high_side * (curvature * md_rate * md_rate);
  // Only with a turn (without one the sums are skipped: the plane well's numbers are unchanged).
  if (turn != 0.0) p_ddot += right * (sin_i * turn * md_rate * md_rate);

  // Geodetic position and the exact derivatives of v_E, v_N, v_U.
  k.latitude_rad = site_.latitude_rad + p.y() / meridian0_plus_h_;
  k.longitude_rad = site_.longitude_rad + p.x() / transverse0_plus_h_cos_;
  k.height_m = site_.height_m + p.z();
  const EarthFactors own =
      earth == nullptr ? earth_factors(k.latitude_rad, k.height_m) : EarthFactors{};
  const EarthFactors& e = earth == nullptr ? own : *earth;
  if (computed != nullptr && earth == nullptr) *computed = own;
  const EarthRadii& radii = e.radii;
  const EarthRadii& radii_rate = e.radii_rate;
  const double lat_rate = p_dot.y() / meridian0_plus_h_;
  const double h_rate = p_dot.z();
  const double sin_lat = e.sin_lat;
  const double cos_lat = e.cos_lat;
  const double d_east = (radii.transverse_m + k.height_m) * cos_lat / transverse0_plus_h_cos_;
  const double d_north = (radii.meridian_m + k.height_m) / meridian0_plus_h_;
  const double d_east_rate = ((radii_rate.transverse_m * lat_rate + h_rate) * cos_lat -
                              (radii.transverse_m + k.height_m) * sin_lat * lat_rate) /
                             transverse0_plus_h_cos_;
  const double d_north_rate = (radii_rate.meridian_m * lat_rate + h_rate) / meridian0_plus_h_;
  k.v_n = Eigen::Vector3d(d_east * p_dot.x(), d_north * p_dot.y(), p_dot.z());
  k.a_n = Eigen::Vector3d(d_east_rate * p_dot.x() + d_east * p_ddot.x(),
                          d_north_rate * p_dot.y() + d_north * p_ddot.y(), p_ddot.z());

  // Attitude: C_nb = R_z(-A) R_x(I) C_0 R_z(TF) (ins/mwd_attitude.hpp), written with the
  // tangent z_b, the high side h and r = z_b x h = (cos A, -sin A, 0):
  // x_b = cos TF h + sin TF r, y_b = cos TF r - sin TF h; omega_nb_b = (dI sin TF, dI cos TF, dTF).
  // With a turn: omega_nb_b gains A' md' (-sin I cos TF, sin I sin TF, cos I).
  const double sin_tf = std::sin(toolface);
  const double cos_tf = std::cos(toolface);
  k.C_nb.col(0) = cos_tf * high_side + sin_tf * right;
  k.C_nb.col(1) = cos_tf * right - sin_tf * high_side;
  k.C_nb.col(2) = tangent;
  const double inclination_rate = curvature * md_rate;
  k.omega_nb_b =
      Eigen::Vector3d(inclination_rate * sin_tf, inclination_rate * cos_tf, toolface_rate);
  if (turn != 0.0) {
    const double azimuth_rate = turn * md_rate;
    k.omega_nb_b += azimuth_rate * Eigen::Vector3d(-sin_i * cos_tf, sin_i * sin_tf, cos_i);
  }
  return k;
}

TruthSample DrillingMotion::truth(double t_s) {
  const Kinematics k = kinematics(t_s);
  TruthSample truth;
  truth.t_s = t_s;
  truth.latitude_rad = k.latitude_rad;
  truth.longitude_rad = k.longitude_rad;
  truth.height_m = k.height_m;
  truth.v_n = k.v_n;
  truth.C_nb = k.C_nb;
  truth.measured_depth_m = k.measured_depth_m;
  truth.rop_mps = k.rop_mps;
  const auto it = std::upper_bound(phases_.begin(), phases_.end(), t_s,
                                   [](double t, const ScenarioPhase& p) { return t < p.start_s; });
  truth.stationary = it != phases_.begin() && std::prev(it)->stationary;
  return truth;
}

double DrillingMotion::local_rate_bound(double t0_s, double t1_s) const {
  double rate = schedule_.max_rotation_radps + (config_.ramp_s > 0.0 ? kPi / config_.ramp_s : 0.0);
  // Orientation: toolface rate up to pi |change| / (2 orient_s) <= pi^2 / (2 orient_s).
  if (schedule_.orients) rate += (kPi + 0.5 * kPi * kPi) / config_.orient_s;
  for_episodes_in(t0_s, t1_s, [&](const VibrationEpisodeConfig& e) {
    rate += 2.0 * kPi * e.frequency_hz + kPi / episode_ramp(e, config_.ramp_s);
  });
  return rate;
}

void DrillingMotion::integrate(double t0_s, double t1_s, Eigen::Vector3d& delta_theta_b,
                               Eigen::Vector3d& delta_v_b) {
  static constexpr double kNode = 0.7745966692414834;  // sqrt(3/5)
  static constexpr double kWeights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  static constexpr double kNodes[3] = {-kNode, 0.0, kNode};
  delta_theta_b.setZero();
  delta_v_b.setZero();
  const std::vector<double>& breakpoints = schedule_.breakpoints;
  while (breakpoint_cursor_ < breakpoints.size() && breakpoints[breakpoint_cursor_] <= t0_s) {
    ++breakpoint_cursor_;
  }
  if (breakpoint_cursor_ > 0 && breakpoints[breakpoint_cursor_ - 1] > t0_s) {
    breakpoint_cursor_ = static_cast<std::size_t>(
        std::upper_bound(breakpoints.begin(), breakpoints.end(), t0_s) - breakpoints.begin());
  }
  double a = t0_s;
  std::size_t next = breakpoint_cursor_;
  while (a < t1_s) {
    const double b =
        next < breakpoints.size() && breakpoints[next] < t1_s ? breakpoints[next] : t1_s;
    ++next;
    if (b <= a) continue;
    const int pieces = std::max(
        1, static_cast<int>(std::ceil(local_rate_bound(a, b) * (b - a) / kMaxTurnPerSubinterval)));
    const double h = (b - a) / pieces;
    for (int piece = 0; piece < pieces; ++piece) {
      const double mid = a + (piece + 0.5) * h;
      EarthFactors earth;
      const Kinematics center = kinematics(mid, nullptr, &earth);
      const double inverse_meridian = 1.0 / (earth.radii.meridian_m + earth.height_m);
      const double inverse_transverse = 1.0 / (earth.radii.transverse_m + earth.height_m);
      const double tan_lat = earth.sin_lat / earth.cos_lat;
      for (int node = 0; node < 3; ++node) {
        const Kinematics k = node == 1 ? center : kinematics(mid + 0.5 * h * kNodes[node], &earth);
        const Eigen::Vector3d omega_en_n(-k.v_n.y() * inverse_meridian,
                                         k.v_n.x() * inverse_transverse,
                                         k.v_n.x() * tan_lat * inverse_transverse);
        // Gravity follows the node's height (vibration moves it by millimetres).
        const Eigen::Vector3d g_n(
            0.0, 0.0,
            -(earth.gravity_mps2 + earth.gravity_per_height * (k.height_m - earth.height_m)));
        const Eigen::Matrix3d C_bn = k.C_nb.transpose();
        const Eigen::Vector3d omega_ib_b = k.omega_nb_b + C_bn * (earth.omega_ie_n + omega_en_n);
        const Eigen::Vector3d f_b =
            C_bn * (k.a_n + (2.0 * earth.omega_ie_n + omega_en_n).cross(k.v_n) - g_n);
        const double w = 0.5 * h * kWeights[node];
        delta_theta_b += w * omega_ib_b;
        delta_v_b += w * f_b;
      }
    }
    a = b;
  }
}

nlohmann::json DrillingMotion::describe() const {
  // The original form unless a feature beyond it is used (shipped scenarios are unchanged).
  const bool extended =
      !config_.stand_pattern.empty() || !path_.plane() || episodes_.size() > time_episodes_;
  const auto kind_name = [](const DrillSegment& s) {
    switch (s.kind) {
      case SegmentKind::kDrill:
        return "drilling";
      case SegmentKind::kOrient:
        return "orienting";
      case SegmentKind::kConnection:
        return "connection";
      case SegmentKind::kStatic:
        break;
    }
    return "static";
  };
  nlohmann::json stands = nlohmann::json::array();
  for (const auto& s : schedule_.segments) {
    nlohmann::json entry = {{"start_s", s.start_s},
                            {"end_s", s.end_s},
                            {"kind", kind_name(s)},
                            {"start_md_m", s.start_md_m},
                            {"start_toolface_rad", s.start_toolface_rad}};
    if (extended && s.kind == SegmentKind::kDrill) {
      entry["rop_mps"] = s.rop_mps;
      entry["rotation_radps"] = s.rotation_radps;
    }
    if (s.kind == SegmentKind::kOrient) entry["toolface_change_rad"] = s.toolface_change_rad;
    if (s.pattern_index >= 0) entry["pattern_index"] = s.pattern_index;
    stands.push_back(std::move(entry));
  }
  if (!extended) {
    return {{"model",
             "drilling: well path vertical / circular build / hold in the plane of the well "
             "azimuth, parameterised by measured depth; stands drilled with raised-cosine ramps "
             "of ROP and rotation; axial vibration x = -(A/w^2) e(tau) sin(w tau)"},
            {"build_end_md_m", config_.well.kickoff_md_m + config_.well.target_inclination_rad /
                                                               config_.well.build_rate_rad_per_m},
            {"drill_segment_s", config_.stand_length_m / config_.rop_mps + config_.ramp_s},
            {"segments", std::move(stands)}};
  }
  nlohmann::json sections = nlohmann::json::array();
  for (double md : path_.section_start_md_m()) {
    const WellPathPoint point = path_.at(md);
    sections.push_back(
        {{"start_md_m", md},
         {"inclination_rad", point.inclination_rad},
         {"azimuth_rad", point.azimuth_rad},
         {"offset_enu_m", {point.offset_enu_m.x(), point.offset_enu_m.y(), point.offset_enu_m.z()}},
         {"build_rate_rad_per_m", point.build_rate_rad_per_m},
         {"turn_rate_rad_per_m", point.turn_rate_rad_per_m}});
  }
  nlohmann::json spans = nlohmann::json::array();
  for (std::size_t i = time_episodes_; i < episodes_.size(); ++i) {
    spans.push_back({{"start_s", episodes_[i].start_s},
                     {"end_s", episodes_[i].end_s},
                     {"axial_mps2", episodes_[i].axial_amplitude_mps2},
                     {"frequency_hz", episodes_[i].frequency_hz}});
  }
  nlohmann::json out = {
      {"model",
       "drilling: well path of sections with constant build and turn rates in measured depth "
       "(inclination and azimuth linear in md, closed-form positions), or vertical / build / "
       "hold; stands drilled segment by segment (rotate or slide) with raised-cosine ramps of "
       "ROP and rotation, a raised-cosine toolface orientation (depth still) before each slide; "
       "axial vibration x = -(A/w^2) e(tau) sin(w tau) by time or while drilling a depth range"},
      {"segments", std::move(stands)},
      {"md_vibration_spans", std::move(spans)}};
  if (path_.plane()) {
    out["build_end_md_m"] = config_.well.kickoff_md_m +
                            config_.well.target_inclination_rad / config_.well.build_rate_rad_per_m;
  } else {
    out["well_sections"] = std::move(sections);
  }
  return out;
}

}  // namespace stochnav::scenario_detail
