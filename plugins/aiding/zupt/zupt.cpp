// Aid plugin "zupt": zero-velocity updates while the tool is stationary (pipe connections).
//   z = v_n (m/s, estimate - 0),  H = [0 I 0 0 0],  R = sigma_velocity^2 I.
//
// params:
//   "source"              "flags" (default): at every row of the aid data whose column
//                         "zupt" is 1 (a scenario's aids.csv, or a rig's slips/pump signal);
//                         "detector": at "rate_hz", when the compensated IMU sample of the
//                         epoch is stationary: | |f_b| - g | < "accel_threshold_mps2" and
//                         |omega_ib_b| < "gyro_threshold_radps" (|omega_ib_b| of a stationary
//                         tool is the Earth rate, 7.3e-5 rad/s). A one-sample detector: under
//                         vibration it stays silent, which is the safe failure.
//   "rate_hz"             detector rate (Hz), > 0, default 1
//   "accel_threshold_mps2"  default 0.05;  "gyro_threshold_radps"  default 1e-3
//   "sigma_velocity_mps"  1-sigma of the zero velocity (m/s), > 0, default 0.001
//   gate keys: see plugin/aid_plugin.hpp (read_nis_gate)

#include <fmt/format.h>

#include "stochnav/ins/earth.hpp"
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

struct ZuptParams {
  bool detector = false;        ///< "source": "detector" (else "flags")
  double rate_hz;               ///< Hz
  double accel_threshold_mps2;  ///< m/s^2
  double gyro_threshold_radps;  ///< rad/s
  double sigma_velocity_mps;    ///< m/s
  stochnav::plugin::NisGateParams gate;
};

const auto kZuptTable = stochnav::plugin::aid_param_table<ZuptParams>({
    stochnav::plugin::choice(&ZuptParams::detector, "source",
                             {{"flags", false}, {"detector", true}}, false,
                             "rows flagged in the aid data's \"zupt\" column, or the "
                             "stationarity detector"),
    scalar(&ZuptParams::rate_hz, "rate_hz", ParamUnit::fixed("Hz"), Bound::kPositive, 1.0,
           "detector: update rate"),
    scalar(&ZuptParams::accel_threshold_mps2, "accel_threshold_mps2", ParamUnit::fixed("m/s^2"),
           Bound::kPositive, 0.05, "detector: largest specific-force deviation at rest"),
    scalar(&ZuptParams::gyro_threshold_radps, "gyro_threshold_radps", ParamUnit::fixed("rad/s"),
           Bound::kPositive, 1e-3, "detector: largest angular rate at rest"),
    scalar(&ZuptParams::sigma_velocity_mps, "sigma_velocity_mps", ParamUnit::fixed("m/s"),
           Bound::kPositive, 0.001, "1-sigma of the zero velocity"),
});

class ZuptAid final : public stochnav::plugin::TabulatedAid<ZuptParams> {
 public:
  ZuptAid(const ZuptParams& params, stochnav::plugin::AidSchedule schedule,
          std::span<const double> flags)
      : TabulatedAid(kZuptTable, params, 3), schedule_(schedule), flags_(flags) {}

  std::string_view type() const override { return "zupt"; }
  int measurement_size() const override { return 3; }

  bool has_measurement(double t_s) const override {
    const auto row = schedule_.row_at(t_s);
    if (!row) return false;
    return parameters().detector || flags_[*row] > 0.5;
  }

  bool measure(double, const stochnav::NavState& state, const stochnav::plugin::ImuSample& imu,
               Eigen::Ref<Eigen::VectorXd> residual, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    const ZuptParams& params = parameters();
    if (params.detector) {
      const double g = stochnav::normal_gravity(state.latitude_rad, state.height_m);
      if (std::abs(imu.f_ib_b.norm() - g) >= params.accel_threshold_mps2 ||
          imu.omega_ib_b.norm() >= params.gyro_threshold_radps) {
        return false;
      }
    }
    residual = state.v_n;
    h.setZero();
    h.block<3, 3>(0, cs::kVelocity).setIdentity();
    r.setZero();
    r.diagonal().setConstant(params.sigma_velocity_mps * params.sigma_velocity_mps);
    return true;
  }

  bool states_velocity() const override { return true; }

  // At rest.
  bool stated_velocity_n(double, const stochnav::NavState&, Eigen::Ref<Eigen::Vector3d> v_n,
                         double& sigma_mps) const override {
    v_n.setZero();
    sigma_mps = parameters().sigma_velocity_mps;
    return true;
  }

 private:
  stochnav::plugin::AidSchedule schedule_;
  std::span<const double> flags_;
};

std::unique_ptr<stochnav::plugin::AidPlugin> make_zupt(
    const nlohmann::json& json, const stochnav::plugin::AidContext& context) {
  const ZuptParams params = stochnav::plugin::parse_aid_params(kZuptTable, json, context);
  if (params.detector) {
    return std::make_unique<ZuptAid>(
        params, stochnav::plugin::AidSchedule::periodic(context.initial_state.t_s, params.rate_hz),
        std::span<const double>());
  }
  const auto flags = context.data->column("zupt", context.params_pointer + "/source");
  return std::make_unique<ZuptAid>(
      params, stochnav::plugin::AidSchedule::at_rows(context.data->time_s()), flags);
}

}  // namespace

STOCHNAV_AID_PLUGIN("zupt", "Zero-velocity updates from aid flags or a stationarity detector",
                    make_zupt)
STOCHNAV_PLUGIN_DOCUMENTATION(kZuptTable)
