#pragma once
// The MWD navigation filter: a strapdown INS (ins/strapdown.hpp) corrected by a closed-loop
// error-state Kalman filter whose 15 core states (plugin/state_layout.hpp) are followed by the
// augmented states of the gyro and accelerometer noise models (plugins). The noise models give
// the system noise, possibly time-varying (DAVAR); the aiding plugins give the measurements.
//
// Per IMU epoch (step): the raw increments are compensated by the estimated biases, augmented
// sensor errors and scale factors (when FilterOptions asks for scale-factor states), the INS
// advances, and the fast inputs of the error dynamics and the
// white-noise covariances (mapped through C_nb) are accumulated. Once per covariance interval,
// and before any measurement, P is propagated over the accumulated interval. Every aid with a
// measurement at the epoch's time is then applied in turn; each accepted update is fed back at
// once (position, velocity, attitude, biases, scale factors, augmented states) and the error
// state reset. Aids get, besides the current state, the means of the INS velocity and attitude
// over the interval since their previous measurement epoch (plugin::InsInterval).
//
// The reference trajectory. When an aid states the tool's velocity (AidPlugin::states_velocity:
// ZUPT, ROP, the pipe tally), the attitude error's effect on the velocity is linearised about
// the velocity the aids state, v_ref (held from one statement to the next; at an epoch with
// several, the smallest speed: at rest wins), in the dynamics (d dv/dt = [f_ref x] phi, f_ref
// the specific force of the reference: its velocity changes, gravity, Coriolis) and in the aids'
// attitude columns (plugin::ImuSample::reference_v_n). The INS velocity and the measured specific
// force hold the INS's own velocity error and this epoch's accelerometer noise; about them,
// those errors read as attitude information: in a vertical hole or while sliding (no rotation
// to average them) the filter claimed a 1.8-deg azimuth and was 10-66 deg off. Model and truth
// then agree to first order: the error the INS velocity inherits from phi when the tool speeds
// up (phi x its velocity change) and the attitude term of a lateral constraint cancel in both
// (docs/drilling-envelope.md). Without such an aid the measured specific force is used (a
// vehicle's manoeuvres are what make its heading observable). The tool's vibration, which no aid
// states, is added to the reference (filter/velocity_oscillation.hpp): in the dynamics' coupling
// and the aids' attitude columns, while the interval aids take the INS velocity less it.
//
// Lifetime: the navigator keeps references to the plugins; they must outlive it.

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "stochnav/filter/block_diagonal_matrix.hpp"
#include "stochnav/filter/error_dynamics.hpp"
#include "stochnav/filter/error_state_filter.hpp"
#include "stochnav/filter/filter_options.hpp"
#include "stochnav/filter/ins_interval_accumulator.hpp"
#include "stochnav/filter/sparse_map.hpp"
#include "stochnav/filter/velocity_oscillation.hpp"
#include "stochnav/ins/nav_state.hpp"
#include "stochnav/ins/strapdown.hpp"
#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav {

/// One measurement update attempt, as recorded in innovations.csv.
struct InnovationRecord {
  double t_s = 0.0;       ///< time (s)
  int aid_index = 0;      ///< position of the aid in the run's list
  bool accepted = false;  ///< passed the NIS gate and S was positive definite
  double nis = 0.0;       ///< normalised innovation squared (NaN when S was singular)
  double log_det_s = 0.0; ///< ln det S (NaN when S was singular)
  int size = 0;           ///< measurement size m (<= kMaxSize)
  static constexpr int kMaxSize = 6;
  double innovation[kMaxSize] = {};        ///< z (aid units)
  double innovation_sigma[kMaxSize] = {};  ///< sqrt(diag S)
};

/// Whether the heading's bias-free information at attitude q_nb is second order: the tool axis
/// within about 8 deg of horizontal east-west, where FilterOptions::heading_considered holds
/// the heading as a consider state (mwd_navigator.cpp, heading_first_order_share).
bool heading_information_is_second_order(const Eigen::Quaterniond& q_nb);

