#include "stochnav/filter/heading_hypotheses.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/strapdown.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav {
namespace {

namespace core = plugin::core_state;
constexpr int kHeading = core::kAttitude + 2;  // phi_U
// A bank is formed when the start's heading sigma exceeds this many hypothesis sigmas (10 deg
// at the default 4): below it one first-order filter with the second-order attitude term is
// consistent (docs/drilling-envelope.md, section 4: aligned starts of 5.7-7.9 deg at 60 N),
// unless it rotates with its heading interval within reach of the east-west mirror (below).
constexpr double kSplitAbove = 2.5;
// The east-west mirror. A rotating tool's cross-axis gyros measure the Earth rate across the
// tool axis free of their biases: the lateral part omega_N sin(psi) and, on the high side,
// a part in omega_N cos(psi) cos(I). The headings psi and 180 deg - psi give the same lateral
// part; only the high side's cos(I) share and the along-hole gyro, one unknown with its bias,
// tell them apart. Where the tool axis is near horizontal east-west, one linearised filter
// that starts on the other side of the east-west line from the truth settles near the mirror
// at a sigma the mirror's data support (120 rpm, 57 N, inclination 82, azimuth 87 turning to
// 83: 94.4 deg estimated against a truth of 83.4, the mirror at 96.6; the heading sigma 0.3 deg;
// docs/drilling-envelope.md, section 7). A bank reads the two sides through its weights, so
// one rotating filter is split whenever its +-3 sigma heading interval crosses the east-west
// line with the inclination above 60 deg (|cos I|, the share of the heading's information that
// is first order on that line, below this), at any heading sigma above
// kMirrorFloor: a start of 3.5 deg, 7 deg across the line (2 sigma), settled 5.5 deg off at a
// sigma of 0.6 (north 3.5 m against 0.4) as one filter (section 7).
constexpr double kMirrorShareBelow = 0.5;
// A filter that settles on the mirror is off by twice its distance from the line, at most 6 of
// its sigmas: 1.5 deg for a quarter of a degree, inside 3 sigma of the 0.6 deg such a filter
// converges to in 2.5 h at 57 N, 160 rpm.
constexpr double kMirrorFloor = 0.25 * std::numbers::pi / 180.0;
// The heading sigma s split on the mirror's account against its hypotheses' s_h. Their grid is
// 2 s_h apart and the middle one's neighbours get exp(-2 s_h^2 / (s^2 - s_h^2)) of its weight:
// at s = 1.5 s_h a fifth, below a tenth under s = 1.37 s_h, where they are soon dropped or
// merged and the bank is one filter again. So the hypotheses are at most s / 1.5 wide, and a
// filter that was split before is split again only once its heading sigma has grown past 1.5
// times its hypotheses' (a survivor held as a consider state near east-west grows; one that
// estimates its heading does not), not at every epoch.
constexpr double kMirrorSplitAbove = 1.5;
// The mirror needs a rotating tool: with the tool still or sliding, the cross-axis gyros' biases
// and the Earth rate across the tool axis are one unknown, the heading's information there is
// weak on both sides of the line, and a filter does not settle on either side. So (by default,
// FilterOptions::heading_hypotheses_mirror_at_rotation) the mirror test is made only while the
// tool rotates: one full turn, net, within the last 10 min (filter/net_rotation_window.hpp). A
// sliding east-west well split at its start kept 6-8 hypotheses of 2-3 deg for hours and ended
// with the azimuth sigma 1.8 times one filter's (docs/drilling-envelope.md, section 7); a filter
// that starts rotating with its heading interval still across the line is split then.
constexpr double kSpreadSigmas = 3.0;  // the grid covers +-3 start sigmas
constexpr int kMaxHalfWidth = 7;       // at most 15 hypotheses
constexpr double kDropBelow = 1e-5;    // of the total weight
constexpr double kMergeWithin = 0.2;   // heading sigmas
// Degrees of freedom of the robust weights' Student-t likelihood. Its influence on a weight,
// d ln L / d NIS, is (nu + m) / (nu + NIS) times the Gaussian's: the same at NIS = m, a
// twentieth at NIS 154 (m = 3). The one value tried.
constexpr double kWeightDof = 5.0;

// ln of one innovation's likelihood, up to a constant the hypotheses share: Gaussian,
// -(nis + ln det S) / 2, or (robust) Student-t, -((nu + m) ln(1 + nis / nu) + ln det S) / 2.
double log_likelihood(const InnovationRecord& record, bool robust) {
  if (!robust) return -0.5 * (record.nis + record.log_det_s);
  return -0.5 * ((kWeightDof + record.size) * std::log1p(record.nis / kWeightDof) +
                 record.log_det_s);
}

Eigen::Matrix<double, 15, 15> core_start_covariance(const FilterOptions& o) {
  if (o.initial_core_covariance) return *o.initial_core_covariance;
  Eigen::Matrix<double, 15, 1> sigma;
  sigma << o.position_sigma_m, o.velocity_sigma_mps, o.attitude_sigma_rad,
      o.accel_bias_sigma_mps2, o.gyro_bias_sigma_radps;
  return sigma.array().square().matrix().asDiagonal();
}

std::vector<plugin::AidPlugin*> raw_aids(const NavigatorPlugins& plugins) {
  std::vector<plugin::AidPlugin*> aids;
  for (const auto& aid : plugins.aids) aids.push_back(aid.get());
  return aids;
}

std::unique_ptr<MwdNavigator> make_navigator(const NavState& start, const FilterOptions& options,
                                             NavigatorPlugins& plugins) {
  return std::make_unique<MwdNavigator>(start, *plugins.gyro, *plugins.accel, raw_aids(plugins),
                                        options);
}

// One hypothesis' start: its estimate, covariance and prior log-weight.
struct SplitStart {
  CoreEstimate estimate;
  Eigen::Matrix<double, 15, 15> covariance;
  double log_weight = 0.0;
};

FilterOptions with_start(const FilterOptions& options, const SplitStart& start) {
  FilterOptions split = options;
  split.initial_core_covariance = start.covariance;
  split.whole_start.reset();  // each hypothesis starts with the whole bias in its bias state
  const Eigen::Matrix<double, 15, 1> sigma = start.covariance.diagonal().cwiseSqrt();
  split.position_sigma_m = sigma.segment<3>(core::kPosition);
  split.velocity_sigma_mps = sigma.segment<3>(core::kVelocity);
  split.attitude_sigma_rad = sigma.segment<3>(core::kAttitude);
  split.accel_bias_sigma_mps2 = sigma.segment<3>(core::kAccelBias);
  split.gyro_bias_sigma_radps = sigma.segment<3>(core::kGyroBias);
  split.initial_accel_bias_mps2 = start.estimate.accel_bias_b;
  split.initial_gyro_bias_radps = start.estimate.gyro_bias_b;
  split.heading_considered = options.heading_hypotheses_consider_heading;
  return split;
}

// A Gaussian of covariance P split along its heading (variance s0^2 = P_UU) into hypotheses of
// heading sigma s_c on a grid of spacing 2 s_c over +-3 s0 (at most kMaxHalfWidth each side),
// each conditioned linearly on its heading: hypothesis i is corrected by gain d_i (gain =
// P e_U / s0^2, d_i = i spacing) and has the covariance P - (1 - s_c^2 / s0^2) gain e_U^T P and
// the prior log-weight -d_i^2 / (2 (s0^2 - s_c^2)). For the start's fixed-size core (15 x 15)
// and a running filter's whole P alike.
template <typename Covariance>
struct HeadingGrid {
  Eigen::Matrix<double, Covariance::RowsAtCompileTime, 1> gain;
  Covariance conditioned;
  double spacing = 0.0;
  int half_width = 0;
  double residual_variance = 0.0;

