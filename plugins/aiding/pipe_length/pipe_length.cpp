// Aid plugin "pipe_length": the measured depth (MD) from the drill-pipe tally. Consecutive
// tally readings k-1, k give the distance travelled along the hole over [t_k-1, t_k]; it is
// compared with the INS's distance along the tool axis over the same interval: the mean ENU
// velocity (plugin::InsInterval; the INS displacement over the interval divided by it) on the
// tool axis u_n = C_nb z_b at the epoch. Not the instantaneous velocity: under axial vibration
// that oscillates by up to A / (2 pi f), and aid epochs at whole seconds sample whole-hertz
// vibration at the same phase every time.
//   z = u_n . mean_v_n - (MD_k - MD_k-1) / T,            T = t_k - t_k-1
//   H = u_n^T mean_velocity_error_map + [0, 0, (v_ref x u_n)^T, 0, 0]
//       (InsInterval; C_nb_est = (I - [phi x]) C_nb; v_ref = ImuSample::reference_v_n, the
//       velocity the aids state: along the axis, where the term vanishes. About the INS velocity
//       it would be (dv x u_n)^T, the INS's lateral velocity error read as attitude information)
// States the velocity u_n times the tally's mean rate over the last 60 s of rows, with its
// 1-sigma (AidPlugin::stated_velocity_n; ROP's, when the run has it, is more precise).
//   R = u_n^T mean_velocity_noise_covariance u_n
//       + ((sigma_scale dMD)^2 + 2 sigma_random^2 + 2 sigma_displacement^2) / T^2
// where the depth error model is MD_measured = (1 + s) MD + e, s ~ N(0, sigma_scale^2),
// e ~ N(0, sigma_random^2) per reading, and sigma_displacement is the tool's axial displacement
// against the surface reading (string stretch, axial oscillation). Successive differences share
// a reading, so their errors are negatively correlated (-1/2); the filter treats them as
// independent, which understates the tally's information over long spans (conservative).
// A row gives a measurement only when the previous row was this aid's previous measurement
// epoch (the interval means then cover exactly [t_k-1, t_k]); the first row gives none.
//
// params:
//   "sigma_scale"           relative depth scale error, >= 0, default 1e-3
//   "sigma_random_m"        random error per reading (m), > 0, default 0.05
//   "sigma_displacement_m"  axial displacement of the tool against the surface (m), >= 0,
//                           default 0
//   gate keys: see plugin/aid_plugin.hpp (read_nis_gate)

#include <fmt/format.h>

#include <cmath>

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

struct PipeLengthParams {
  double sigma_scale;           ///< relative
  double sigma_random_m;        ///< m
  double sigma_displacement_m;  ///< m
  stochnav::plugin::NisGateParams gate;
};

const auto kPipeLengthTable = stochnav::plugin::aid_param_table<PipeLengthParams>({
    scalar(&PipeLengthParams::sigma_scale, "sigma_scale", ParamUnit::fixed(""), Bound::kNonNegative,
           1e-3, "relative 1-sigma of the tally (scale error)"),
    scalar(&PipeLengthParams::sigma_random_m, "sigma_random_m", ParamUnit::fixed("m"),
           Bound::kPositive, 0.05, "1-sigma of the random depth error"),
    scalar(&PipeLengthParams::sigma_displacement_m, "sigma_displacement_m", ParamUnit::fixed("m"),
           Bound::kNonNegative, 0.0, "1-sigma of the displacement since the last update"),
});

class PipeLengthAid final : public stochnav::plugin::TabulatedAid<PipeLengthParams> {
 public:
  static constexpr double kStatementSpan_s = 60.0;

  PipeLengthAid(const PipeLengthParams& params, std::span<const double> times_s,
                std::span<const double> depth_m)
      : TabulatedAid(kPipeLengthTable, params, 1),
        schedule_(stochnav::plugin::AidSchedule::at_rows(times_s)),
        times_s_(times_s),
        depth_m_(depth_m) {}