class MwdNavigator final {
 public:
  /// `initial`: the initial navigation state (its t_s is the start time). The plugins are
  /// laid out in the error state here (set_placement); `aids` may be empty.
  MwdNavigator(const NavState& initial, plugin::NoiseModelPlugin& gyro_noise,
               plugin::NoiseModelPlugin& accel_noise, std::vector<plugin::AidPlugin*> aids,
               const FilterOptions& options);

  // Holds pointers to the plugins and into itself (the interval map's layout): a copy is made
  // by split() only, on plugins of its own.
  MwdNavigator& operator=(const MwdNavigator&) = delete;

  /// A copy of this navigator, everything it holds (the INS, P, the open aid intervals, the
  /// reference trajectory), run on its own plugins (built as this one's were: same models, same
  /// aid data; a plugin's own history, such as an adaptive model's, starts afresh), then
  /// corrected by the error state `correction` (n, fed back as an update's) and given the
  /// covariance `covariance` (n x n, symmetric positive definite), its
  /// FilterOptions::heading_considered set to `heading_considered`: a hypothesis split from a
  /// running filter (HeadingHypotheses). Throws std::invalid_argument when the plugins' layout
  /// or the sizes differ from this navigator's.
  std::unique_ptr<MwdNavigator> split(plugin::NoiseModelPlugin& gyro_noise,
                                      plugin::NoiseModelPlugin& accel_noise,
                                      std::vector<plugin::AidPlugin*> aids,
                                      const Eigen::VectorXd& correction,
                                      const Eigen::MatrixXd& covariance,
                                      bool heading_considered) const;

  /// Advances over one IMU epoch of raw (uncompensated) increments.
  void step(const ImuIncrement& raw);

  const NavState& state() const { return ins_.state(); }
  const Eigen::Vector3d& gyro_bias_b() const { return gyro_bias_b_; }    ///< rad/s
  const Eigen::Vector3d& accel_bias_b() const { return accel_bias_b_; }  ///< m/s^2
  /// The whole bias the navigator compensates now, per body axis: the bias state plus the noise
  /// model's augmented share M x (rad/s; m/s^2).
  Eigen::Vector3d gyro_total_bias_b() const;
  Eigen::Vector3d accel_total_bias_b() const;
  /// The covariance of the core states (core_state order, 15 x 15) with each bias state
  /// replaced by its whole bias, T P T^T: T takes the core rows and adds M to the bias rows at
  /// the augmented columns. What a new navigator whose augmented states start from their prior
  /// must start from to carry what this one knows of the sensor errors.
  Eigen::Matrix<double, 15, 15> core_covariance_with_total_biases() const;
  /// Everything a navigator of the same layout needs to continue this one from its state():
  /// the bias states, the augmented states and the whole P (FilterOptions::whole_start).
  FilterOptions::WholeStart whole_start() const;
  /// Scale-factor estimates per body axis (dimensionless; zero when not estimated).
  const Eigen::Vector3d& gyro_scale_factor() const { return gyro_scale_.estimate; }
  const Eigen::Vector3d& accel_scale_factor() const { return accel_scale_.estimate; }
  /// P of the error state (n x n), propagated up to the last covariance interval or update.
  const Eigen::MatrixXd& covariance() const { return filter_.covariance(); }
  const plugin::StateLayout& layout() const { return layout_; }
  /// The estimate of a sensor-error block of layout(), by its name: "accel_bias" (body,
  /// m/s^2), "gyro_bias" (body, rad/s), "gyro_scale_factor", "accel_scale_factor"
  /// (dimensionless, per body axis), "gyro.<type>", "accel.<type>" (a noise model's augmented
  /// states x, whose sensor error is M x: NoiseModelPlugin::augmented_sensor_map). The
  /// navigation blocks ("position", "velocity", "attitude") are state(): their error states are
  /// zero after every feedback. Throws std::invalid_argument for a navigation block or an unknown
  /// name, listing the blocks there are.
  Eigen::VectorXd block_estimate(std::string_view name) const;
  /// Block `name`'s rows and columns of covariance() (size x size, in the block's units; the
  /// navigation blocks too: "attitude" in rad^2). Throws std::invalid_argument for an unknown
  /// name.
  Eigen::MatrixXd block_covariance(std::string_view name) const;
  /// P at the current epoch: propagates the epochs since the last covariance interval now, as a
  /// measurement epoch does (the next interval starts here), and returns covariance(). A host
  /// that asks at every epoch propagates at every epoch.
  const Eigen::MatrixXd& covariance_now();
  const FilterHealth& health() const { return filter_.health(); }
  /// The update attempts of the last step.
  std::span<const InnovationRecord> innovations() const { return innovations_; }
  /// With FilterOptions::heading_considered: whether the heading is a consider state from the
  /// next step on, decided by the caller instead of by this navigator's own attitude. A bank
  /// over the heading decides for all its hypotheses alike (HeadingHypotheses), so that its
  /// weights compare innovations of filters that treat the heading the same way.
  /// std::nullopt: this navigator's attitude decides again.
  void hold_heading(std::optional<bool> held) { heading_held_ = held; }
  /// Whether the heading was a consider state at the last aid epoch.
  bool heading_held() const;

