#pragma once
// Aiding plugins: measurements that correct the INS (pipe length, ROP, ZUPT, static position).
// Plugin API (plugin_api.hpp); one instance per aid entry of a run config.
//
// Error-state convention (state_layout.hpp, core_state): dx = x_estimated - x_true, with the 15
// core states [dr (ENU, m), dv_n (ENU, m/s), phi (attitude error in n, rad), b_a (b, m/s^2),
// b_g (b, rad/s)]. The attitude error is defined by C_nb_est = (I - [phi x]) C_nb_true (ENU
// n; C_nb maps body axes into n), so a body vector u_b predicted as C_nb_est u_b errs by
// -phi x (C_nb u_b) = [(C_nb u_b) x] phi (H columns +[u_n x]), and a navigation vector v_n
// predicted in the body as C_nb_est^T v_n errs by C_bn (phi x v_n) (H columns -C_bn [v_n x]).
// An aid predicts its measurement y from the estimated state and returns
//   z = h(x_estimated) - y_measured   (m, in the aid's units),
//   H = dz/d(dx)                      (m x 15, core states only: the runtime pads zeros for
//                                      the augmented states),
//   R                                 (m x m, covariance of y's error),
// so that z ~ H dx + v, v ~ N(0, R). The filter rejects an update whose normalised innovation
// squared z^T (H P H^T + R)^-1 z exceeds gate().threshold.

#include <Eigen/Core>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "stochnav/ins/nav_state.hpp"
#include "stochnav/plugin/param_table.hpp"
#include "stochnav/plugin/plugin_api.hpp"

namespace stochnav::plugin {

class ParamReader;

/// Time series of aiding data by column name (an aids.csv: t, measured_depth_m, rop_mph, zupt,
/// ...). Every column has one value per row; the column "t" is the time (s), ascending.
class AidData {
 public:
  AidData() = default;
  /// Throws InputError when lengths differ, "t" is missing or t is not ascending.
  AidData(std::string source, std::vector<std::string> names,
          std::vector<std::vector<double>> columns);

  bool has(std::string_view name) const;
  /// The column's values; throws ConfigError "<pointer>: aid data <source> has no column
  /// '<name>'; ..." listing the columns.
  std::span<const double> column(std::string_view name, std::string_view pointer) const;
  /// The "t" column (s); empty when there is no data.
  std::span<const double> time_s() const;
  const std::vector<std::string>& names() const { return names_; }
  const std::string& source() const { return source_; }
  std::size_t rows() const;

  /// Moves row `row`'s time to `t_s` (s), the IMU epoch that applies it
  /// (experiment/aid_epochs.hpp puts rows recorded off the IMU grid on the grid). The caller keeps
  /// the times increasing: t_s lies between the neighbouring rows' times.
  void move_row_time(std::size_t row, double t_s);

