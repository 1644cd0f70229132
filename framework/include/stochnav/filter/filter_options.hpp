#pragma once
// Options of the MWD navigation filter (filter/mwd_navigator.hpp), with units. The run config's
// "filter" section (plugin/run_config.hpp) parses into this struct: the member initialisers
// below are THE defaults, of the library and of `stochnav run` / `compare` alike, and nowhere
// else are they written.

#include <Eigen/Core>
#include <numbers>
#include <optional>

namespace stochnav {

struct FilterOptions {
  /// P is propagated once per interval of this length (s), with the transition and noise of
  /// the whole interval accumulated from every IMU epoch in it (the fast inputs, C_nb and f_n,
  /// integrated exactly; see filter/error_dynamics.hpp). 0 propagates at every IMU epoch. The
  /// INS itself always runs at the IMU rate. At 0.1 s the covariance differs from the
  /// every-epoch propagation by far less than its own uncertainty (tests/filter).
  double covariance_interval_s = 0.1;

  /// After this many consecutive NIS-gate rejections of one aid, its next measurement is
  /// applied ungated. A gate must not lock the filter out of its aiding for good once the state
  /// has drifted past the gate (the classic gate lockout: rejected updates let the error grow,
  /// which makes the next NIS larger still). 0 keeps the gate strict. Three: for an aid at 1 Hz,
  /// three rejections in a row say the state has moved, not the aid. On the 4-h drilling record
  /// a 12-s excursion of the accelerometer noise (4 sigma in spin-free axes, 3 g vibration)
  /// pushed the ROP NIS past the gate: with 10 the velocity error grew to 0.022 m/s and the
  /// position error to 0.15 m before the aid came back; with 3, 0.012 m/s and 0.024 m.
  int max_consecutive_rejections = 3;

  // Initial 1-sigma uncertainties of the core error states. Chosen for a tool started from a
  // surveyed tie-on after a static alignment, erring on the side of too large: a too-small
  // initial sigma makes the filter optimistic from the first epoch (and its gate rejects the
  // aids that would correct it), a too-large one only costs the first minutes of convergence.
  //   position 0.1 m, velocity 0.01 m/s: a tie-on surveyed to decimetres, a tool at rest;
  //   attitude 1 mrad (0.057 deg) tilt, 10 mrad (0.57 deg) heading: what a FOG tool's static
  //     alignment delivers (tilt from the accelerometers, heading from gyrocompassing);
  //   accel bias 1e-3 m/s^2 (0.1 mg): the turn-on bias of a navigation-grade accelerometer;
  //   gyro bias 5e-6 rad/s (1.03 deg/h): covers the turn-on bias of the MWD FOG class
  //     (0.01 to 1 deg/h), so an unknown tool is not over-trusted; ZUPTs and the alignment
  //     shrink it within minutes. (The run config's former 0.05 deg/h was the in-run bias
  //     stability of a good FOG, not the uncertainty of its bias at turn-on.)
  Eigen::Vector3d position_sigma_m{0.1, 0.1, 0.1};          ///< ENU (m)
  Eigen::Vector3d velocity_sigma_mps{0.01, 0.01, 0.01};     ///< ENU (m/s)
  Eigen::Vector3d attitude_sigma_rad{1e-3, 1e-3, 1e-2};     ///< phi about E, N, U (rad)
  Eigen::Vector3d accel_bias_sigma_mps2{1e-3, 1e-3, 1e-3};  ///< body axes (m/s^2)
  Eigen::Vector3d gyro_bias_sigma_radps{5e-6, 5e-6, 5e-6};  ///< body axes (rad/s) (~1 deg/h)

  /// When set, the 15 x 15 core block of the initial P, correlations included (core_state
  /// order; a static alignment hands its final covariance over this way: the heading and the
  /// horizontal gyro biases are known together far better than apart). Its diagonal must agree
  /// with the sigmas above, which the run reports; the scale-factor and augmented blocks start
  /// as documented below.
  std::optional<Eigen::Matrix<double, 15, 15>> initial_core_covariance;