 private:
  MwdNavigator(const MwdNavigator&) = default;  // split() only

  struct AugmentedGroup {
    plugin::NoiseModelPlugin* model = nullptr;
    int offset = -1;
    int size = 0;
    Eigen::MatrixXd sensor_map;  // 3 x size
    Eigen::VectorXd estimate;    // nominal augmented states
    Eigen::MatrixXd phi, q_d;    // of the last interval, size x size
    // Structured covariance (FilterOptions::structured_covariance):
    BlockDiagonalStructure blocks;      // of phi and q_d, coarsened when a new pattern shows
    BlockDiagonalMatrix transition;     // phi on `blocks`
    BlockDiagonalMatrix noise;          // q_d on `blocks`
    double transition_interval_s = -1;  // phi, q_d are valid for it (time-invariant models)
    SparseMap sparse_sensor_map;        // sensor_map's nonzeros
    Eigen::Matrix3d coupling;           // +-C_nb_dt: Phi's group rows are coupling * M
    Eigen::VectorXd propagated;         // scratch, size
  };

  struct ScaleFactorBlock {
    int offset = -1;  // first index in the error state; -1 when not estimated
    Eigen::Vector3d estimate = Eigen::Vector3d::Zero();
  };
  IntervalMapLayout interval_map_layout() const;
  // The interval aid `index` reads (its own or the one it shares), and its restart at the aid's
  // measurement epoch: an aid sharing it inherits the sums, and the restarted one shares an
  // interval that starts at the same epoch.
  const InsIntervalAccumulator& aid_interval(std::size_t index) const;
  void restart_aid_interval(std::size_t index);
  // The measurement matrix of an aid that sees the error state only through its interval's
  // mean (AidPlugin::measures_interval_mean): h_core extended to the states beyond the core.
  const Eigen::MatrixXd& widened_measurement_matrix(const InsIntervalAccumulator& interval);

  void accumulate_noise(plugin::NoiseModelPlugin& model, double t_s, double dt_s,
                        const Eigen::Matrix3d& c_nb, Eigen::Matrix3d& cache, double& cached_dt,
                        Eigen::Matrix3d& sum);
  void propagate_covariance();
  void advance_augmented_groups(double interval);
  // True when the layout has a fixed-size kernel (filter/core_covariance.hpp) and P was
  // propagated by it.
  bool propagate_by_fixed_size_kernel(const CoreMatrix& f_t, double interval);
  template <int N>
  void propagate_fixed_size(const CoreMatrix& f_t, double interval);
  void propagate_by_dynamic_blocks(const CoreMatrix& f_t, double interval);
  CoreMatrix core_process_noise(double interval, const Eigen::Matrix3d& second_order_noise);
  struct SecondOrderTerm {
    Eigen::Matrix3d noise = Eigen::Matrix3d::Zero();  // rad^2 over the interval
    Eigen::Vector3d drift = Eigen::Vector3d::Zero();  // rad over the interval
  };
  SecondOrderTerm second_order_term(double interval) const;
  void feed_back_second_order_drift(const Eigen::Vector3d& drift);
  void close_interval(double interval);
  void add_position_shape_correction(Eigen::Ref<Eigen::MatrixXd> phi) const;
  void update_augmented_transition(AugmentedGroup& group, double interval_s);
  void apply_aids(double t_s, const Eigen::Vector3d& omega_ib_b, const Eigen::Vector3d& f_ib_b);
  Eigen::Vector3d reference_specific_force_increment(double dt_s,
                                                     const Eigen::Vector3d& measured_delta_v_n);
  void feed_back(const Eigen::VectorXd& correction);
  Eigen::Vector3d sensor_correction(const AugmentedGroup& group) const;

