// Aid plugin "rop": rate of penetration as the velocity along the tool axis, with the lateral
// constraint (the tool moves along its axis only: a non-holonomic constraint of the drill
// string in the hole). At every row of the aid data (column "rop_mph", m/h):
//   v_b = C_bn v_n (m/s, body axes);  z = v_b - (0, 0, rop / 3600)
//   H: d z / d dv_n = C_bn,  d z / d phi = -C_bn [v_n x]   (C_nb_est = (I - [phi x]) C_nb)
//   R = diag(sigma_lateral^2, sigma_lateral^2, sigma_rop^2)
//
// params:
//   "sigma_rop_mps"      1-sigma of the ROP along the axis (m/s), > 0, default 1.4e-4 (0.5 m/h)
//   "sigma_lateral_mps"  1-sigma of the lateral velocity (m/s), > 0, default 1e-4
//   gate keys: see plugin/aid_plugin.hpp (read_nis_gate)

#include <fmt/format.h>

#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/aid_schedule.hpp"
#include "stochnav/plugin/params.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace {

namespace cs = stochnav::plugin::core_state;
using stochnav::plugin::Bound;

struct RopParams {
  double sigma_rop_mps = 0.5 / 3600.0;
  double sigma_lateral_mps = 1e-4;
};

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

class RopAid final : public stochnav::plugin::AidPlugin {
 public:
  RopAid(const RopParams& params, stochnav::plugin::NisGate gate,
         std::span<const double> times_s, std::span<const double> rop_mph)
      : AidPlugin(gate),
        params_(params),
        schedule_(stochnav::plugin::AidSchedule::at_rows(times_s)),
        rop_mph_(rop_mph) {}

  std::string_view type() const override { return "rop"; }
  int measurement_size() const override { return 3; }
  bool has_measurement(double t_s) const override { return schedule_.due(t_s); }

  bool measure(double t_s, const stochnav::NavState& state, const stochnav::plugin::ImuSample&,
               Eigen::Ref<Eigen::VectorXd> residual, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    const auto row = schedule_.row_at(t_s);
    if (!row) return false;
    const Eigen::Matrix3d c_bn = state.q_nb.toRotationMatrix().transpose();
    residual = c_bn * state.v_n;
    residual(2) -= rop_mph_[*row] / 3600.0;
    h.setZero();
    h.block<3, 3>(0, cs::kVelocity) = c_bn;
    h.block<3, 3>(0, cs::kAttitude) = -c_bn * skew(state.v_n);
    r.setZero();
    r(0, 0) = r(1, 1) = params_.sigma_lateral_mps * params_.sigma_lateral_mps;
    r(2, 2) = params_.sigma_rop_mps * params_.sigma_rop_mps;
    return true;
  }

  std::string describe() const override {
    return fmt::format("rop: tool-axis velocity from rop_mph, sigma {} m/s; lateral sigma {} m/s",
                       params_.sigma_rop_mps, params_.sigma_lateral_mps);
  }

 private:
  RopParams params_;
  stochnav::plugin::AidSchedule schedule_;
  std::span<const double> rop_mph_;
};

std::unique_ptr<stochnav::plugin::AidPlugin> make_rop(const nlohmann::json& json,
                                                      const stochnav::plugin::AidContext& context) {
  stochnav::plugin::ParamReader reader(json, context.params_pointer);
  RopParams params;
  params.sigma_rop_mps =
      reader.number_or("sigma_rop_mps", params.sigma_rop_mps, Bound::kPositive, "m/s");
  params.sigma_lateral_mps =
      reader.number_or("sigma_lateral_mps", params.sigma_lateral_mps, Bound::kPositive, "m/s");
  const auto gate = stochnav::plugin::read_nis_gate(reader, 3);
  reader.finish();
  return std::make_unique<RopAid>(params, gate, context.data->time_s(),
                                  context.data->column("rop_mph", context.params_pointer));
}

}  // namespace

STOCHNAV_AID_PLUGIN("rop", "Rate of penetration along the tool axis with the lateral constraint",
                    make_rop)