 private:
  std::string source_;
  std::vector<std::string> names_;
  std::vector<std::vector<double>> columns_;
};

/// Reads a CSV with a header row of column names, one of them "t" (s), numeric cells. Throws
/// InputError naming the file and line.
AidData read_aid_data(const std::filesystem::path& csv_path);

/// What an aid factory gets besides its params.
struct AidContext {
  std::string params_pointer;        ///< JSON pointer of params, e.g. "/aids/0/params"
  const AidData* data = nullptr;     ///< the run's aid data; never null (empty when there is none)
  NavState initial_state;            ///< initial position, velocity and attitude of the run
  std::filesystem::path config_dir;  ///< folder of the config file
};

/// What the INS did over the interval [t_prev, t] from this aid's previous measurement epoch
/// (the previous epoch at which has_measurement was true; the start of the run for the first)
/// to the current one, for aids whose measurement is itself an interval quantity (a depth
/// increment, a rate of penetration averaged by the rig). Under axial vibration the
/// instantaneous velocity oscillates by up to A / (2 pi f) (0.6 m/s at 3 g, 8 Hz), and aid epochs
/// at whole seconds sample whole-hertz vibration at the same phase every time: compared with an
/// interval rate, the instantaneous velocity turns the vibration into a steady velocity error.
///
/// The mean ENU velocity removes the oscillation, which the accelerometers measure well over
/// an interval. Its error is not the velocity error at the epoch: the velocity error drifts
/// within the interval (d dv_n/dt = [f_n x] phi - C_nb db_a + C_nb w_a + ...), so that, to first
/// order in the interval and with the core error state dx (core_state) at the epoch t,
///   mean_v_n(estimate) - mean_v_n(true) = mean_velocity_error_map dx - e,
///   mean_velocity_error_map = [0, I, -(1/T) int (s - t_prev) [f_n(s) x] ds,
///                              (1/T) int (s - t_prev) C_nb(s) ds, gyro-bias term] (3 x 15)
///   e ~ N(0, mean_velocity_noise_covariance),  (1/T^2) int (s - t_prev)^2 dQ_v(s)  (ENU, m^2/s^2)
/// with dQ_v the accelerometer white noise integrated into the velocity (the Coriolis and
/// transport terms, of order 1e-4 dv per s, are left out). The gyro-bias columns carry the
/// attitude's drift inside the interval; filter/ins_interval_accumulator.hpp gives every term,
/// and those of the states beyond the core (AidPlugin::measures_interval_mean). At a tilt error of
/// 1e-4 rad the drift term alone is g 1e-4 T / 2 = 5e-4 m/s over a 1-s interval: an aid that
/// linearised the mean on dv at the epoch would be overconfident by far. Aids project the mean with
/// the attitude at the epoch (the hole direction does not rotate with the toolface, whereas a mean
/// of the rotating body axes would average the lateral information away). Only interval aids
/// (AidPlugin::measures_interval_mean) get an interval; the others see duration_s = 0.
struct InsInterval {
  double duration_s = 0.0;                             ///< T = t - t_prev (s); 0 at the start
  Eigen::Vector3d mean_v_n = Eigen::Vector3d::Zero();  ///< (1/T) int v_n dt, ENU (m/s)
  Eigen::Matrix<double, 3, 15> mean_velocity_error_map = Eigen::Matrix<double, 3, 15>::Zero();
  Eigen::Matrix3d mean_velocity_noise_covariance = Eigen::Matrix3d::Zero();  ///< m^2/s^2
};

/// The IMU and INS at the time of a measurement.
struct ImuSample {
  double t_s = 0.0;                                      ///< time (s)
  Eigen::Vector3d omega_ib_b = Eigen::Vector3d::Zero();  ///< angular rate, body (rad/s)
  Eigen::Vector3d f_ib_b = Eigen::Vector3d::Zero();      ///< specific force, body (m/s^2)
  InsInterval interval;  ///< since this aid's previous measurement epoch
  /// The velocity the filter linearises the attitude error's effect on velocity about (ENU,
  /// m/s): the reference velocity of MwdNavigator, the last velocity an aid stated
  /// (AidPlugin::stated_velocity_n), or the INS velocity in a run whose aids state none. An aid
  /// whose prediction rotates a velocity with the attitude (C_bn v) takes its attitude columns
  /// about this velocity, not the INS's: to first order the residual is C_bn (dv + phi x
  /// v_true), and the INS velocity v_true + dv would add [dv x] phi, the INS's own velocity error
  /// read as attitude information (docs/drilling-envelope.md).
  Eigen::Vector3d reference_v_n = Eigen::Vector3d::Zero();
};

/// Innovation gate on NIS = z^T S^-1 z.
struct NisGate {
  bool enabled = true;
  double threshold = std::numeric_limits<double>::infinity();  ///< reject when NIS > threshold

