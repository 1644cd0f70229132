// Vibration table: the tool clamped at a fixed site and attitude, shaken linearly along its X
// axis by sine or random vibration (scenario/vibration.hpp), phase after phase.
//
// Truth: with u = C_nb e_x (the X axis in ENU) and s(t) the table displacement along X (s = 0 at
// t = 0), the position is the site plus s u mapped with the radii at the site, v_n = u ds/dt,
// and C_nb constant (the tool keeps its MWD angles relative to the local level). Increments:
//   dtheta = C_bn [omega_ie_n dt + (d omega_ie_n / ds) int s dt + W u ds]
//   dv     = C_bn [u d(ds/dt) + 2 omega_ie_n x u ds + (W u x u) int (ds/dt)^2 dt
//                  + (0, 0, g0 dt + (dg/ds) int s dt)]
// with W the linear map v_n -> omega_en_n at the site and d/ds the first-order change with the
// displacement's latitude and height. The integrals of s and its derivatives are closed forms;
// velocity steps where a vibration starts or stops land in the interval that holds them, so truth
// and increments stay consistent. Approximated: int (ds/dt)^2 dt by the trapezoid rule (the term
// is below 2e-8 m/s^2, so dv is exact to ~3e-9 relative; dtheta to ~1e-12), and terms of second
// order in the millimetre displacement.

#include <cmath>

#include "motion_models.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/scenario/vibration.hpp"
#include "stochnav/sim/normal_generator.hpp"