  double heading_error(int i) const { return i * spacing; }
  double log_weight(int i) const {
    return -0.5 * heading_error(i) * heading_error(i) / residual_variance;
  }
};

template <typename Covariance>
HeadingGrid<Covariance> heading_grid(const Covariance& p, double sigma) {
  HeadingGrid<Covariance> grid;
  const double variance = p(kHeading, kHeading);
  grid.spacing = 2.0 * sigma;
  grid.half_width = std::min(
      kMaxHalfWidth,
      static_cast<int>(std::ceil(kSpreadSigmas * std::sqrt(variance) / grid.spacing)));
  grid.gain = p.col(kHeading) / variance;
  grid.conditioned = p - (1.0 - sigma * sigma / variance) * grid.gain * p.row(kHeading);
  grid.conditioned = 0.5 * (grid.conditioned + grid.conditioned.transpose()).eval();
  grid.residual_variance = variance - sigma * sigma;
  return grid;
}

// Without an alignment prior: the start's Gaussian split along its heading (heading_grid).
std::vector<SplitStart> linear_split(const CoreEstimate& start,
                                     const Eigen::Matrix<double, 15, 15>& p0, double sigma) {
  const HeadingGrid grid = heading_grid(p0, sigma);
  std::vector<SplitStart> starts;
  for (int i = -grid.half_width; i <= grid.half_width; ++i) {
    SplitStart split{start, grid.conditioned, grid.log_weight(i)};
    apply_core_correction(grid.gain * grid.heading_error(i), split.estimate);
    starts.push_back(std::move(split));
  }
  return starts;
}

// After a static alignment: headings over the whole circle, each with the gyro bias the static
// data then imply. The static span's mean rate is m = C_bn w_ie + b; hypothesis i turns the
// aligned attitude by d_i about the vertical (C_nb_i = Rot(d_i e_U) C_nb), so its bias is
// b_i = m - C_bn_i w_ie, exactly, not linearised about the aligned heading (and all of it in the
// bias state, as fine_alignment hands it over: the augmented states restart from their prior).
// Its prior weight is the bias prior's density at b_i (the static data's noise is negligible
// beside it): the gyrocompass's posterior. Its covariance is the start's conditioned on the
// heading, plus a heading sigma s_c along the direction in which the heading moves that bias.
std::vector<SplitStart> circle_split(const CoreEstimate& start,
                                     const Eigen::Matrix<double, 15, 15>& p0, double sigma,
                                     const FilterOptions::StaticGyrocompass& gyrocompass) {
  const int count = static_cast<int>(std::ceil(2.0 * std::numbers::pi / (2.0 * sigma)));
  const double spacing = 2.0 * std::numbers::pi / count;
  const Eigen::Vector3d earth_rate = earth_rate_n(start.state.latitude_rad);
  const Eigen::Matrix3d c_bn = start.state.q_nb.toRotationMatrix().transpose();
  const auto bias_at = [&](double heading_error) -> Eigen::Vector3d {
    const Eigen::Matrix3d turn =
        quaternion_from_rotation_vector(heading_error * Eigen::Vector3d::UnitZ())
            .toRotationMatrix();
    return gyrocompass.mean_rate_radps - c_bn * turn.transpose() * earth_rate;
  };
  Eigen::Matrix<double, 15, 15> conditioned =
      p0 - p0.col(kHeading) * p0.row(kHeading) / p0(kHeading, kHeading);
  conditioned = 0.5 * (conditioned + conditioned.transpose()).eval();
  std::vector<SplitStart> starts;
  for (int i = 0; i < count; ++i) {
    const double heading_error = std::remainder(i * spacing, 2.0 * std::numbers::pi);
    SplitStart split{start, conditioned, 0.0};
    split.estimate.state.q_nb =
        (quaternion_from_rotation_vector(heading_error * Eigen::Vector3d::UnitZ()) *
         start.state.q_nb)
            .normalized();
    split.estimate.gyro_bias_b = bias_at(heading_error);
    const Eigen::Vector3d standardised =
        (split.estimate.gyro_bias_b - gyrocompass.bias_mean_radps)
            .cwiseQuotient(gyrocompass.bias_sigma_radps);
    split.log_weight = -0.5 * standardised.squaredNorm();
    // d(estimate)/d(heading): the heading itself and, through the Earth rate, the gyro bias.
    Eigen::Matrix<double, 15, 1> direction = Eigen::Matrix<double, 15, 1>::Zero();
    direction(kHeading) = 1.0;
    constexpr double kStep = 1e-4;  // rad
    // x = estimate - truth: a heading error d + e means the truth's bias is b(d + e).
    direction.segment<3>(core::kGyroBias) =
        -(bias_at(heading_error + kStep) - bias_at(heading_error - kStep)) / (2.0 * kStep);
    split.covariance += sigma * sigma * direction * direction.transpose();
    starts.push_back(std::move(split));
  }
  return starts;
}

// Whether the headings within +-reach_rad of this attitude's cross the east-west line at an
// inclination that leaves the heading's first-order information there (|cos I| of it) below
// kMirrorShareBelow. From the tool axis in ENU (C_nb's third column, ins/mwd_attitude.hpp):
// cos I is minus its up component, and the azimuth's distance from the east-west line is the
// angle of its horizontal part from that line. Checked at every epoch of a running filter: the
// inclination first, with no trigonometry.
bool reaches_east_west_mirror(const Eigen::Quaterniond& q_nb, double reach_rad) {
  const Eigen::Vector3d tool_axis_n = q_nb * Eigen::Vector3d::UnitZ();
  if (!(std::abs(tool_axis_n.z()) < kMirrorShareBelow)) return false;
  return std::atan2(std::abs(tool_axis_n.y()), std::abs(tool_axis_n.x())) < reach_rad;
}

// The heading sigma of the hypotheses one filter of heading variance s^2 is split into, or 0 for
// no split (s_c the hypothesis sigma): s_c when s is wider than one first-order filter can
// hold; at most s / kMirrorSplitAbove when `mirror_possible` (the tool rotates), its heading
// interval reaches the east-west mirror, s is above kMirrorFloor and above kMirrorSplitAbove
// times `last_split_sigma`, the sigma of the hypotheses this filter was split into before
// (0: never).
double split_hypothesis_sigma(const NavState& state, double heading_variance, double sigma,
                              double last_split_sigma, bool mirror_possible) {
  if (!(sigma > 0.0)) return 0.0;
  if (heading_variance > std::pow(kSplitAbove * sigma, 2)) return sigma;
  if (!mirror_possible) return 0.0;
  const double heading_sigma = std::sqrt(heading_variance);
  if (heading_sigma > kMirrorFloor && heading_sigma > kMirrorSplitAbove * last_split_sigma &&
      reaches_east_west_mirror(state.q_nb, kSpreadSigmas * heading_sigma)) {
    return std::min(sigma, heading_sigma / kMirrorSplitAbove);
  }
  return 0.0;
}

}  // namespace