  plugin::NoiseModelPlugin* gyro_noise_;
  plugin::NoiseModelPlugin* accel_noise_;
  std::vector<plugin::AidPlugin*> aids_;
  std::vector<int> consecutive_rejections_;  ///< per aid, for FilterOptions' lockout rule
  std::optional<bool> heading_held_;         ///< hold_heading(); unset: this attitude's rule
  FilterOptions options_;
  plugin::StateLayout layout_;
  StrapdownIntegrator ins_;
  ErrorStateFilter filter_;
  Eigen::Vector3d gyro_bias_b_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias_b_ = Eigen::Vector3d::Zero();
  AugmentedGroup gyro_augmented_;
  AugmentedGroup accel_augmented_;
  ScaleFactorBlock gyro_scale_;
  ScaleFactorBlock accel_scale_;
  int head_size_ = 0;  // D: core + scale-factor states, the dense head before the augmented blocks
  Eigen::MatrixXd head_f_;                             // head_size_ x head_size_ scratch
  std::vector<InsIntervalAccumulator> aid_intervals_;  // per aid, since its previous epoch
  std::vector<std::size_t> interval_aids_;             // the aids that measure an interval mean
  // Interval aids whose intervals started at the same epoch hold the same sums (the pipe tally
  // and ROP, measuring every second): one of them accumulates, and the others read its sums.
  // Per aid: -1 for its own accumulator, else the aid whose accumulator it reads.
  std::vector<int> interval_shared_with_;
  IntervalMapLayout interval_layout_;
  Eigen::MatrixXd interval_map_;  // 3 x interval_layout_.width

  // Accumulated over the current covariance interval.
  double interval_start_s_ = 0.0;
  FastInputIntegrals fast_;
  Eigen::Matrix3d attitude_noise_ = Eigen::Matrix3d::Zero();  // integral of C Qw_g C^T (rad^2)
  Eigen::Matrix3d velocity_noise_ = Eigen::Matrix3d::Zero();  // integral of C Qw_a C^T
  Eigen::Matrix3d gyro_white_cache_, accel_white_cache_;      // Qw at cached dt (constant models)
  double gyro_cached_dt_ = -1.0;
  double accel_cached_dt_ = -1.0;
  Eigen::Matrix3d c_nb_;  // attitude at the start of the current epoch
  // The specific force the accelerometer scale-factor states multiply: ENU (m/s^2), smoothed
  // over kSpecificForceSmoothing_s (a mean over 10 s is gravity plus the manoeuvre, with the
  // white noise averaged out and no weight on the current aid interval's noise).
  static constexpr double kSpecificForceSmoothing_s = 10.0;
  static constexpr double kReferenceSmoothing_s = 100.0;
  Eigen::Vector3d smoothed_specific_force_n_;

  struct ReferenceTrajectory {
    bool active = false;                                         // some aid states the velocity
    Eigen::Vector3d v_n = Eigen::Vector3d::Zero();               // v_ref, ENU (m/s)
    Eigen::Vector3d pending_change_n = Eigen::Vector3d::Zero();  // since the last epoch (m/s)
    Eigen::Vector3d smoothed_acceleration_n = Eigen::Vector3d::Zero();    // m/s^2
    Eigen::Vector3d smoothed_specific_force_n = Eigen::Vector3d::Zero();  // m/s^2, measured
  };
  ReferenceTrajectory reference_;
  // The tool's vibration, which the reference lacks (FilterOptions::vibration_velocity_threshold).
  VelocityOscillation oscillation_;

  Eigen::MatrixXd phi_, q_d_;  // n x n scratch (D x D, the head, when structured)
  Eigen::Matrix3d bias_walk_;
  Eigen::VectorXd correction_;
  Eigen::VectorXd residual_;
  Eigen::MatrixXd h_core_, h_wide_, r_;
  std::vector<InnovationRecord> innovations_;
};

}  // namespace stochnav
