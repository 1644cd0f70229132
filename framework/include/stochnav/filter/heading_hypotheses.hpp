#pragma once
// A bank of navigation filters over the heading (a Gaussian sum), for a start that leaves the
// heading uncertain by more than 10 deg, and for a running filter whose heading comes to need it
// (below): uncertain by more than a quarter of a degree within reach of the east-west mirror
// while the tool rotates (heading_hypotheses.cpp: a rotating tool's cross axes cannot tell psi
// from 180 deg - psi; there the hypotheses are at most the filter's sigma / 1.5 wide), or by
// more than 10 deg. The first case: a static alignment at high latitude, where the
// horizontal Earth rate is a fraction of the equator's (80 N: a sixth) and a FOG's turn-on bias
// may be as large. The gyrocompass's heading is then far from Gaussian (seed 1 at 80 N: 120 deg
// off while the linearised fine alignment said 18 +- 18), and one extended Kalman filter
// linearised about it converged 3 deg off with a sigma of 0.6 (docs/drilling-envelope.md,
// section 4). Each hypothesis starts with a heading sigma small enough for the first-order model
// (plus the second-order term, filter/second_order_attitude.hpp) to hold.
//
// The split after a static alignment (FilterOptions::static_gyrocompass set): headings
// over the whole circle, 2 s_c apart (s_c: FilterOptions::heading_hypothesis_sigma_rad, or
// narrower on the mirror's account). With
// m the static span's mean rate, hypothesis i turns the aligned attitude by d_i about the
// vertical and carries the gyro bias the span then implies, b_i = m - C_bn(d_i) w_ie, exactly;
// its prior weight is the bias prior's density at b_i (the gyrocompass's posterior); its
// covariance is the start's conditioned on the heading, plus s_c^2 along the direction in which
// the heading moves b_i. Without an alignment: the start's Gaussian split along its heading on a
// grid 2 s_c apart over +-3 start sigmas s0, each hypothesis conditioned on its heading linearly
// (corrected by P0 e_U d_i / s0^2, covariance P0 - (1 - s_c^2 / s0^2) P0 e_U e_U^T P0 / s0^2,
// weight exp(-d_i^2 / (2 (s0^2 - s_c^2))): N(0, P0) to within 1.5 % in density).
//
// A running filter (FilterOptions::heading_hypotheses_split_running) is checked at every epoch:
// a heading sigma s above 10 deg, or above a quarter of a degree with its +-3 s headings across
// the east-west line at an inclination above 60 deg while the tool rotates (a full turn about
// its axis, net, within the last 10 min, FilterOptions::heading_hypotheses_mirror_at_rotation:
// the first rotation after a still start, a well turned east-west, a heading uncertainty grown
// there), and above 1.5 times its hypotheses' sigma if it was split before, splits it as a start
// without an alignment is, each hypothesis a whole copy of the filter (MwdNavigator::split: its
// augmented states, open aid intervals and reference trajectory) corrected along the heading,
// with the conditioned covariance.
//
// In a horizontal east-west hole each hypothesis holds its heading as a consider state
// (FilterOptions::heading_considered, ::heading_hypotheses_consider_heading): no update corrects
// it, its cell's uncertainty stays in P and in the innovations' S. There the heading's
// bias-free information is second order (the rotating cross-axis gyros see cos psi of the
// horizontal Earth rate; to first order the along-hole gyro bias and the heading are one
// unknown); a first-order filter a few degrees from the truth read it as first order and ended
// 2.2 deg off with a sigma of 0.8 (80 N, seed 3); with consider headings the weights read it
// over the whole bank, and the heading's resolution is the cell. In any other direction the
// cross axes give first-order information and the heading is estimated. The bank decides for
// all its hypotheses alike (FilterOptions::heading_hypotheses_hold_together): every one holds
// its heading while those near east-west carry at least half the weight, and every one
// estimates it otherwise. Decided per hypothesis, held cells (their heading variance growing)
// and estimated neighbours (theirs shrinking) were weighed by innovations whose S differed by
// that treatment alone, and the held cells nearest the truth lost.
//
// The weights. At every aid epoch each hypothesis' weight is multiplied by the likelihood of
// its innovations raised to a power (FilterOptions::heading_hypotheses_likelihood_power, 1/2:
// successive innovations are not independent), gated out or not (an aid counts only at epochs
// where every hypothesis measured it, so that the weights compare like with like): a
// Student-t of 5 degrees of freedom with scale S, robust to outliers, where an innovation
// every hypothesis gated out is left out (FilterOptions::heading_hypotheses_robust_weights);
// N(z; 0, S) without. The Gaussian reads an outlier's NIS at full weight, so that differences
// of a part in a thousand in S between hypotheses become decisive: 362 gated-out ROP
// innovations in a vibration episode at 8.37 Hz (NIS 154) collapsed a sliding well's bank at
// 74 N onto a heading 24 deg off. A hypothesis below 1e-5 of the total is dropped; two whose
// headings agree to a fifth of a sigma merge (the weights add). Once one is left the bank is
// that filter.
//
// The outputs are the mixture's: the mean (about the most probable hypothesis, as an error
// state) and the covariance sum_i w_i (P_i + (x_i - x)(x_i - x)^T) of the 15 core states.
// Innovations and health are the most probable hypothesis'. With one hypothesis (a start
// whose heading sigma is below 2.5 s_c, or s_c = 0) every output is that filter's own, until it
// splits. Each hypothesis is a whole navigator: a bank that cannot single out a heading (sliding
// east-west at 74 N: 21 hypotheses after 8 h) costs that many filters.

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "stochnav/filter/core_correction.hpp"
#include "stochnav/filter/filter_options.hpp"
#include "stochnav/filter/mwd_navigator.hpp"
#include "stochnav/filter/net_rotation_window.hpp"