HeadingHypotheses::HeadingHypotheses(const NavState& initial, const FilterOptions& options,
                                     NavigatorPlugins first,
                                     const std::function<NavigatorPlugins()>& make_plugins) {
  const Eigen::Matrix<double, 15, 15> p0 = core_start_covariance(options);
  make_plugins_ = make_plugins;
  hypothesis_sigma_rad_ = options.heading_hypothesis_sigma_rad;
  split_running_ = options.heading_hypotheses_split_running;
  consider_heading_ = options.heading_hypotheses_consider_heading;
  robust_weights_ = options.heading_hypotheses_robust_weights;
  hold_together_ = options.heading_hypotheses_hold_together;
  likelihood_power_ = options.heading_hypotheses_likelihood_power;
  // Waiting for the rotation needs a running filter that can split.
  mirror_at_rotation_ = options.heading_hypotheses_mirror_at_rotation && split_running_;
  const bool after_alignment = options.static_gyrocompass &&
                               (options.static_gyrocompass->bias_sigma_radps.array() > 0.0).all();
  // Whether the tool rotates is not known before its first epoch.
  const double sigma = split_hypothesis_sigma(initial, p0(kHeading, kHeading),
                                              hypothesis_sigma_rad_, 0.0, !mirror_at_rotation_);
  last_split_sigma_rad_ = sigma;
  if (sigma == 0.0) {
    hypotheses_.push_back({std::move(first), nullptr, 0.0});
    hypotheses_.back().navigator = make_navigator(initial, options, hypotheses_.back().plugins);
    return;
  }
  const CoreEstimate start{initial, options.initial_accel_bias_mps2,
                           options.initial_gyro_bias_radps};
  std::vector<SplitStart> starts =
      after_alignment ? circle_split(start, p0, sigma, *options.static_gyrocompass)
                   : linear_split(start, p0, sigma);
  // Only the hypotheses the prior leaves a chance need a filter.
  double largest = -INFINITY;
  for (const SplitStart& s : starts) largest = std::max(largest, s.log_weight);
  std::erase_if(starts, [&](const SplitStart& s) {
    return s.log_weight - largest < std::log(kDropBelow);
  });
  bool first_used = false;
  for (const SplitStart& split : starts) {
    Hypothesis hypothesis{first_used ? make_plugins() : std::move(first), nullptr,
                          split.log_weight};
    first_used = true;
    hypothesis.navigator =
        make_navigator(split.estimate.state, with_start(options, split), hypothesis.plugins);
    hypotheses_.push_back(std::move(hypothesis));
  }
  initial_count_ = hypotheses_.size();
  prune_and_merge();
  update_mixture();
}