  /// When set, a navigator's whole start: the bias states, the noise models' augmented states
  /// and the whole initial P (StateLayout order), from a navigator of the same layout. A static
  /// alignment hands its end over this way (experiment/run/initial_state.cpp): a one-filter run
  /// continues the alignment's filter, so nothing it learned is dropped or counted twice. Takes
  /// precedence over the sigmas, initial_core_covariance and the initial biases below, which
  /// then describe the same start with each bias whole (bias state plus augmented share): the
  /// form the bank over the heading starts from (heading_hypotheses.cpp clears whole_start for
  /// its hypotheses, whose augmented states restart from their prior: the augmented share of the
  /// bias uncertainty is counted twice there, which is conservative).
  /// MwdNavigator throws std::invalid_argument when the sizes differ from its layout.
  struct WholeStart {
    Eigen::Vector3d gyro_bias_radps = Eigen::Vector3d::Zero();  ///< the bias state, body axes
    Eigen::Vector3d accel_bias_mps2 = Eigen::Vector3d::Zero();  ///< the bias state, body axes
    Eigen::VectorXd gyro_augmented;   ///< the gyro model's augmented states x
    Eigen::VectorXd accel_augmented;  ///< the accelerometer model's augmented states x
    Eigen::MatrixXd covariance;       ///< n x n, the whole error state's P
  };
  std::optional<WholeStart> whole_start;

  /// When the start comes from a static alignment: what its gyrocompass measured and assumed.
  /// The bank over the heading (filter/heading_hypotheses.hpp) gives each heading on the whole
  /// circle the gyro bias the static span's mean rate then implies and weighs it by how likely
  /// that bias is under the prior: the gyrocompass's exact posterior, which is far from Gaussian
  /// where the bias is as large as the horizontal Earth rate.
  struct StaticGyrocompass {
    Eigen::Vector3d mean_rate_radps = Eigen::Vector3d::Zero();   ///< static span, body axes
    Eigen::Vector3d bias_mean_radps = Eigen::Vector3d::Zero();   ///< prior before the span
    Eigen::Vector3d bias_sigma_radps = Eigen::Vector3d::Zero();  ///< core + augmented shares
  };
  std::optional<StaticGyrocompass> static_gyrocompass;

  // Initial estimates of the sensor biases (the navigator starts from these, not from zero):
  // a run started from an alignment hands over its bias estimates here, and a run config's
  // "initial_error" offsets them (the estimate's offset from where the filter would start).
  Eigen::Vector3d initial_accel_bias_mps2{0.0, 0.0, 0.0};  ///< body axes (m/s^2)
  Eigen::Vector3d initial_gyro_bias_radps{0.0, 0.0, 0.0};  ///< body axes (rad/s)

  // Scale-factor error states (plugin/state_layout.hpp: blocks "gyro_scale_factor" and
  // "accel_scale_factor", 3 states each, after the 15 core states): the sensor reads
  // (1 + s) times the true rate or specific force per body axis, s a random constant
  // (dimensionless; 1e-6 = 1 ppm). A group's 3 states exist when any of its sigmas is > 0; they
  // start at zero with these 1-sigma uncertainties. A tool rotating at 60 rpm turns a 10 ppm
  // z scale factor into a 13 deg/h apparent z bias while drilling that vanishes at every
  // connection: without these states the filter attributes it to the bias.
  Eigen::Vector3d gyro_scale_factor_sigma{0.0, 0.0, 0.0};   ///< body axes (dimensionless)
  Eigen::Vector3d accel_scale_factor_sigma{0.0, 0.0, 0.0};  ///< body axes (dimensionless)
  bool estimates_gyro_scale_factor() const { return (gyro_scale_factor_sigma.array() > 0.0).any(); }
  bool estimates_accel_scale_factor() const {
    return (accel_scale_factor_sigma.array() > 0.0).any();
  }