namespace stochnav {

/// The plugins of one navigator, owned with it.
struct NavigatorPlugins {
  std::shared_ptr<plugin::NoiseModelPlugin> gyro;
  std::shared_ptr<plugin::NoiseModelPlugin> accel;
  std::vector<std::shared_ptr<plugin::AidPlugin>> aids;
};

class HeadingHypotheses final {
 public:
  /// `first` serves the first hypothesis; `make_plugins` builds an independent set for each
  /// further one (plugins may hold state). `initial` and `options` as for MwdNavigator.
  HeadingHypotheses(const NavState& initial, const FilterOptions& options, NavigatorPlugins first,
                    const std::function<NavigatorPlugins()>& make_plugins);

  HeadingHypotheses(const HeadingHypotheses&) = delete;
  HeadingHypotheses& operator=(const HeadingHypotheses&) = delete;

  /// Advances every hypothesis over one IMU epoch of raw increments and reweighs them.
  void step(const ImuIncrement& raw);

  /// The mixture's mean estimate.
  const NavState& state() const;
  const Eigen::Vector3d& gyro_bias_b() const;   ///< rad/s
  const Eigen::Vector3d& accel_bias_b() const;  ///< m/s^2
  /// The mixture covariance: 15 x 15 (the core states) with several hypotheses; with one, the
  /// filter's own n x n P.
  const Eigen::MatrixXd& covariance() const;
  /// The update attempts of the last step, of the most probable hypothesis.
  std::span<const InnovationRecord> innovations() const;
  const FilterHealth& health() const;

  std::size_t initial_hypotheses() const { return initial_count_; }
  /// How many times one running filter split into a bank
  /// (FilterOptions::heading_hypotheses_split_running).
  std::size_t splits() const { return splits_; }
  std::size_t hypotheses() const { return hypotheses_.size(); }
  /// The normalised weight of the most probable hypothesis.
  double largest_weight() const;
  /// The most probable hypothesis' filter.
  const MwdNavigator& most_probable() const;
  /// The span of the hypotheses' headings (rad): the largest less the smallest heading
  /// difference from the most probable one; 0 with one hypothesis.
  double heading_span_rad() const;
  /// The normalised weight of the hypotheses whose heading lies within `half_width_rad` of the
  /// most probable one's (itself included).
  double weight_within_rad(double half_width_rad) const;
  /// Hypothesis i's filter and normalised weight (i < hypotheses()).
  const MwdNavigator& hypothesis(std::size_t i) const { return *hypotheses_.at(i).navigator; }
  double weight(std::size_t i) const;

 private:
  struct Hypothesis {
    NavigatorPlugins plugins;
    std::unique_ptr<MwdNavigator> navigator;
    double log_weight = 0.0;
  };
  void split_running_filter(double sigma);
  // Hypothesis i's heading less the most probable one's (rad), as an error state.
  double heading_from_most_probable_rad(std::size_t i) const;
  void hold_headings(const std::vector<double>& weights, double total);
  void reweigh();
  void prune_and_merge();
  void update_mixture();

  std::vector<Hypothesis> hypotheses_;
  std::function<NavigatorPlugins()> make_plugins_;
  double hypothesis_sigma_rad_ = 0.0;  // FilterOptions::heading_hypothesis_sigma_rad
  double last_split_sigma_rad_ = 0.0;  // the hypotheses' heading sigma at the last split
  bool split_running_ = true;          // FilterOptions::heading_hypotheses_split_running
  bool mirror_at_rotation_ = true;     // FilterOptions::heading_hypotheses_mirror_at_rotation
  NetRotationWindow rotation_;         // the tool's net rotation about its axis, last 10 min
  bool consider_heading_ = true;       // FilterOptions::heading_hypotheses_consider_heading
  std::size_t splits_ = 0;
  bool robust_weights_ = true;  // FilterOptions::heading_hypotheses_robust_weights
  bool hold_together_ = true;   // FilterOptions::heading_hypotheses_hold_together
  double likelihood_power_ = 0.5;  // FilterOptions::heading_hypotheses_likelihood_power
  std::size_t initial_count_ = 1;
  std::size_t best_ = 0;
  CoreEstimate mixture_;
  Eigen::MatrixXd mixture_covariance_;
};

}  // namespace stochnav