void HeadingHypotheses::step(const ImuIncrement& raw) {
  for (Hypothesis& hypothesis : hypotheses_) hypothesis.navigator->step(raw);
  if (mirror_at_rotation_) rotation_.add(raw.t_s, raw.delta_theta_b.z());
  if (hypotheses_.size() == 1) {
    if (!split_running_) return;
    const MwdNavigator& running = *hypotheses_.front().navigator;
    const bool mirror_possible = !mirror_at_rotation_ || rotation_.rotating();
    const double sigma = split_hypothesis_sigma(
        running.state(), running.covariance()(kHeading, kHeading), hypothesis_sigma_rad_,
        last_split_sigma_rad_, mirror_possible);
    if (sigma > 0.0) split_running_filter(sigma);
    return;
  }
  reweigh();
  prune_and_merge();
  update_mixture();
}

// One running filter whose heading now needs the bank (split_hypothesis_sigma): its whole state
// split along the heading as a start without an alignment is (linear_split), into hypotheses of
// heading sigma `sigma`, each a copy of the filter (MwdNavigator::split: its open aid intervals,
// reference trajectory and augmented states carried over) corrected by P e_U d_i / s^2 with the
// conditioned covariance, on the grid of spacing 2 sigma over +-3 s. The middle one keeps the
// running filter's plugins.
void HeadingHypotheses::split_running_filter(double sigma) {
  Hypothesis running = std::move(hypotheses_.front());
  hypotheses_.clear();
  const MwdNavigator& filter = *running.navigator;
  const HeadingGrid grid = heading_grid(filter.covariance(), sigma);
  for (int i = -grid.half_width; i <= grid.half_width; ++i) {
    Hypothesis hypothesis{i == 0 ? running.plugins : make_plugins_(), nullptr,
                          grid.log_weight(i)};
    hypothesis.navigator = filter.split(*hypothesis.plugins.gyro, *hypothesis.plugins.accel,
                                        raw_aids(hypothesis.plugins),
                                        grid.gain * grid.heading_error(i), grid.conditioned,
                                        consider_heading_);
    hypotheses_.push_back(std::move(hypothesis));
  }
  ++splits_;
  last_split_sigma_rad_ = sigma;
  prune_and_merge();
  update_mixture();
}

