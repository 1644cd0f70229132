// Aid plugin "rop": rate of penetration as the mean velocity along the tool axis, with the
// lateral constraint (the tool moves along its axis only: a non-holonomic constraint of the
// drill string in the hole). The rig's ROP is a surface rate averaged over seconds, so it is
// compared with the INS's MEAN velocity over the interval since the previous ROP epoch
// (plugin::InsInterval), not with the instantaneous velocity: under axial vibration the
// instantaneous velocity oscillates by up to A / (2 pi f) (0.6 m/s at 3 g, 8 Hz) and 1-Hz
// epochs sample the same phase of whole-hertz vibration every time, which a filter fed
// instantaneous velocities turns into a steady velocity error. The mean ENU velocity (free of
// the oscillation) is projected on the body axes with the attitude at the epoch. At every row
// k of the aid data (column "rop_mph", m/h) after the first epoch of the run:
//   rop_k  = (ROP_k-1 + ROP_k) / 2 when row k-1 is at the interval's start (trapezoid of the
//            rate over the interval), else ROP_k
//   z      = C_bn mean_v_n - (0, 0, rop_k / 3600)           (m/s, body axes)
//   H      = C_bn mean_velocity_error_map - [0, 0, C_bn [v_ref x], 0, 0]
//            (InsInterval; C_nb_est = (I - [phi x]) C_nb), v_ref = ImuSample::reference_v_n:
//            the attitude columns about the velocity the aids state, not the INS's (whose
//            velocity error would read as attitude information)
//   R      = C_bn mean_velocity_noise_covariance C_bn^T
//            + diag(sigma_lateral^2, sigma_lateral^2, sigma_rop^2 + 2 sigma_displacement^2 / T^2)
// sigma_displacement covers what moves the tool but not the surface reading over the interval
// (axial oscillation of the string, stretch): its change over T adds to the mean rate.
//
// params:
//   "sigma_rop_mps"           1-sigma of the ROP along the axis (m/s), > 0, default 2.78e-4
//                             (1 m/h, the scatter of a rig's ROP channel)
//   "sigma_lateral_mps"       1-sigma of the mean lateral velocity (m/s), > 0, default 1e-3: a
//                             tool moves across the hole by millimetres per second (clearance,
//                             whirl); at 1e-4 the 36-h drilling scenario's inclination was
//                             inside its 3 sigma only 76 % of the time (98 % at 1e-3)
//   "sigma_displacement_m"    1-sigma of the tool's axial displacement against the surface
//                             (m), >= 0, default 0
//   gate keys: see plugin/aid_plugin.hpp (read_nis_gate)
// States the velocity u_n ROP_k / 3600 (AidPlugin::stated_velocity_n).

#include <fmt/format.h>

#include <cmath>

#include "stochnav/ins/cross_product_matrix.hpp"
#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/aid_schedule.hpp"
#include "stochnav/plugin/param_table.hpp"
#include "stochnav/plugin/params.hpp"
#include "stochnav/plugin/state_layout.hpp"
#include "stochnav/plugin/tabulated_aid.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"

namespace {

namespace cs = stochnav::plugin::core_state;
using stochnav::plugin::Bound;
using stochnav::plugin::ParamUnit;

struct RopParams {
  double sigma_rop_mps;         ///< m/s
  double sigma_lateral_mps;     ///< m/s
  double sigma_displacement_m;  ///< m
  stochnav::plugin::NisGateParams gate;
};

const auto kRopTable = stochnav::plugin::aid_param_table<RopParams>({
    scalar(&RopParams::sigma_rop_mps, "sigma_rop_mps", ParamUnit::fixed("m/s"), Bound::kPositive,
           1.0 / 3600.0, "1-sigma of the measured rate of penetration"),
    scalar(&RopParams::sigma_lateral_mps, "sigma_lateral_mps", ParamUnit::fixed("m/s"),
           Bound::kPositive, 1e-3, "1-sigma of the zero lateral velocity"),
    scalar(&RopParams::sigma_displacement_m, "sigma_displacement_m", ParamUnit::fixed("m"),
           Bound::kNonNegative, 0.0, "1-sigma of the displacement since the last update"),
});

class RopAid final : public stochnav::plugin::TabulatedAid<RopParams> {
 public:
  RopAid(const RopParams& params, std::span<const double> times_s, std::span<const double> rop_mph)
      : TabulatedAid(kRopTable, params, 3),
        schedule_(stochnav::plugin::AidSchedule::at_rows(times_s)),
        times_s_(times_s),
        rop_mph_(rop_mph) {}