  /// Correlation time (s) of the attitude error's second-order rate, -1/2 [phi x]^2 omega_in
  /// (filter/second_order_attitude.hpp), added as process noise while the heading is uncertain
  /// by degrees, its mean fed back every covariance interval; 0 leaves the term out (the
  /// first-order filter). Without it, an east-west hole drilled
  /// from a field start at 46-80 deg latitude ended 4-7 sigma off in azimuth and north: the
  /// filter read an unmodelled tilt drift as heading information. The term is a random
  /// constant for as long as the heading error stays put; 900 s is the horizon of the
  /// levelling loop (ZUPT and ROP updates observe a tilt drift within minutes). 600-1200 s
  /// gave the same consistency on the envelope cases, 300 s and 7200 s did not
  /// (docs/drilling-envelope.md, section 4); with the heading known to 0.1 deg it adds
  /// nothing measurable.
  double second_order_attitude_correlation_s = 900.0;

  /// Heading 1-sigma (rad) of each hypothesis of the bank of filters over the heading
  /// (filter/heading_hypotheses.hpp) that a run forms when its start's heading sigma exceeds
  /// 2.5 times this (10 deg), or when the start's +-3 sigma headings reach the east-west mirror
  /// (then at most the start's sigma / 1.5 each); 0: one filter whatever the start (and no
  /// split of a running filter). After a static alignment the
  /// hypotheses cover the whole circle 2 sigmas apart (45 at 4 deg, fewer once the prior's
  /// unlikely headings are dropped). 8 deg was tried and is worse (docs/drilling-envelope.md,
  /// section 4).
  double heading_hypothesis_sigma_rad = 4.0 * std::numbers::pi / 180.0;