// The consider rule of FilterOptions::heading_considered, decided for the whole bank from the
// weights (unnormalised, their sum `total`): every hypothesis holds its heading when those
// whose own attitude would hold it carry at least half the weight. Decided per hypothesis, the
// filters near east-west (heading held, its variance growing) and their neighbours (heading
// estimated, its variance shrinking on what the aids seem to say of it) were weighed by
// innovations whose S differed by that treatment alone: at 74 N, sliding east-west, the held
// cells nearest the truth lost to estimated ones 20-40 deg off by about a factor of 2 every
// half hour (docs/drilling-envelope.md, section 7).
void HeadingHypotheses::hold_headings(const std::vector<double>& weights, double total) {
  if (!hold_together_) return;
  double held = 0.0;
  for (std::size_t i = 0; i < hypotheses_.size(); ++i) {
    if (heading_information_is_second_order(hypotheses_[i].navigator->state().q_nb)) {
      held += weights[i];
    }
  }
  for (Hypothesis& hypothesis : hypotheses_) {
    hypothesis.navigator->hold_heading(held >= 0.5 * total);
  }
}

void HeadingHypotheses::reweigh() {
  // The aids every hypothesis measured at this epoch: only they compare the hypotheses.
  // With robust weights, an innovation every hypothesis gated out says that the aid failed
  // there, not which heading is right: it is left out.
  std::vector<int> common;
  for (const InnovationRecord& record : hypotheses_.front().navigator->innovations()) {
    const auto record_of = [&](const Hypothesis& h) -> const InnovationRecord* {
      for (const InnovationRecord& r : h.navigator->innovations()) {
        if (r.aid_index == record.aid_index) return &r;
      }
      return nullptr;
    };
    bool everywhere = true;
    bool accepted_somewhere = false;
    for (const Hypothesis& h : hypotheses_) {
      const InnovationRecord* r = record_of(h);
      everywhere = everywhere && r != nullptr && std::isfinite(r->nis + r->log_det_s);
      accepted_somewhere = accepted_somewhere || (r != nullptr && r->accepted);
    }
    if (everywhere && (accepted_somewhere || !robust_weights_)) {
      common.push_back(record.aid_index);
    }
  }
  if (common.empty()) return;
  for (Hypothesis& hypothesis : hypotheses_) {
    for (const InnovationRecord& record : hypothesis.navigator->innovations()) {
      if (std::find(common.begin(), common.end(), record.aid_index) == common.end()) continue;
      hypothesis.log_weight += likelihood_power_ * log_likelihood(record, robust_weights_);
    }
  }
}