  std::string_view type() const override { return "rop"; }
  int measurement_size() const override { return 3; }
  bool measures_interval_mean() const override { return true; }
  bool has_measurement(double t_s) const override { return schedule_.due(t_s); }

  bool measure(double t_s, const stochnav::NavState& state, const stochnav::plugin::ImuSample& imu,
               Eigen::Ref<Eigen::VectorXd> residual, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    const auto row = schedule_.row_at(t_s);
    const stochnav::plugin::InsInterval& interval = imu.interval;
    if (!row || !(interval.duration_s > 0.0)) return false;
    double rop_mph = rop_mph_[*row];
    if (*row > 0 && std::abs(times_s_[*row - 1] - (t_s - interval.duration_s)) <=
                        stochnav::plugin::kEpochMatchTolerance_s) {
      rop_mph = 0.5 * (rop_mph_[*row - 1] + rop_mph);
    }
    const Eigen::Matrix3d c_bn = state.q_nb.toRotationMatrix().transpose();
    residual = c_bn * interval.mean_v_n;
    residual(2) -= rop_mph / 3600.0;
    h = c_bn * interval.mean_velocity_error_map;
    h.block<3, 3>(0, cs::kAttitude) -= c_bn * stochnav::skew(imu.reference_v_n);
    const RopParams& params = parameters();
    r = c_bn * interval.mean_velocity_noise_covariance * c_bn.transpose();
    r(0, 0) += params.sigma_lateral_mps * params.sigma_lateral_mps;
    r(1, 1) += params.sigma_lateral_mps * params.sigma_lateral_mps;
    const double displacement_rate = params.sigma_displacement_m / interval.duration_s;
    r(2, 2) +=
        params.sigma_rop_mps * params.sigma_rop_mps + 2.0 * displacement_rate * displacement_rate;
    return true;
  }

  bool states_velocity() const override { return true; }

  // Along the tool axis at the rate of penetration of the row.
  bool stated_velocity_n(double t_s, const stochnav::NavState& state,
                         Eigen::Ref<Eigen::Vector3d> v_n, double& sigma_mps) const override {
    const auto row = schedule_.row_at(t_s);
    if (!row) return false;
    v_n = state.q_nb * Eigen::Vector3d::UnitZ() * (rop_mph_[*row] / 3600.0);
    sigma_mps = parameters().sigma_rop_mps;
    return true;
  }

 private:
  std::string detail() const override { return "mean tool-axis velocity from rop_mph"; }

  stochnav::plugin::AidSchedule schedule_;
  std::span<const double> times_s_;
  std::span<const double> rop_mph_;
};

std::unique_ptr<stochnav::plugin::AidPlugin> make_rop(const nlohmann::json& json,
                                                      const stochnav::plugin::AidContext& context) {
  return std::make_unique<RopAid>(stochnav::plugin::parse_aid_params(kRopTable, json, context),
                                  context.data->time_s(),
                                  context.data->column("rop_mph", context.params_pointer));
}

}  // namespace

STOCHNAV_AID_PLUGIN("rop", "Rate of penetration along the tool axis with the lateral constraint",
                    make_rop)
STOCHNAV_PLUGIN_DOCUMENTATION(kRopTable)
