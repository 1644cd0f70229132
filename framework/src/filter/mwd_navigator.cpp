#include "stochnav/filter/mwd_navigator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "stochnav/filter/core_correction.hpp"
#include "stochnav/filter/core_covariance.hpp"
#include "stochnav/filter/second_order_attitude.hpp"
#include "stochnav/ins/earth.hpp"

namespace stochnav {
namespace {

namespace cs = plugin::core_state;

Eigen::MatrixXd initial_covariance(const plugin::StateLayout& layout, const FilterOptions& o,
                                   plugin::NoiseModelPlugin& gyro,
                                   plugin::NoiseModelPlugin& accel) {
  if (o.whole_start) {
    if (o.whole_start->covariance.rows() != layout.size() ||
        o.whole_start->covariance.cols() != layout.size()) {
      throw std::invalid_argument("MwdNavigator: FilterOptions::whole_start's covariance is " +
                                  std::to_string(o.whole_start->covariance.rows()) + " x " +
                                  std::to_string(o.whole_start->covariance.cols()) +
                                  ", the state layout has " + std::to_string(layout.size()) +
                                  " states; hand over from a navigator of the same models");
    }
    return o.whole_start->covariance;
  }
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(layout.size(), layout.size());
  p.diagonal().segment<3>(cs::kPosition) = o.position_sigma_m.array().square().matrix();
  p.diagonal().segment<3>(cs::kVelocity) = o.velocity_sigma_mps.array().square().matrix();
  p.diagonal().segment<3>(cs::kAttitude) = o.attitude_sigma_rad.array().square().matrix();
  p.diagonal().segment<3>(cs::kAccelBias) = o.accel_bias_sigma_mps2.array().square().matrix();
  p.diagonal().segment<3>(cs::kGyroBias) = o.gyro_bias_sigma_radps.array().square().matrix();
  if (o.initial_core_covariance) p.topLeftCorner<cs::kSize, cs::kSize>() = *o.initial_core_covariance;
  for (auto [name, sigma] : {std::pair{"gyro_scale_factor", &o.gyro_scale_factor_sigma},
                             std::pair{"accel_scale_factor", &o.accel_scale_factor_sigma}}) {
    if (const plugin::StateBlock* block = layout.find(name)) {
      p.diagonal().segment<3>(block->offset) = sigma->array().square().matrix();
    }
  }
  for (plugin::NoiseModelPlugin* model : {&gyro, &accel}) {
    const int size = model->augmented_size();
    if (size == 0) continue;
    const int offset = model->placement().augmented_offset;
    model->augmented_initial_covariance(p.block(offset, offset, size, size));
  }
  return p;
}

plugin::SensorErrorStates sensor_error_states(const FilterOptions& options) {
  return {.gyro_scale_factor = options.estimates_gyro_scale_factor(),
          .accel_scale_factor = options.estimates_accel_scale_factor()};
}

int block_offset(const plugin::StateLayout& layout, std::string_view name) {
  const plugin::StateBlock* block = layout.find(name);
  return block == nullptr ? -1 : block->offset;
}

// The increment corrected for the estimated bias and scale factor: the sensor reads
// (1 + s) truth + b, so truth = (reading - b) / (1 + s) per axis.
Eigen::Vector3d compensated_increment(const Eigen::Vector3d& raw, const Eigen::Vector3d& bias,
                                      const Eigen::Vector3d& scale_factor, double dt_s) {
  return ((raw - bias * dt_s).array() / (1.0 + scale_factor.array())).matrix();
}

// The heading error phi_U, the state FilterOptions::heading_considered makes a consider state.
constexpr int kHeadingState = cs::kAttitude + 2;

// The bias-free, first-order information on the heading that a rotating tool's cross-axis gyros
// get from the Earth rate, relative to the horizontal Earth rate: turning the tool by d about
// the vertical changes the measured rate by d omega_h e_E (in body axes), of which the cross
// axes see sqrt(1 - (e_E . z_b)^2), z_b the tool axis; the along-hole part is one unknown with
// the along-hole gyro bias. 1 for a vertical or north-south tool, 0 in a horizontal east-west
// hole, where the heading's information is second order (docs/drilling-envelope.md, section 4).
double heading_first_order_share(const Eigen::Quaterniond& q_nb) {
  const double east = (q_nb * Eigen::Vector3d::UnitZ()).x();
  return std::sqrt(std::max(0.0, 1.0 - east * east));
}

// Below this share the heading is a consider state (when FilterOptions::heading_considered):
// sin 8 deg, the tool axis within about 8 deg of horizontal east-west, two 4-deg cells of the
// bank over the heading, across which cos psi's curvature is as large as the first-order slope.
// The one value tried (docs/drilling-envelope.md, section 4, fix 5).
constexpr double kHeadingFirstOrderShareFloor = 0.14;

}  // namespace

bool heading_information_is_second_order(const Eigen::Quaterniond& q_nb) {
  return heading_first_order_share(q_nb) < kHeadingFirstOrderShareFloor;
}

MwdNavigator::MwdNavigator(const NavState& initial, plugin::NoiseModelPlugin& gyro_noise,
                           plugin::NoiseModelPlugin& accel_noise,
                           std::vector<plugin::AidPlugin*> aids, const FilterOptions& options)
    : gyro_noise_(&gyro_noise),
      accel_noise_(&accel_noise),
      aids_(std::move(aids)),
      options_(options),
      layout_(plugin::assign_state_layout(gyro_noise, accel_noise, sensor_error_states(options))),
      ins_(initial),
      filter_(initial_covariance(layout_, options, gyro_noise, accel_noise)),
      interval_start_s_(initial.t_s),
      c_nb_(initial.q_nb.toRotationMatrix()),
      smoothed_specific_force_n_(-gravity_n(initial.latitude_rad, initial.height_m)),
      oscillation_(options.vibration_velocity_threshold_mps, initial.v_n) {
  for (auto [group, model] :
       {std::pair{&gyro_augmented_, &gyro_noise}, std::pair{&accel_augmented_, &accel_noise}}) {
    group->model = model;
    group->size = model->augmented_size();
    group->offset = model->placement().augmented_offset;
    group->sensor_map = Eigen::MatrixXd::Zero(3, group->size);
    group->estimate = Eigen::VectorXd::Zero(group->size);
    group->phi = Eigen::MatrixXd::Identity(group->size, group->size);
    group->q_d = Eigen::MatrixXd::Zero(group->size, group->size);
    if (group->size > 0) model->augmented_sensor_map(group->sensor_map);
    group->blocks = BlockDiagonalStructure(group->size);
    group->sparse_sensor_map = SparseMap(group->sensor_map);
    group->propagated = Eigen::VectorXd::Zero(group->size);
  }
  // The dense head ends where the first augmented block starts (layout: head, then the gyro's
  // augmented block, then the accelerometer's).
  head_size_ = layout_.size();
  for (const AugmentedGroup* group : {&accel_augmented_, &gyro_augmented_}) {
    if (group->size > 0) head_size_ = group->offset;
  }
  gyro_bias_b_ = options.initial_gyro_bias_radps;
  accel_bias_b_ = options.initial_accel_bias_mps2;
  if (options.whole_start) {
    gyro_bias_b_ = options.whole_start->gyro_bias_radps;
    accel_bias_b_ = options.whole_start->accel_bias_mps2;
    for (auto [group, estimate] :
         {std::pair{&gyro_augmented_, &options.whole_start->gyro_augmented},
          std::pair{&accel_augmented_, &options.whole_start->accel_augmented}}) {
      if (estimate->size() != group->size) {
        throw std::invalid_argument("MwdNavigator: FilterOptions::whole_start holds " +
                                    std::to_string(estimate->size()) + " augmented states of " +
                                    std::string(group->model->type()) + ", the model has " +
                                    std::to_string(group->size));
      }
      group->estimate = *estimate;
    }
  }
  gyro_scale_.offset = block_offset(layout_, "gyro_scale_factor");
  accel_scale_.offset = block_offset(layout_, "accel_scale_factor");
  head_f_ = Eigen::MatrixXd::Zero(head_size_, head_size_);
  aid_intervals_.assign(aids_.size(), InsIntervalAccumulator{});
  interval_shared_with_.assign(aids_.size(), -1);
  for (std::size_t index = 0; index < aids_.size(); ++index) {
    if (!aids_[index]->measures_interval_mean()) continue;
    if (!interval_aids_.empty()) {
      interval_shared_with_[index] = static_cast<int>(interval_aids_.front());
    }
    interval_aids_.push_back(index);
  }
  interval_layout_ = interval_map_layout();
  interval_map_ = Eigen::MatrixXd::Zero(3, interval_layout_.width);
  const int n = layout_.size();
  const int phi_size = options_.structured_covariance ? head_size_ : n;
  phi_ = Eigen::MatrixXd::Identity(phi_size, phi_size);
  q_d_ = Eigen::MatrixXd::Zero(phi_size, phi_size);
  correction_ = Eigen::VectorXd::Zero(n);
  innovations_.reserve(aids_.size());
  reference_.active = std::any_of(aids_.begin(), aids_.end(), [](const plugin::AidPlugin* aid) {
    return aid->states_velocity();
  });
  reference_.v_n = initial.v_n;
  reference_.smoothed_specific_force_n = smoothed_specific_force_n_;
  consecutive_rejections_.assign(aids_.size(), 0);
}

std::unique_ptr<MwdNavigator> MwdNavigator::split(plugin::NoiseModelPlugin& gyro_noise,
                                                 plugin::NoiseModelPlugin& accel_noise,
                                                 std::vector<plugin::AidPlugin*> aids,
                                                 const Eigen::VectorXd& correction,
                                                 const Eigen::MatrixXd& covariance,
                                                 bool heading_considered) const {
  const plugin::StateLayout layout =
      plugin::assign_state_layout(gyro_noise, accel_noise, sensor_error_states(options_));
  const auto same_blocks = [&] {
    if (layout.blocks().size() != layout_.blocks().size()) return false;
    for (std::size_t i = 0; i < layout.blocks().size(); ++i) {
      const plugin::StateBlock& a = layout.blocks()[i];
      const plugin::StateBlock& b = layout_.blocks()[i];
      if (a.name != b.name || a.offset != b.offset || a.size != b.size) return false;
    }
    return true;
  };
  const int n = layout_.size();
  if (!same_blocks() || aids.size() != aids_.size() || correction.size() != n ||
      covariance.rows() != n || covariance.cols() != n) {
    throw std::invalid_argument(
        "MwdNavigator::split: the plugins, the correction or the covariance do not match the "
        "navigator's layout of " + std::to_string(n) + " states and " +
        std::to_string(aids_.size()) + " aids");
  }
  std::unique_ptr<MwdNavigator> copy(new MwdNavigator(*this));
  copy->gyro_noise_ = &gyro_noise;
  copy->accel_noise_ = &accel_noise;
  copy->gyro_augmented_.model = &gyro_noise;
  copy->accel_augmented_.model = &accel_noise;
  copy->aids_ = std::move(aids);
  copy->interval_layout_ = copy->interval_map_layout();  // points into the copy's groups
  copy->options_.heading_considered = heading_considered;
  copy->filter_.replace_covariance(covariance);
  copy->feed_back(correction);
  return copy;
}

Eigen::Vector3d MwdNavigator::sensor_correction(const AugmentedGroup& group) const {
  if (group.size == 0) return Eigen::Vector3d::Zero();
  return group.sensor_map * group.estimate;
}

Eigen::Vector3d MwdNavigator::gyro_total_bias_b() const {
  return gyro_bias_b_ + sensor_correction(gyro_augmented_);
}

Eigen::Vector3d MwdNavigator::accel_total_bias_b() const {
  return accel_bias_b_ + sensor_correction(accel_augmented_);
}

FilterOptions::WholeStart MwdNavigator::whole_start() const {
  return {.gyro_bias_radps = gyro_bias_b_,
          .accel_bias_mps2 = accel_bias_b_,
          .gyro_augmented = gyro_augmented_.estimate,
          .accel_augmented = accel_augmented_.estimate,
          .covariance = filter_.covariance()};
}

Eigen::Matrix<double, 15, 15> MwdNavigator::core_covariance_with_total_biases() const {
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(cs::kSize, layout_.size());
  t.leftCols<cs::kSize>().setIdentity();
  for (auto [group, row] :
       {std::pair{&gyro_augmented_, cs::kGyroBias}, std::pair{&accel_augmented_, cs::kAccelBias}}) {
    if (group->size > 0) t.block(row, group->offset, 3, group->size) = group->sensor_map;
  }
  return t * filter_.covariance() * t.transpose();
}

void MwdNavigator::accumulate_noise(plugin::NoiseModelPlugin& model, double t_s, double dt_s,
                                    const Eigen::Matrix3d& c_nb, Eigen::Matrix3d& cache,
                                    double& cached_dt, Eigen::Matrix3d& sum) {
  if (model.time_varying() || dt_s != cached_dt) {
    model.white_noise_covariance(t_s, dt_s, cache);
    if (!model.time_varying()) cached_dt = dt_s;
  }
  // Equal noise on every axis is invariant under rotation (C q I C^T = q I): skip the products.
  const double q = cache(0, 0);
  if (cache(1, 1) == q && cache(2, 2) == q && cache(0, 1) == 0.0 && cache(0, 2) == 0.0 &&
      cache(1, 2) == 0.0) {
    sum.diagonal().array() += q;
  } else {
    sum.noalias() += c_nb * cache * c_nb.transpose();
  }
}

void MwdNavigator::step(const ImuIncrement& raw) {
  innovations_.clear();
  const double dt = raw.dt_s;
  const double t_start = raw.t_s - dt;
  ImuIncrement compensated = raw;
  compensated.delta_theta_b =
      compensated_increment(raw.delta_theta_b, gyro_bias_b_ + sensor_correction(gyro_augmented_),
                            gyro_scale_.estimate, dt);
  compensated.delta_v_b =
      compensated_increment(raw.delta_v_b, accel_bias_b_ + sensor_correction(accel_augmented_),
                            accel_scale_.estimate, dt);
  // The interval aids compare the rig's rates with the velocity less the tool's vibration.
  const Eigen::Vector3d v_start = ins_.state().v_n - oscillation_.velocity_n();
  ins_.update(compensated);

  // The epoch's mean attitude for the integrals of C_nb (the chord of the start and end attitudes
  // is short across the spin axis: ins/strapdown.hpp), and the specific force the strapdown
  // integrated, rotation- and sculling-compensated, in n.
  const Eigen::Matrix3d c_mean = epoch_mean_attitude(c_nb_, compensated.delta_theta_b);
  c_nb_ = ins_.state().q_nb.toRotationMatrix();
  const Eigen::Vector3d& specific_force_dv_n = ins_.specific_force_increment_n();
  // The specific force the attitude error rotates (d dv/dt = [f_n x] phi + ...): the measured
  // one, or the reference trajectory's when the aids state the velocity.
  const Eigen::Vector3d coupling_delta_v_n =
      reference_.active ? reference_specific_force_increment(dt, specific_force_dv_n)
                        : specific_force_dv_n;
  // The tool's vibration, which the reference lacks: the velocity error inherits phi x its
  // change as well (filter/velocity_oscillation.hpp). The interval aids' mean-error maps keep
  // the reference's coupling alone: they measure the velocity less the oscillation, whose
  // counted part carries the attitude error's share of it.
  const Eigen::Vector3d oscillation_change =
      reference_.active ? oscillation_.update(ins_.state().v_n, dt) : Eigen::Vector3d::Zero();
  // The accelerometer scale factors multiply the true specific force: a smoothed one from the
  // epochs before this one, not this epoch's measurement, whose noise also drives the velocity
  // error and would correlate the gains with the residuals (over a day of 1-s aids that biased
  // the scale factors, hence the inclination, by -0.015 deg in the middle of the build).
  const bool smoothing = accel_scale_.offset >= 0 || !interval_aids_.empty() || reference_.active;
  const Eigen::Vector3d scale_factor_delta_v_b =
      smoothing ? Eigen::Vector3d(c_mean.transpose() * smoothed_specific_force_n_ * dt)
                : Eigen::Vector3d::Zero();
  if (smoothing && dt > 0.0) {
    smoothed_specific_force_n_ +=
        (std::min(dt, kSpecificForceSmoothing_s) / kSpecificForceSmoothing_s) *
        (specific_force_dv_n / dt - smoothed_specific_force_n_);
  }
  if (gyro_scale_.offset >= 0)
    fast_.gyro_scale_dt += c_mean * compensated.delta_theta_b.asDiagonal();
  fast_.add_velocity_inputs(dt, c_mean * dt, coupling_delta_v_n + oscillation_change);
  if (accel_scale_.offset >= 0) {
    fast_.add_accel_scale_input(dt, c_mean * scale_factor_delta_v_b.asDiagonal());
  }
  const Eigen::Matrix3d attitude_noise_before = attitude_noise_;
  accumulate_noise(*gyro_noise_, t_start, dt, c_mean, gyro_white_cache_, gyro_cached_dt_,
                   attitude_noise_);
  const Eigen::Matrix3d velocity_noise_before = velocity_noise_;
  accumulate_noise(*accel_noise_, t_start, dt, c_mean, accel_white_cache_, accel_cached_dt_,
                   velocity_noise_);
  if (!interval_aids_.empty()) {
    const InsIntervalAccumulator::Epoch interval_epoch{
        .v_start_n = v_start,
        .v_end_n = ins_.state().v_n - oscillation_.velocity_n(),
        .c_nb_mean = c_mean,
        .delta_v_n = coupling_delta_v_n,
        .scale_factor_delta_v_b = scale_factor_delta_v_b,
        .delta_theta_b = compensated.delta_theta_b,
        .velocity_noise = velocity_noise_ - velocity_noise_before,
        .attitude_noise = attitude_noise_ - attitude_noise_before,
        .dt_s = dt,
        .oscillation_share = oscillation_.share()};
    for (const std::size_t index : interval_aids_) {
      if (interval_shared_with_[index] < 0) aid_intervals_[index].add_epoch(interval_epoch);
    }
  }

  bool measurement_due = false;
  for (const plugin::AidPlugin* aid : aids_) measurement_due |= aid->has_measurement(raw.t_s);
  // The interval closes within half an epoch of its nominal length, so that a 0.1 s interval
  // at 100 Hz is exactly 10 epochs whatever the rounding of the time stamps.
  if (measurement_due || fast_.interval_s >= options_.covariance_interval_s - 0.5 * dt) {
    propagate_covariance();
  }
  if (measurement_due && dt > 0.0) {
    apply_aids(raw.t_s, compensated.delta_theta_b / dt, compensated.delta_v_b / dt);
  }
}

// The specific-force increment over an epoch of dt s (ENU, m/s) the attitude error rotates in
// a run with a reference trajectory: the reference's acceleration (its velocity change since
// the previous epoch, the aids' new statement if any, plus its Coriolis and transport terms),
// so that the velocity error inherits phi x (the reference's velocity change) as the INS's does
// the true one's; plus the rest of the specific force, gravity as the INS sees it through its
// attitude error, from the measured specific force smoothed over kReferenceSmoothing_s before
// this epoch, less the reference acceleration smoothed alike. This epoch's accelerometer noise,
// which also drives the velocity error, stays out: a coefficient correlated with the process
// noise reads the noise as attitude information (at 10 s of smoothing the remaining noise still
// pulled a sliding run's azimuth 10 sigma off; at 100 s it does not). Gravity from the model
// alone left out the INS's tilt of it, which under a heading error of degrees rotates the tilt's
// effect on the velocity; the filter put that into the accelerometer biases (docs/
// drilling-envelope.md).
Eigen::Vector3d MwdNavigator::reference_specific_force_increment(
    double dt_s, const Eigen::Vector3d& measured_delta_v_n) {
  const NavState& state = ins_.state();
  const LatitudeTerms& latitude = ins_.latitude_terms();
  const Eigen::Vector3d rotation =
      2.0 * earth_rate_n(latitude.trig) +
      transport_rate_n(latitude.trig, latitude.radii, state.height_m, reference_.v_n);
  const Eigen::Vector3d acceleration_dt =
      reference_.pending_change_n + rotation.cross(reference_.v_n) * dt_s;
  reference_.pending_change_n.setZero();
  const Eigen::Vector3d increment =
      acceleration_dt +
      (reference_.smoothed_specific_force_n - reference_.smoothed_acceleration_n) * dt_s;
  if (dt_s > 0.0) {
    const double weight = std::min(dt_s, kReferenceSmoothing_s) / kReferenceSmoothing_s;
    reference_.smoothed_acceleration_n +=
        weight * (acceleration_dt / dt_s - reference_.smoothed_acceleration_n);
    reference_.smoothed_specific_force_n +=
        weight * (measured_delta_v_n / dt_s - reference_.smoothed_specific_force_n);
  }
  return increment;
}

const InsIntervalAccumulator& MwdNavigator::aid_interval(std::size_t index) const {
  const int shared = interval_shared_with_[index];
  return aid_intervals_[shared < 0 ? index : static_cast<std::size_t>(shared)];
}

void MwdNavigator::restart_aid_interval(std::size_t index) {
  const int restarted = static_cast<int>(index);
  int heir = -1;
  for (const std::size_t other : interval_aids_) {
    if (interval_shared_with_[other] != restarted) continue;
    if (heir < 0) {
      heir = static_cast<int>(other);
      aid_intervals_[other] = aid_intervals_[index];
      interval_shared_with_[other] = -1;
    } else {
      interval_shared_with_[other] = heir;
    }
  }
  aid_intervals_[index] = InsIntervalAccumulator{};
  interval_shared_with_[index] = -1;
  if (!aids_[index]->measures_interval_mean()) return;
  for (const std::size_t other : interval_aids_) {
    if (other != index && interval_shared_with_[other] < 0 &&
        !(aid_intervals_[other].duration_s() > 0.0)) {
      interval_shared_with_[index] = static_cast<int>(other);
      return;
    }
  }
}

IntervalMapLayout MwdNavigator::interval_map_layout() const {
  IntervalMapLayout layout;
  layout.gyro_scale_offset = gyro_scale_.offset;
  layout.accel_scale_offset = accel_scale_.offset;
  layout.width = cs::kSize;
  for (const int offset : {gyro_scale_.offset, accel_scale_.offset}) {
    if (offset >= 0) layout.width = std::max(layout.width, offset + 3);
  }
  if (gyro_augmented_.size > 0) {
    layout.gyro_augmented_offset = gyro_augmented_.offset;
    layout.gyro_sensor_map = &gyro_augmented_.sensor_map;
    layout.width = std::max(layout.width, gyro_augmented_.offset + gyro_augmented_.size);
  }
  if (accel_augmented_.size > 0) {
    layout.accel_augmented_offset = accel_augmented_.offset;
    layout.accel_sensor_map = &accel_augmented_.sensor_map;
    layout.width = std::max(layout.width, accel_augmented_.offset + accel_augmented_.size);
  }
  return layout;
}

const Eigen::MatrixXd& MwdNavigator::widened_measurement_matrix(
    const InsIntervalAccumulator& interval) {
  // The aid's h is P * map_core (+ terms of the attitude used to project the mean), P = dz /
  // d mean_v_n = the velocity columns of h (the core map's velocity block is I).
  interval.mean_error_map(interval_layout_, interval_map_);
  const Eigen::Index m = h_core_.rows();
  const Eigen::Index beyond = interval_layout_.width - cs::kSize;
  h_wide_.resize(m, interval_layout_.width);
  h_wide_.leftCols<cs::kSize>() = h_core_;
  h_wide_.rightCols(beyond).noalias() =
      h_core_.middleCols<3>(cs::kVelocity) * interval_map_.rightCols(beyond);
  return h_wide_;
}

void MwdNavigator::propagate_covariance() {
  const double interval = fast_.interval_s;
  if (interval <= 0.0) return;
  const CoreMatrix f_t = integrated_core_dynamics(ins_.state(), ins_.latitude_terms(), fast_);
  advance_augmented_groups(interval);
  // The core alone always, and with the structured products (the default) any state whose
  // transition has the fixed-size form: the scale-factor blocks and first-order augmented states.
  if (layout_.size() == cs::kSize || options_.structured_covariance) {
    if (propagate_by_fixed_size_kernel(f_t, interval)) return;
  }
  propagate_by_dynamic_blocks(f_t, interval);
}

// Phi and Qd of each noise model's augmented states over the interval, the coupling of those
// states into the attitude or velocity rows, and their nominal values propagated.
void MwdNavigator::advance_augmented_groups(double interval) {
  // Augmented sensor errors enter like the biases: + C M x (gyro, attitude rows) and
  // - C M x (accelerometer, velocity rows), with the sign of d omega = -(db + M dx).
  for (auto [group, sign] :
       {std::pair{&gyro_augmented_, 1.0}, std::pair{&accel_augmented_, -1.0}}) {
    if (group->size == 0) continue;
    update_augmented_transition(*group, interval);
    group->coupling = sign * fast_.c_nb_dt;
    group->transition.multiply(group->estimate, group->propagated);
    group->estimate.swap(group->propagated);
  }
}

bool MwdNavigator::propagate_by_fixed_size_kernel(const CoreMatrix& f_t, double interval) {
  // The kernel needs diagonal transition rows after the navigation states: every augmented
  // group's Phi (and Qd, on the same structure) diagonal.
  for (const AugmentedGroup* group : {&gyro_augmented_, &accel_augmented_}) {
    if (!group->blocks.is_diagonal()) return false;
  }
  switch (layout_.size()) {
    case 15: propagate_fixed_size<15>(f_t, interval); return true;
    case 18: propagate_fixed_size<18>(f_t, interval); return true;
    case 21: propagate_fixed_size<21>(f_t, interval); return true;
    case 24: propagate_fixed_size<24>(f_t, interval); return true;
    case 27: propagate_fixed_size<27>(f_t, interval); return true;
    default: return false;
  }
}

// The N-state error state in fixed-size matrices (filter/core_covariance.hpp): Phi and Qd as the
// dense path builds them (the head's second-order transition, the augmented states' first-order
// coupling and their own Phi, Qd), then the kernel.
template <int N>
void MwdNavigator::propagate_fixed_size(const CoreMatrix& f_t, double interval) {
  using Square = NavDiagonalMatrix<N>;
  Square f = Square::Zero();
  f.template topLeftCorner<cs::kSize, cs::kSize>() = f_t;
  // The scale-factor columns couple into attitude (gyro) and velocity (accel) like the biases.
  if (gyro_scale_.offset >= 0) {
    f.template block<3, 3>(cs::kAttitude, gyro_scale_.offset) = fast_.gyro_scale_dt;
  }
  if (accel_scale_.offset >= 0) {
    f.template block<3, 3>(cs::kVelocity, accel_scale_.offset) = -fast_.accel_scale_dt;
  }
  Square phi = second_order_transition_increment<N>(f);
  phi.diagonal().array() += 1.0;
  add_position_shape_correction(phi);
  Square q_d = Square::Zero();
  const SecondOrderTerm second_order = second_order_term(interval);
  q_d.template topLeftCorner<cs::kSize, cs::kSize>() =
      core_process_noise(interval, second_order.noise);
  for (auto [group, rows] : {std::pair{&gyro_augmented_, cs::kAttitude},
                             std::pair{&accel_augmented_, cs::kVelocity}}) {
    if (group->size == 0) continue;
    for (int i = 0; i < group->size; ++i) {
      const int state = group->offset + i;
      phi(state, state) = group->phi(i, i);
      q_d(state, state) = group->q_d(i, i);
      phi.template block<3, 1>(rows, state).noalias() =
          group->coupling * Eigen::Vector3d(group->sensor_map.col(i));
    }
  }
  filter_.propagate_nav_diagonal<N>(phi, q_d);
  feed_back_second_order_drift(second_order.drift);
  close_interval(interval);
}

// Any other layout (augmented states with 2 x 2 or larger blocks, or the dense reference):
// the head in dynamic-size matrices, the augmented states by blocks (BlockTransition) or
// densely.
void MwdNavigator::propagate_by_dynamic_blocks(const CoreMatrix& f_t, double interval) {
  phi_.setIdentity();
  if (head_size_ == cs::kSize) {
    phi_.topLeftCorner<15, 15>() += second_order_transition_increment(f_t);
  } else {
    // The scale-factor columns couple into attitude (gyro) and velocity (accel) like the biases.
    head_f_.setZero();
    head_f_.topLeftCorner<15, 15>() = f_t;
    if (gyro_scale_.offset >= 0) {
      head_f_.block<3, 3>(cs::kAttitude, gyro_scale_.offset) = fast_.gyro_scale_dt;
    }
    if (accel_scale_.offset >= 0) {
      head_f_.block<3, 3>(cs::kVelocity, accel_scale_.offset) = -fast_.accel_scale_dt;
    }
    phi_.topLeftCorner(head_size_, head_size_) += head_f_ + 0.5 * head_f_ * head_f_;
  }
  add_position_shape_correction(phi_);
  q_d_.setZero();
  const SecondOrderTerm second_order = second_order_term(interval);
  q_d_.topLeftCorner<cs::kSize, cs::kSize>() = core_process_noise(interval, second_order.noise);
  if (!options_.structured_covariance) {
    for (auto [group, rows] : {std::pair{&gyro_augmented_, cs::kAttitude},
                               std::pair{&accel_augmented_, cs::kVelocity}}) {
      if (group->size == 0) continue;
      phi_.block(group->offset, group->offset, group->size, group->size) = group->phi;
      q_d_.block(group->offset, group->offset, group->size, group->size) = group->q_d;
      phi_.block(rows, group->offset, 3, group->size) = group->coupling * group->sensor_map;
    }
    filter_.propagate(phi_, q_d_);
  } else {
    const std::array<TailSegment, 2> tail{
        TailSegment{gyro_augmented_.offset, gyro_augmented_.transition, gyro_augmented_.noise,
                    cs::kAttitude, gyro_augmented_.coupling, gyro_augmented_.sparse_sensor_map},
        TailSegment{accel_augmented_.offset, accel_augmented_.transition, accel_augmented_.noise,
                    cs::kVelocity, accel_augmented_.coupling, accel_augmented_.sparse_sensor_map}};
    filter_.propagate(BlockTransition{phi_, q_d_, tail});
  }
  feed_back_second_order_drift(second_order.drift);
  close_interval(interval);
}

// The position rows from the velocity rows' inputs' double integrals, not T / 2 times their
// single integrals (filter/error_dynamics.hpp, position_shape_correction).
void MwdNavigator::add_position_shape_correction(Eigen::Ref<Eigen::MatrixXd> phi) const {
  const PositionShapeCorrection correction = position_shape_correction(fast_);
  phi.block<3, 3>(cs::kPosition, cs::kAttitude) += correction.attitude;
  phi.block<3, 3>(cs::kPosition, cs::kAccelBias) += correction.accel_bias;
  if (accel_scale_.offset >= 0) {
    phi.block<3, 3>(cs::kPosition, accel_scale_.offset) += correction.accel_scale;
  }
}

// Qd of the 15 core states over the interval: the white noises accumulated through C_nb, the
// attitude error's second-order spread, and the bias walks.
CoreMatrix MwdNavigator::core_process_noise(double interval,
                                            const Eigen::Matrix3d& second_order_noise) {
  CoreMatrix q_d = CoreMatrix::Zero();
  q_d.block<3, 3>(cs::kAttitude, cs::kAttitude) = attitude_noise_ + second_order_noise;
  q_d.block<3, 3>(cs::kVelocity, cs::kVelocity) = velocity_noise_;
  gyro_noise_->bias_walk_covariance(interval_start_s_, interval, bias_walk_);
  q_d.block<3, 3>(cs::kGyroBias, cs::kGyroBias) = bias_walk_;
  accel_noise_->bias_walk_covariance(interval_start_s_, interval, bias_walk_);
  q_d.block<3, 3>(cs::kAccelBias, cs::kAccelBias) = bias_walk_;
  return q_d;
}

// The attitude error's second-order rate while the heading is uncertain by degrees
// (filter/second_order_attitude.hpp), from the covariance at the interval's start: its spread
// as process noise, and its mean, the attitude error the interval is expected to have added
// whatever the sign of the heading error, to be fed back at the interval's end.
MwdNavigator::SecondOrderTerm MwdNavigator::second_order_term(double interval) const {
  if (!(options_.second_order_attitude_correlation_s > 0.0)) return {};
  const NavState& state = ins_.state();
  const LatitudeTerms& latitude = ins_.latitude_terms();
  const Eigen::Vector3d omega_in_n =
      earth_rate_n(latitude.trig) +
      transport_rate_n(latitude.trig, latitude.radii, state.height_m, state.v_n);
  const Eigen::Matrix3d p_attitude =
      filter_.covariance().block<3, 3>(cs::kAttitude, cs::kAttitude);
  return {.noise = second_order_attitude_noise(p_attitude, omega_in_n, interval,
                                               options_.second_order_attitude_correlation_s),
          .drift = second_order_attitude_rate_mean(p_attitude, omega_in_n) * interval};
}

void MwdNavigator::feed_back_second_order_drift(const Eigen::Vector3d& drift) {
  if (drift.isZero(0.0)) return;
  correction_.setZero();
  correction_.segment<3>(cs::kAttitude) = drift;
  feed_back(correction_);
}

void MwdNavigator::close_interval(double interval) {
  interval_start_s_ += interval;
  fast_ = FastInputIntegrals{};
  attitude_noise_.setZero();
  velocity_noise_.setZero();
}

// Phi and Qd of a time-invariant model depend on the interval only: computed again only when
// it changes (not the exp() of every state at every interval). A pattern outside the known
// blocks (a new model phase, an entry that was zero at the first interval) coarsens them.
void MwdNavigator::update_augmented_transition(AugmentedGroup& group, double interval_s) {
  if (!group.model->time_varying() && interval_s == group.transition_interval_s) return;
  group.model->augmented_transition(interval_start_s_, interval_s, group.phi, group.q_d);
  group.transition_interval_s = group.model->time_varying() ? -1.0 : interval_s;
  if (!group.blocks.covers(group.phi) || !group.blocks.covers(group.q_d)) {
    group.blocks.cover(group.phi).cover(group.q_d);
  }
  group.transition.assign(group.blocks, group.phi);
  group.noise.assign(group.blocks, group.q_d);
}

bool MwdNavigator::heading_held() const { return filter_.considered(kHeadingState); }

void MwdNavigator::apply_aids(double t_s, const Eigen::Vector3d& omega_ib_b,
                              const Eigen::Vector3d& f_ib_b) {
  if (options_.heading_considered) {
    if (heading_held_.value_or(heading_information_is_second_order(ins_.state().q_nb))) {
      filter_.consider(kHeadingState);
    } else {
      filter_.release(kHeadingState);
    }
  }
  plugin::ImuSample imu{.t_s = t_s, .omega_ib_b = omega_ib_b, .f_ib_b = f_ib_b};
  // The velocity the attitude error rotates at the epoch: the reference plus the vibration.
  imu.reference_v_n = reference_.active
                          ? Eigen::Vector3d(reference_.v_n + oscillation_.velocity_n())
                          : ins_.state().v_n;
  // The statement of the epoch: the most precise of the accepted aids' (ties: the smaller
  // speed, so that a tool at rest by ZUPT and by a zero ROP stays at rest).
  bool stated = false;
  Eigen::Vector3d statement_n = Eigen::Vector3d::Zero();
  double statement_sigma = 0.0;
  for (std::size_t index = 0; index < aids_.size(); ++index) {
    plugin::AidPlugin& aid = *aids_[index];
    if (!aid.has_measurement(t_s)) continue;
    const InsIntervalAccumulator interval = aid_interval(index);  // empty unless an interval aid
    imu.interval = interval.interval();
    restart_aid_interval(index);
    const int m = aid.measurement_size();
    residual_.resize(m);
    h_core_.resize(m, cs::kSize);
    r_.resize(m, m);
    if (!aid.measure(t_s, ins_.state(), imu, residual_, h_core_, r_)) continue;

    const bool adaptive = gyro_noise_->time_varying() || accel_noise_->time_varying();
    const Eigen::MatrixXd prior = adaptive ? filter_.covariance() : Eigen::MatrixXd();
    correction_.setZero();
    int& rejections = consecutive_rejections_[index];
    const bool locked_out = options_.max_consecutive_rejections > 0 &&
                            rejections >= options_.max_consecutive_rejections;
    const bool gated = aid.gate().enabled && !locked_out;
    const bool widen = aid.measures_interval_mean() && interval.duration_s() > 0.0 &&
                       interval_layout_.width > cs::kSize;
    const UpdateOutcome outcome = filter_.update(
        residual_, widen ? widened_measurement_matrix(interval) : h_core_, r_,
        gated ? aid.gate().threshold : INFINITY, correction_,
        options_.structured_covariance ? JosephForm::kExpanded : JosephForm::kProduct);
    rejections = outcome.accepted ? 0 : rejections + 1;
    InnovationRecord record{.t_s = t_s,
                            .aid_index = static_cast<int>(index),
                            .accepted = outcome.accepted,
                            .nis = outcome.nis,
                            .log_det_s = outcome.log_det_s,
                            .size = std::min(m, InnovationRecord::kMaxSize)};
    const Eigen::MatrixXd& s = filter_.last_innovation_covariance();
    for (int i = 0; i < record.size; ++i) {
      record.innovation[i] = residual_(i);
      record.innovation_sigma[i] = std::sqrt(std::max(0.0, s(i, i)));
    }
    innovations_.push_back(record);
    if (adaptive) {
      const plugin::UpdateFeedback feedback{t_s,
                                            aid.type(),
                                            outcome.accepted,
                                            outcome.nis,
                                            residual_,
                                            s,
                                            filter_.last_gain(),
                                            prior,
                                            filter_.covariance()};
      gyro_noise_->on_update(feedback);
      accel_noise_->on_update(feedback);
    }
    if (outcome.accepted) {
      feed_back(correction_);
      Eigen::Vector3d v_n;
      double sigma = 0.0;
      if (reference_.active && aid.stated_velocity_n(t_s, ins_.state(), v_n, sigma) &&
          v_n.allFinite() && sigma > 0.0 &&
          (!stated || sigma < statement_sigma ||
           (sigma == statement_sigma && v_n.norm() < statement_n.norm()))) {
        statement_n = v_n;
        statement_sigma = sigma;
        stated = true;
      }
    }
  }
  if (stated) {
    reference_.pending_change_n += statement_n - reference_.v_n;
    reference_.v_n = statement_n;
  }
}

void MwdNavigator::feed_back(const Eigen::VectorXd& correction) {
  CoreEstimate estimate{ins_.state(), accel_bias_b_, gyro_bias_b_};
  apply_core_correction(correction, estimate);
  oscillation_.shift(estimate.state.v_n - ins_.state().v_n);
  ins_.correct_state(estimate.state);
  c_nb_ = estimate.state.q_nb.toRotationMatrix();
  accel_bias_b_ = estimate.accel_bias_b;
  gyro_bias_b_ = estimate.gyro_bias_b;
  for (ScaleFactorBlock* block : {&gyro_scale_, &accel_scale_}) {
    if (block->offset >= 0) block->estimate -= correction.segment<3>(block->offset);
  }
  // The open intervals of the aids hold the velocity history before this correction; what the
  // correction says about that history is its image through each interval's mean-error map
  // (plugin::InsInterval). Without this shift an aid measuring later at the same epoch (ROP after
  // the pipe tally) would see the corrected error again and apply it twice, every epoch.
  for (InsIntervalAccumulator& interval : aid_intervals_) {
    if (!(interval.duration_s() > 0.0)) continue;
    interval.mean_error_map(interval_layout_, interval_map_);
    interval.shift_mean_velocity(interval_map_ * correction.head(interval_layout_.width));
  }
  for (AugmentedGroup* group : {&gyro_augmented_, &accel_augmented_}) {
    if (group->size > 0) group->estimate -= correction.segment(group->offset, group->size);
  }
}

}  // namespace stochnav
