#include "stochnav/filter/error_dynamics.hpp"

#include <cmath>

#include "stochnav/ins/cross_product_matrix.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/latitude_terms.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav {
namespace {

namespace cs = plugin::core_state;

}  // namespace

// Over an epoch a single integral runs linearly from its value at the start: the double
// integral gains dt times its mean over the epoch.
void FastInputIntegrals::add_velocity_inputs(double dt_s, const Eigen::Matrix3d& c_nb_dt_epoch,
                                             const Eigen::Vector3d& f_n_dt_epoch) {
  c_nb_dt2 += dt_s * (c_nb_dt + 0.5 * c_nb_dt_epoch);
  f_n_dt2 += dt_s * (f_n_dt + 0.5 * f_n_dt_epoch);
  interval_s += dt_s;
  c_nb_dt += c_nb_dt_epoch;
  f_n_dt += f_n_dt_epoch;
}

void FastInputIntegrals::add_accel_scale_input(double dt_s,
                                               const Eigen::Matrix3d& accel_scale_dt_epoch) {
  accel_scale_dt2 += dt_s * (accel_scale_dt + 0.5 * accel_scale_dt_epoch);
  accel_scale_dt += accel_scale_dt_epoch;
}

PositionShapeCorrection position_shape_correction(const FastInputIntegrals& fast) {
  // The signs follow the velocity rows: + [f_n x] phi, - C_nb db_a, - C_nb diag(f_b) ds_a.
  const double half = 0.5 * fast.interval_s;
  return {.attitude = skew(fast.f_n_dt2 - half * fast.f_n_dt),
          .accel_bias = -(fast.c_nb_dt2 - half * fast.c_nb_dt),
          .accel_scale = -(fast.accel_scale_dt2 - half * fast.accel_scale_dt)};
}

CoreMatrix integrated_core_dynamics(const NavState& state, const FastInputIntegrals& fast) {
  return integrated_core_dynamics(state, LatitudeTerms(state.latitude_rad), fast);
}

CoreMatrix integrated_core_dynamics(const NavState& state, const LatitudeTerms& latitude,
                                    const FastInputIntegrals& fast) {
  const double t = fast.interval_s;
  const double h = state.height_m;
  const LatitudeTrig& trig = latitude.trig;  // one sin, cos, tan for every term below
  const EarthRadii& radii = latitude.radii;
  const double rm = radii.meridian_m + h;
  const double rn = radii.transverse_m + h;
  const double tan_lat = trig.tan;
  const double sec_lat = 1.0 / trig.cos;
  const double w = wgs84::kEarthRate_radps;
  const double ve = state.v_n.x();
  const double vn = state.v_n.y();
  const double vu = state.v_n.z();
  const Eigen::Vector3d omega_ie_n = earth_rate_n(trig);
  const Eigen::Vector3d omega_en_n = transport_rate_n(trig, radii, h, state.v_n);

  // Partial derivatives of the rates with respect to dv and dr (dlat = dr_N / rm, dh = dr_U).
  Eigen::Matrix3d d_omega_en_dv;
  d_omega_en_dv << 0.0, -1.0 / rm, 0.0,  //
      1.0 / rn, 0.0, 0.0,                //
      tan_lat / rn, 0.0, 0.0;
  Eigen::Matrix3d d_omega_ie_dr = Eigen::Matrix3d::Zero();
  d_omega_ie_dr(1, 1) = -w * trig.sin / rm;
  d_omega_ie_dr(2, 1) = w * trig.cos / rm;
  Eigen::Matrix3d d_omega_en_dr = Eigen::Matrix3d::Zero();
  d_omega_en_dr(0, 2) = vn / (rm * rm);
  d_omega_en_dr(1, 2) = -ve / (rn * rn);
  d_omega_en_dr(2, 1) = ve * sec_lat * sec_lat / (rn * rm);
  d_omega_en_dr(2, 2) = -ve * tan_lat / (rn * rn);

  const Eigen::Matrix3d v_cross = skew(state.v_n);
  CoreMatrix f_t = CoreMatrix::Zero();
  // Position.
  f_t.block<3, 3>(cs::kPosition, cs::kVelocity) = Eigen::Matrix3d::Identity() * t;
  Eigen::Matrix3d rr;
  rr << vu / rn - tan_lat * vn / rm, ve * tan_lat / rm, -ve / rn,  //
      0.0, vu / rm, -vn / rm,                                      //
      0.0, 0.0, 0.0;
  f_t.block<3, 3>(cs::kPosition, cs::kPosition) = rr * t;
  // Velocity.
  f_t.block<3, 3>(cs::kVelocity, cs::kAttitude) = skew(fast.f_n_dt);
  f_t.block<3, 3>(cs::kVelocity, cs::kVelocity) =
      (v_cross * d_omega_en_dv - skew(2.0 * omega_ie_n + omega_en_n)) * t;
  Eigen::Matrix3d vr = v_cross * (2.0 * d_omega_ie_dr + d_omega_en_dr);
  const double mean_radius = std::sqrt(radii.meridian_m * radii.transverse_m) + h;
  vr(2, 2) += 2.0 * normal_gravity(trig, h) / mean_radius;
  f_t.block<3, 3>(cs::kVelocity, cs::kPosition) = vr * t;
  f_t.block<3, 3>(cs::kVelocity, cs::kAccelBias) = -fast.c_nb_dt;
  // Attitude.
  f_t.block<3, 3>(cs::kAttitude, cs::kAttitude) = -skew(omega_ie_n + omega_en_n) * t;
  f_t.block<3, 3>(cs::kAttitude, cs::kVelocity) = d_omega_en_dv * t;
  f_t.block<3, 3>(cs::kAttitude, cs::kPosition) = (d_omega_ie_dr + d_omega_en_dr) * t;
  f_t.block<3, 3>(cs::kAttitude, cs::kGyroBias) = fast.c_nb_dt;
  return f_t;
}

}  // namespace stochnav