  std::string_view type() const override { return "pipe_length"; }
  int measurement_size() const override { return 1; }
  bool measures_interval_mean() const override { return true; }

  // Every row is a measurement epoch (so that the interval of row k starts at row k-1), though
  // the first gives no measurement.
  bool has_measurement(double t_s) const override { return schedule_.due(t_s); }

  bool measure(double t_s, const stochnav::NavState& state, const stochnav::plugin::ImuSample& imu,
               Eigen::Ref<Eigen::VectorXd> residual, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    const auto row = schedule_.row_at(t_s);
    if (!row || *row == 0) return false;
    const double dt = times_s_[*row] - times_s_[*row - 1];
    const stochnav::plugin::InsInterval& interval = imu.interval;
    if (!(dt > 0.0) ||
        std::abs(interval.duration_s - dt) > stochnav::plugin::kEpochMatchTolerance_s) {
      return false;
    }
    const double depth_change = depth_m_[*row] - depth_m_[*row - 1];
    const Eigen::Vector3d axis_n = state.q_nb * Eigen::Vector3d::UnitZ();
    residual(0) = axis_n.dot(interval.mean_v_n) - depth_change / dt;
    h = axis_n.transpose() * interval.mean_velocity_error_map;
    h.block<1, 3>(0, cs::kAttitude) += imu.reference_v_n.cross(axis_n).transpose();
    const PipeLengthParams& params = parameters();
    const double scale_part = params.sigma_scale * depth_change;
    r(0, 0) = axis_n.dot(interval.mean_velocity_noise_covariance * axis_n) +
              (scale_part * scale_part + 2.0 * params.sigma_random_m * params.sigma_random_m +
               2.0 * params.sigma_displacement_m * params.sigma_displacement_m) /
                  (dt * dt);
    return true;
  }

  bool states_velocity() const override { return true; }

  // Along the tool axis at the tally's mean rate over the rows of the last kStatementSpan_s
  // (one reading's 5 cm over 1 s is 0.07 m/s, ten times a drilling speed; over 60 s, 1.2e-3).
  bool stated_velocity_n(double t_s, const stochnav::NavState& state,
                         Eigen::Ref<Eigen::Vector3d> v_n, double& sigma_mps) const override {
    const auto row = schedule_.row_at(t_s);
    if (!row || *row == 0) return false;
    std::size_t first = *row - 1;
    while (first > 0 && times_s_[*row] - times_s_[first - 1] <= kStatementSpan_s) --first;
    const double span = times_s_[*row] - times_s_[first];
    if (!(span > 0.0)) return false;
    const double change = depth_m_[*row] - depth_m_[first];
    v_n = state.q_nb * Eigen::Vector3d::UnitZ() * (change / span);
    const PipeLengthParams& params = parameters();
    const double scale_part = params.sigma_scale * change;
    sigma_mps =
        std::sqrt(scale_part * scale_part + 2.0 * params.sigma_random_m * params.sigma_random_m +
                  2.0 * params.sigma_displacement_m * params.sigma_displacement_m) /
        span;
    return sigma_mps > 0.0;
  }

 private:
  std::string detail() const override { return "depth tally against the mean tool-axis velocity"; }

  stochnav::plugin::AidSchedule schedule_;
  std::span<const double> times_s_;
  std::span<const double> depth_m_;
};

std::unique_ptr<stochnav::plugin::AidPlugin> make_pipe_length(
    const nlohmann::json& json, const stochnav::plugin::AidContext& context) {
  return std::make_unique<PipeLengthAid>(
      stochnav::plugin::parse_aid_params(kPipeLengthTable, json, context), context.data->time_s(),
      context.data->column("measured_depth_m", context.params_pointer));
}

}  // namespace

STOCHNAV_AID_PLUGIN("pipe_length", "Measured depth from the drill-pipe tally (along-hole speed)",
                    make_pipe_length)
STOCHNAV_PLUGIN_DOCUMENTATION(kPipeLengthTable)
