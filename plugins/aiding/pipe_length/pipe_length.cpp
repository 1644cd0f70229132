// Aid plugin "pipe_length": the measured depth (MD) from the drill-pipe tally. Consecutive
// tally readings give the distance travelled along the hole over [t_prev, t]; divided by the
// interval it is a measurement of the mean velocity along the tool axis, compared with the
// INS velocity projected on the tool axis u_n = C_nb (0, 0, 1):
//   z = u_n^T v_n - (MD_k - MD_k-1) / (t_k - t_k-1)
//   H: d z / d dv_n = u_n^T,  d z / d phi = -(u_n x v_n)^T ... = (v_n x u_n)^T
//   R = ((sigma_scale dMD)^2 + 2 sigma_random^2) / dt^2
// where the depth error model is MD_measured = (1 + s) MD + e, s ~ N(0, sigma_scale^2) per
// stand, e ~ N(0, sigma_random^2) per reading. Successive differences share a reading, so their
// errors are negatively correlated (-1/2); the filter treats them as independent, which
// overstates the information of the tally by at most a factor of two over long spans.
// The first row has no predecessor and gives no measurement.
//
// params:
//   "sigma_scale"     relative depth scale error, >= 0, default 1e-3
//   "sigma_random_m"  random error per reading (m), > 0, default 0.02
//   gate keys: see plugin/aid_plugin.hpp (read_nis_gate)

#include <fmt/format.h>

#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/aid_schedule.hpp"
#include "stochnav/plugin/params.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace {

namespace cs = stochnav::plugin::core_state;
using stochnav::plugin::Bound;

struct PipeLengthParams {
  double sigma_scale = 1e-3;
  double sigma_random_m = 0.02;
};

class PipeLengthAid final : public stochnav::plugin::AidPlugin {
 public:
  PipeLengthAid(const PipeLengthParams& params, stochnav::plugin::NisGate gate,
                std::span<const double> times_s, std::span<const double> depth_m)
      : AidPlugin(gate),
        params_(params),
        schedule_(stochnav::plugin::AidSchedule::at_rows(times_s)),
        times_s_(times_s),
        depth_m_(depth_m) {}

  std::string_view type() const override { return "pipe_length"; }
  int measurement_size() const override { return 1; }

  bool has_measurement(double t_s) const override {
    const auto row = schedule_.row_at(t_s);
    return row && *row > 0;
  }

  bool measure(double t_s, const stochnav::NavState& state, const stochnav::plugin::ImuSample&,
               Eigen::Ref<Eigen::VectorXd> residual, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    const auto row = schedule_.row_at(t_s);
    if (!row || *row == 0) return false;
    const double dt = times_s_[*row] - times_s_[*row - 1];
    if (!(dt > 0.0)) return false;
    const double depth_change = depth_m_[*row] - depth_m_[*row - 1];
    const Eigen::Vector3d axis_n = state.q_nb * Eigen::Vector3d::UnitZ();
    residual(0) = axis_n.dot(state.v_n) - depth_change / dt;
    h.setZero();
    h.block<1, 3>(0, cs::kVelocity) = axis_n.transpose();
    h.block<1, 3>(0, cs::kAttitude) = state.v_n.cross(axis_n).transpose();
    const double scale_part = params_.sigma_scale * depth_change;
    r(0, 0) = (scale_part * scale_part + 2.0 * params_.sigma_random_m * params_.sigma_random_m) /
              (dt * dt);
    return true;
  }

  std::string describe() const override {
    return fmt::format("pipe_length: depth tally, scale sigma {}, random sigma {} m",
                       params_.sigma_scale, params_.sigma_random_m);
  }

 private:
  PipeLengthParams params_;
  stochnav::plugin::AidSchedule schedule_;
  std::span<const double> times_s_;
  std::span<const double> depth_m_;
};

std::unique_ptr<stochnav::plugin::AidPlugin> make_pipe_length(
    const nlohmann::json& json, const stochnav::plugin::AidContext& context) {
  stochnav::plugin::ParamReader reader(json, context.params_pointer);
  PipeLengthParams params;
  params.sigma_scale = reader.number_or("sigma_scale", params.sigma_scale, Bound::kNonNegative, "");
  params.sigma_random_m =
      reader.number_or("sigma_random_m", params.sigma_random_m, Bound::kPositive, "m");
  const auto gate = stochnav::plugin::read_nis_gate(reader, 1);
  reader.finish();
  return std::make_unique<PipeLengthAid>(
      params, gate, context.data->time_s(),
      context.data->column("measured_depth_m", context.params_pointer));
}

}  // namespace

STOCHNAV_AID_PLUGIN("pipe_length", "Measured depth from the drill-pipe tally (along-hole speed)",
                    make_pipe_length)