void HeadingHypotheses::prune_and_merge() {
  double largest = -INFINITY;
  for (const Hypothesis& h : hypotheses_) largest = std::max(largest, h.log_weight);
  for (Hypothesis& h : hypotheses_) h.log_weight -= largest;  // the largest is now 0
  double total = 0.0;
  for (const Hypothesis& h : hypotheses_) total += std::exp(h.log_weight);
  std::erase_if(hypotheses_,
                [&](const Hypothesis& h) { return std::exp(h.log_weight) < kDropBelow * total; });
  // Merge into the more probable of two hypotheses whose headings agree.
  std::sort(hypotheses_.begin(), hypotheses_.end(),
            [](const Hypothesis& a, const Hypothesis& b) { return a.log_weight > b.log_weight; });
  for (std::size_t keep = 0; keep < hypotheses_.size(); ++keep) {
    const MwdNavigator& kept = *hypotheses_[keep].navigator;
    const double heading_sigma = std::sqrt(kept.covariance()(kHeading, kHeading));
    const CoreEstimate kept_estimate{kept.state(), kept.accel_bias_b(), kept.gyro_bias_b()};
    for (std::size_t other = keep + 1; other < hypotheses_.size();) {
      const MwdNavigator& candidate = *hypotheses_[other].navigator;
      const double difference =
          core_difference({candidate.state(), candidate.accel_bias_b(), candidate.gyro_bias_b()},
                          kept_estimate)(kHeading);
      if (std::abs(difference) < kMergeWithin * heading_sigma) {
        hypotheses_[keep].log_weight +=
            std::log1p(std::exp(hypotheses_[other].log_weight - hypotheses_[keep].log_weight));
        hypotheses_.erase(hypotheses_.begin() + static_cast<std::ptrdiff_t>(other));
      } else {
        ++other;
      }
    }
  }
  best_ = 0;  // sorted, and merging only adds to the kept ones' weights
  for (std::size_t i = 1; i < hypotheses_.size(); ++i) {
    if (hypotheses_[i].log_weight > hypotheses_[best_].log_weight) best_ = i;
  }
}