  /// The heading error (phi_U) as a consider state (ErrorStateFilter::consider) while the
  /// tool axis lies within about 8 deg of horizontal east-west: no update corrects it there, its
  /// uncertainty stays in P. Set by the bank over the heading for its hypotheses, whose heading
  /// is the bank's cell: in such a hole the heading's bias-free information is second order
  /// (the rotating cross-axis gyros see cos psi of the horizontal Earth rate), which the weights
  /// read over the whole bank and one first-order filter a few degrees off reads as first
  /// order. Elsewhere (a vertical start, any other direction) the cross axes give first-order
  /// information, and the heading is estimated (docs/drilling-envelope.md, section 4, fix 5).
  bool heading_considered = false;
  /// Whether the bank over the heading sets heading_considered for its hypotheses (run config
  /// "filter/heading_hypothesis_consider"; false: the ablation, under which 80 N east-west seed
  /// 3 ends 3.9 sigma off in azimuth). A consider heading everywhere, not only near east-west,
  /// discarded the first-order information of a vertical start at 80 N (azimuth sigma 6.5 deg
  /// instead of 0.15, north 5 sigma off; docs/drilling-envelope.md, section 4, fix 5).
  bool heading_hypotheses_consider_heading = true;
  /// Whether the bank decides the consider rule above for all its hypotheses alike (run config
  /// "filter/heading_hypothesis_hold_together"): the heading is held in every hypothesis while
  /// those near horizontal east-west carry at least half the weight, else estimated in every
  /// one. false, the ablation: each hypothesis decides by its own attitude, and held and
  /// estimated neighbours are weighed by innovations whose S differ by that alone
  /// (docs/drilling-envelope.md, section 7).
  bool heading_hypotheses_hold_together = true;
  /// Whether one running filter splits into a bank when its heading comes to need one (run
  /// config "filter/heading_hypothesis_split_running"): checked at every epoch by the rule a
  /// start is checked by (heading sigma above 2.5 hypothesis sigmas, or above 0.25 deg with the
  /// +-3-sigma heading interval across the east-west line at an inclination above 60 deg; once
  /// split, only after growing past 1.5 times the hypotheses' sigma). A well that turns
  /// east-west, or whose heading sigma grows there, meets the mirror (heading_hypotheses.cpp)
  /// as a start would. false, the ablation: the test is made at the start only
  /// (docs/drilling-envelope.md, section 7).
  bool heading_hypotheses_split_running = true;
  /// Whether the east-west mirror test waits for the tool to rotate (run config
  /// "filter/heading_hypothesis_mirror_at_rotation"): made only while the tool has turned a
  /// full turn about its axis, net, within the last 10 min (filter/net_rotation_window.hpp; the
  /// mirror is a rotating tool's), so a start is not split on the mirror's account and a
  /// running filter is split at its first rotation if its heading interval still reaches the
  /// line. Without heading_hypotheses_split_running the start is tested as under false, the
  /// ablation: the test is made at the start and at every epoch, sliding or not (a sliding
  /// east-west well then keeps 6-8 hypotheses for hours; docs/drilling-envelope.md, section 7).
  bool heading_hypotheses_mirror_at_rotation = true;
  /// Whether the bank's weights are robust to aid outliers (run config "filter/heading_
  /// hypothesis_robust_weights"): an innovation gated out by every hypothesis does not weigh
  /// them (the aid, not a heading, failed there), and each one that does counts by a Student-t
  /// likelihood with 5 degrees of freedom, whose influence is bounded, instead of a Gaussian
  /// one. Under axial vibration at 8.37 Hz the ROP's innovations were gated out 362 times in
  /// 10 min (NIS 154 on average); read as Gaussian, differences of a part in a thousand in S
  /// between hypotheses collapsed the bank onto a heading 24 deg off (weight 0.995) on a
  /// sliding well at 74 N (docs/drilling-envelope.md, section 4, fix 6). false: the ablation.
  bool heading_hypotheses_robust_weights = true;
  /// The power to which the bank's weights raise each aid epoch's innovation likelihood (run
  /// config "filter/heading_hypothesis_likelihood_power", in [0.05, 1]; 1: the full Bayesian
  /// likelihood, the ablation). Successive innovations of the aids are not independent (lag-1
  /// autocorrelation -0.49 for the pipe tally, +0.36 for ROP along the hole), and hypotheses
  /// that explain the data almost equally well then trade weight back and forth on the full
  /// likelihood: on a 160-rpm east-west well at 57 N two hypotheses at the truth and at its
  /// east-west mirror went from 0.28 / 0.70 to 0.04 / 0.96 and back to 0.84 / 0.16 in 2.5 h,
  /// the mixture 4.5 sigma off meanwhile; with 1/2 it is inside (docs/drilling-envelope.md,
  /// section 7). The one value tried besides 1 and 1/4.
  double heading_hypotheses_likelihood_power = 0.5;

  /// RMS (m/s) above which the INS velocity's oscillation (filter/velocity_oscillation.hpp: its
  /// part above about 1 Hz, axial vibration of the string) enters the velocity-attitude coupling
  /// beside the reference trajectory the aids state (run config "filter/vibration_velocity_
  /// threshold_m_s"; 0: never, the ablation). Without it a 9-min episode of 2.8 g at 8 Hz moved
  /// the bank over the heading of a sliding east-west well at 74 N by 15-35 deg and halved its
  /// sigma (docs/drilling-envelope.md, section 4, fix 7). 0.02 is 40 times the INS velocity noise
  /// in that band and a thirtieth of that episode's oscillation; the one value tried.
  double vibration_velocity_threshold_mps = 0.02;

  /// Covariance products by blocks (filter/error_state_filter.hpp, BlockTransition and
  /// JosephForm::kExpanded): augmented states cost O(n^2) per propagation and update instead of
  /// O(n^3), with the same results to rounding. false: the dense products, kept as the
  /// reference for tests and benchmarks.
  bool structured_covariance = true;
};

}  // namespace stochnav