namespace stochnav::scenario_detail {

VibrationTableMotion::VibrationTableMotion(const ScenarioConfig& config, std::uint64_t seed)
    : site_(config.site) {
  const VibrationTableConfig& table = *config.vibration_table;
  C_nb_ = dcm_from_mwd(table.attitude);
  axis_n_ = C_nb_.col(0);
  const EarthRadii radii = earth_radii(site_.latitude_rad);
  meridian_plus_h_ = radii.meridian_m + site_.height_m;
  transverse_plus_h_cos_ = (radii.transverse_m + site_.height_m) * std::cos(site_.latitude_rad);
  omega_ie_n_ = earth_rate_n(site_.latitude_rad);
  const Eigen::Vector3d transport_per_axis_speed =
      transport_rate_n(site_.latitude_rad, site_.height_m, axis_n_);
  gravity0_ = normal_gravity(site_.latitude_rad, site_.height_m);
  gravity_per_height_ = normal_gravity_height_gradient(site_.latitude_rad, site_.height_m);
  const Eigen::Matrix3d C_bn = C_nb_.transpose();
  gyro_static_b_ = C_bn * omega_ie_n_;
  gyro_per_displacement_b_ = C_bn * transport_per_axis_speed;
  accel_static_b_ = C_bn * Eigen::Vector3d(0.0, 0.0, gravity0_);
  accel_per_velocity_change_b_ = C_bn * axis_n_;
  accel_per_displacement_b_ = C_bn * (2.0 * omega_ie_n_.cross(axis_n_));
  accel_per_speed_squared_b_ = C_bn * transport_per_axis_speed.cross(axis_n_);
  // Earth rate and gravity follow the displacement's latitude and height to first order:
  // d/ds = d/dlat u_N / (R_M + h) + d/dh u_U.
  const double latitude_per_displacement = axis_n_.y() / meridian_plus_h_;
  const double lat = site_.latitude_rad;
  const Eigen::Vector3d earth_rate_per_latitude(0.0, -wgs84::kEarthRate_radps * std::sin(lat),
                                                wgs84::kEarthRate_radps * std::cos(lat));
  constexpr double kDlat = 1e-6;
  const double gravity_per_latitude =
      (normal_gravity(lat + kDlat, site_.height_m) - normal_gravity(lat - kDlat, site_.height_m)) /
      (2.0 * kDlat);
  gyro_per_displacement_integral_b_ = C_bn * (earth_rate_per_latitude * latitude_per_displacement);
  accel_per_displacement_integral_b_ =
      C_bn * Eigen::Vector3d(0.0, 0.0,
                             gravity_per_height_ * axis_n_.z() +
                                 gravity_per_latitude * latitude_per_displacement);

  double start = 0.0;
  double displacement = 0.0;
  for (std::size_t p = 0; p < table.phases.size(); ++p) {
    const TablePhaseConfig& phase = table.phases[p];
    TablePhase motion;
    motion.start_s = start;
    motion.end_s = start + phase.duration_s;
    motion.start_displacement_m = displacement;
    motion.kind = phase.motion;
    if (phase.motion == TableMotion::kSine) {
      motion.vibration = sine_vibration(phase.sine.frequency_hz, phase.sine.amplitude_mps2);
    } else if (phase.motion == TableMotion::kRandom) {
      motion.vibration =
          random_vibration(phase.random.psd, phase.random.rms_mps2, phase.random.components,
                           derive_stream_seed(seed, 3000 + p));
    }
    if (phase.motion != TableMotion::kStatic) {
      displacement += motion.vibration.evaluate(phase.duration_s).displacement_m;
    }
    table_phases_.push_back(std::move(motion));
    phases_.push_back(
        {phase.name.empty() ? std::string(table_motion_name(phase.motion)) : phase.name, start,
         start + phase.duration_s, phase.motion == TableMotion::kStatic, phase.gyro_noise_scale,
         phase.accel_noise_scale});
    start += phase.duration_s;
  }
  duration_s_ = start;
}

std::size_t VibrationTableMotion::phase_at(double t_s, bool at_end) const {
  // at_end: the phase whose interval (start, end] holds t (a phase's own end point).
  std::size_t p = cursor_ < table_phases_.size() ? cursor_ : 0;
  auto holds = [&](std::size_t q) {
    const auto& ph = table_phases_[q];
    return at_end ? (t_s > ph.start_s && t_s <= ph.end_s) : (t_s >= ph.start_s && t_s < ph.end_s);
  };
  if (holds(p)) return p;
  if (p + 1 < table_phases_.size() && holds(p + 1)) return cursor_ = p + 1;
  for (std::size_t q = 0; q < table_phases_.size(); ++q) {
    if (holds(q)) return cursor_ = q;
  }
  return t_s <= 0.0 ? 0 : table_phases_.size() - 1;
}

VibrationTableMotion::Displacement VibrationTableMotion::displacement_at(std::size_t p,
                                                                         double t_s) {
  if (cache_valid_ && cache_phase_ == p && cache_t_s_ == t_s) return cache_;
  TablePhase& phase = table_phases_[p];
  const double tau = t_s - phase.start_s;
  Displacement d;
  if (phase.kind == TableMotion::kStatic) {
    d.displacement_m = phase.start_displacement_m;
    d.integral_from_phase_start_ms = phase.start_displacement_m * tau;
  } else {
    const auto value = phase.vibration.evaluate_stepping(tau, step_s_);
    d.velocity_mps = value.velocity_mps;
    d.displacement_m = phase.start_displacement_m + value.displacement_m;
    d.integral_from_phase_start_ms =
        phase.start_displacement_m * tau + value.displacement_integral_ms;
  }
  cache_valid_ = true;
  cache_phase_ = p;
  cache_t_s_ = t_s;
  cache_ = d;
  return d;
}

TruthSample VibrationTableMotion::truth(double t_s) {
  const std::size_t p = phase_at(t_s, t_s > 0.0);
  const Displacement d = displacement_at(p, t_s);
  TruthSample truth;
  truth.t_s = t_s;
  truth.latitude_rad = site_.latitude_rad + d.displacement_m * axis_n_.y() / meridian_plus_h_;
  truth.longitude_rad =
      site_.longitude_rad + d.displacement_m * axis_n_.x() / transverse_plus_h_cos_;
  truth.height_m = site_.height_m + d.displacement_m * axis_n_.z();
  truth.v_n = axis_n_ * d.velocity_mps;
  truth.C_nb = C_nb_;
  truth.stationary = phases_[phase_at(t_s, false)].stationary;
  return truth;
}

void VibrationTableMotion::integrate(double t0_s, double t1_s, Eigen::Vector3d& delta_theta_b,
                                     Eigen::Vector3d& delta_v_b) {
  const double dt = t1_s - t0_s;
  if (step_s_ != dt) step_s_ = dt;
  // The state at t0 is the end of the previous interval (the left limit), so a velocity step
  // at a phase start t0 belongs to this interval.
  const std::size_t p0 = phase_at(t0_s, false);
  const std::size_t left = t0_s > 0.0 ? phase_at(t0_s, true) : p0;
  const Displacement start = displacement_at(left, t0_s);
  // Integral of s from p0's start to t0: zero when t0 is p0's start.
  const double integral_before = left == p0 ? start.integral_from_phase_start_ms : 0.0;
  const std::size_t p1 = phase_at(t1_s, true);
  double integral = 0.0;
  for (std::size_t p = p0; p < p1; ++p) {
    // The phase's own closed form up to its end, then the next phase from its start.
    const double integral_end =
        displacement_at(p, table_phases_[p].end_s).integral_from_phase_start_ms;
    integral += integral_end - (p == p0 ? integral_before : 0.0);
  }
  const Displacement end = displacement_at(p1, t1_s);
  integral += end.integral_from_phase_start_ms - (p1 == p0 ? integral_before : 0.0);
  const double delta_displacement = end.displacement_m - start.displacement_m;
  const double delta_velocity = end.velocity_mps - start.velocity_mps;
  const double speed_squared_integral =
      0.5 * (start.velocity_mps * start.velocity_mps + end.velocity_mps * end.velocity_mps) * dt;
  delta_theta_b = gyro_static_b_ * dt + gyro_per_displacement_b_ * delta_displacement +
                  gyro_per_displacement_integral_b_ * integral;
  delta_v_b = accel_static_b_ * dt + accel_per_velocity_change_b_ * delta_velocity +
              accel_per_displacement_b_ * delta_displacement +
              accel_per_speed_squared_b_ * speed_squared_integral +
              accel_per_displacement_integral_b_ * integral;
}

nlohmann::json VibrationTableMotion::describe() const {
  nlohmann::json phases = nlohmann::json::array();
  for (std::size_t p = 0; p < table_phases_.size(); ++p) {
    nlohmann::json entry = {{"name", phases_[p].name},
                            {"start_s", table_phases_[p].start_s},
                            {"end_s", table_phases_[p].end_s},
                            {"motion", table_motion_name(table_phases_[p].kind)},
                            {"start_displacement_m", table_phases_[p].start_displacement_m}};
    if (table_phases_[p].kind != TableMotion::kStatic) {
      entry["vibration_components"] = to_json(table_phases_[p].vibration);
      entry["vibration_rms_mps2"] = table_phases_[p].vibration.rms_mps2();
    }
    phases.push_back(std::move(entry));
  }
  return {{"model",
           "vibration table: fixed site and attitude, linear vibration along the tool X axis; "
           "acceleration a(tau) = sum A_k sin(2 pi f_k tau + phase_k), tau from the phase start"},
          {"x_axis_n", {axis_n_.x(), axis_n_.y(), axis_n_.z()}},
          {"phases", std::move(phases)}};
}

std::string_view table_motion_name(TableMotion motion) {
  switch (motion) {
    case TableMotion::kStatic:
      return "static";
    case TableMotion::kSine:
      return "sine";
    case TableMotion::kRandom:
      return "random";
  }
  return "static";
}

}  // namespace stochnav::scenario_detail