void HeadingHypotheses::update_mixture() {
  if (hypotheses_.size() == 1) {
    // The bank is one filter now: its own attitude decides its consider rule again.
    hypotheses_.front().navigator->hold_heading(std::nullopt);
    return;
  }
  const MwdNavigator& best = *hypotheses_[best_].navigator;
  mixture_ = {best.state(), best.accel_bias_b(), best.gyro_bias_b()};
  std::vector<double> weights;
  double total = 0.0;
  for (const Hypothesis& h : hypotheses_) total += weights.emplace_back(std::exp(h.log_weight));
  hold_headings(weights, total);  // for the next step's aid epochs
  std::vector<Eigen::Matrix<double, 15, 1>> differences;
  Eigen::Matrix<double, 15, 1> mean = Eigen::Matrix<double, 15, 1>::Zero();
  for (std::size_t i = 0; i < hypotheses_.size(); ++i) {
    const MwdNavigator& n = *hypotheses_[i].navigator;
    differences.push_back(
        core_difference({n.state(), n.accel_bias_b(), n.gyro_bias_b()}, mixture_));
    mean += weights[i] / total * differences.back();
  }
  mixture_covariance_.setZero(15, 15);
  for (std::size_t i = 0; i < hypotheses_.size(); ++i) {
    const Eigen::Matrix<double, 15, 1> spread = differences[i] - mean;
    mixture_covariance_ += weights[i] / total *
                           (hypotheses_[i].navigator->covariance().topLeftCorner<15, 15>() +
                            spread * spread.transpose());
  }
  apply_core_correction(-mean, mixture_);
}

const NavState& HeadingHypotheses::state() const {
  return hypotheses_.size() == 1 ? hypotheses_.front().navigator->state() : mixture_.state;
}

const Eigen::Vector3d& HeadingHypotheses::gyro_bias_b() const {
  return hypotheses_.size() == 1 ? hypotheses_.front().navigator->gyro_bias_b()
                                 : mixture_.gyro_bias_b;
}

const Eigen::Vector3d& HeadingHypotheses::accel_bias_b() const {
  return hypotheses_.size() == 1 ? hypotheses_.front().navigator->accel_bias_b()
                                 : mixture_.accel_bias_b;
}

const Eigen::MatrixXd& HeadingHypotheses::covariance() const {
  return hypotheses_.size() == 1 ? hypotheses_.front().navigator->covariance()
                                 : mixture_covariance_;
}

std::span<const InnovationRecord> HeadingHypotheses::innovations() const {
  return most_probable().innovations();
}

const FilterHealth& HeadingHypotheses::health() const { return most_probable().health(); }

double HeadingHypotheses::largest_weight() const { return weight(best_); }

double HeadingHypotheses::weight(std::size_t i) const {
  double total = 0.0;
  for (const Hypothesis& h : hypotheses_) total += std::exp(h.log_weight);
  return std::exp(hypotheses_.at(i).log_weight) / total;
}

const MwdNavigator& HeadingHypotheses::most_probable() const {
  return *hypotheses_[best_].navigator;
}

double HeadingHypotheses::heading_from_most_probable_rad(std::size_t i) const {
  const MwdNavigator& best = most_probable();
  const MwdNavigator& n = *hypotheses_.at(i).navigator;
  return core_difference({n.state(), n.accel_bias_b(), n.gyro_bias_b()},
                         {best.state(), best.accel_bias_b(), best.gyro_bias_b()})(kHeading);
}

double HeadingHypotheses::heading_span_rad() const {
  double lowest = 0.0, highest = 0.0;
  for (std::size_t i = 0; i < hypotheses_.size(); ++i) {
    const double difference = heading_from_most_probable_rad(i);
    lowest = std::min(lowest, difference);
    highest = std::max(highest, difference);
  }
  return highest - lowest;
}

double HeadingHypotheses::weight_within_rad(double half_width_rad) const {
  double total = 0.0, within = 0.0;
  for (std::size_t i = 0; i < hypotheses_.size(); ++i) {
    const double w = std::exp(hypotheses_[i].log_weight);
    total += w;
    if (std::abs(heading_from_most_probable_rad(i)) <= half_width_rad) within += w;
  }
  return within / total;
}

}  // namespace stochnav