  bool accepts(double nis) const { return !enabled || nis <= threshold; }
};

/// Default probability of the chi-square gate: 99.9 %.
inline constexpr double kDefaultGateProbability = 0.999;

/// The chi-square quantile with `dof` degrees of freedom at `probability` (in (0, 1)).
double chi_square_quantile(double probability, int dof);

/// The gate keys of an aid's params, as given (one place for every aid):
///   "nis_gate": bool (default true), "nis_probability": (0, 1) (default 0.999: chi-square
///   quantile with the measurement size as dof), "nis_threshold": > 0 (overrides the
///   probability).
struct NisGateParams {
  bool enabled = true;
  double probability = kDefaultGateProbability;
  double threshold = std::numeric_limits<double>::quiet_NaN();  ///< NaN: from the probability
};

/// The table of NisGateParams; an aid puts its keys beside its own with
/// `kTable.plus(lift(&MyParams::gate, nis_gate_table()))`.
const ParamTable<NisGateParams>& nis_gate_table();

/// The gate of a measurement of `measurement_size` components.
NisGate nis_gate(const NisGateParams& params, int measurement_size);

/// nis_gate() of the gate keys read from an aid's params.
NisGate read_nis_gate(ParamReader& params, int measurement_size);

class AidPlugin {
 public:
  virtual ~AidPlugin();
  AidPlugin(const AidPlugin&) = delete;
  AidPlugin& operator=(const AidPlugin&) = delete;

  /// The plugin type (PluginInfo::type), e.g. "zupt".
  virtual std::string_view type() const = 0;

  /// m >= 1, constant.
  virtual int measurement_size() const = 0;

  /// Whether a measurement exists at t (s), the time of the current IMU epoch.
  virtual bool has_measurement(double t_s) const = 0;

  /// The measurement at t given the current estimate: residual z (m), h (m x 15), r (m x m),
  /// caller-sized, every entry written. Returns false when there is none after all (nothing
  /// written). Const, allocation-free, never throws.
  virtual bool measure(double t_s, const NavState& state, const ImuSample& imu,
                       Eigen::Ref<Eigen::VectorXd> residual, Eigen::Ref<Eigen::MatrixXd> h,
                       Eigen::Ref<Eigen::MatrixXd> r) const = 0;

  /// True for an interval aid, whose measurement depends on the error state at the epoch only
  /// through imu.interval's mean velocity (besides the attitude that projects it), as for ROP
  /// and the pipe tally. Only interval aids get imu.interval; the navigator extends their h
  /// beyond the 15 core states with the mean's sensitivity to the scale-factor and augmented
  /// sensor-error states, P * (their columns of the mean's map), P = dz / d mean_v_n being h's
  /// velocity columns.
  virtual bool measures_interval_mean() const { return false; }

  /// Whether the aid states the tool's velocity (stated_velocity_n): ZUPT (at rest), ROP and
  /// the pipe tally (along the tool axis at their rate). Constant. In a run with such an aid the
  /// navigator linearises about the stated velocities instead of the INS's (ImuSample::
  /// reference_v_n).
  virtual bool states_velocity() const { return false; }

  /// The tool's velocity the measurement at t states, after measure() returned true for it at
  /// the same t and state: v_n (ENU, m/s) and the 1-sigma of its speed, sigma_mps (> 0); false
  /// when it states none (nothing written). The navigator takes the most precise statement of
  /// an epoch. Const, allocation-free, never throws.
  virtual bool stated_velocity_n(double /*t_s*/, const NavState& /*state*/,
                                 Eigen::Ref<Eigen::Vector3d> /*v_n*/, double& /*sigma_mps*/) const {
    return false;
  }

  /// One line with the params in their units.
  virtual std::string describe() const = 0;

  const NisGate& gate() const { return gate_; }

 protected:
  explicit AidPlugin(NisGate gate) : gate_(gate) {}

 private:
  NisGate gate_;
};

/// Builds an aid from its params. Throws ConfigError naming context.params_pointer (+ key).
using AidFactory = std::unique_ptr<AidPlugin>(const nlohmann::json& params,
                                              const AidContext& context);

}  // namespace stochnav::plugin

/// Registers an aiding plugin; use once, at global scope, in the plugin library.
#define STOCHNAV_AID_PLUGIN(TYPE, DESCRIPTION, FACTORY)                              \
  static_assert(std::is_same_v<decltype(&FACTORY), ::stochnav::plugin::AidFactory*>, \
                "STOCHNAV_AID_PLUGIN: FACTORY must be an AidFactory");               \
  STOCHNAV_PLUGIN_INFO_(::stochnav::plugin::PluginKind::kAid, TYPE, DESCRIPTION)     \
  BOOST_DLL_ALIAS(FACTORY, stochnav_aid_factory)
