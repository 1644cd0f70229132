#include "stochnav/experiment/initial_state.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/filter/alignment.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/plugin/state_layout.hpp"
#include "stochnav/sim/random_engine.hpp"

namespace stochnav {
namespace {

constexpr double kRadPerSecondPerDegPerHour = kRadPerDeg / 3600.0;
constexpr double kBlock_s = 1.0;  // block length of the static check
constexpr double kMeasurementPeriod_s = 1.0;

Eigen::Vector3d vector_of(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

// Zero velocity and the known position (ENU, against the site), once a second from the start:
// the fine alignment's measurement. Residual = estimate - measurement.
// The fine alignment's attitude prior, in units of the coarse alignment's error budget.
constexpr double kCoarsePriorFactor = 10.0;

class AtRestAid final : public plugin::AidPlugin {
 public:
  AtRestAid(const NavState& site, double position_sigma_m, double velocity_sigma_mps)
      : AidPlugin(plugin::NisGate{.enabled = false}),
        site_(site),
        position_sigma_m_(position_sigma_m),
        velocity_sigma_mps_(velocity_sigma_mps) {}
  std::string_view type() const override { return "alignment_at_rest"; }
  int measurement_size() const override { return 6; }
  bool has_measurement(double t_s) const override {
    const double k = (t_s - site_.t_s) / kMeasurementPeriod_s;
    return k > 0.5 && std::abs(k - std::round(k)) < 1e-6 / kMeasurementPeriod_s;
  }
  bool measure(double, const NavState& state, const plugin::ImuSample&,
               Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    const EarthRadii radii = earth_radii(site_.latitude_rad);
    z(0) = std::remainder(state.longitude_rad - site_.longitude_rad, 2.0 * std::numbers::pi) *
           (radii.transverse_m + site_.height_m) * std::cos(site_.latitude_rad);
    z(1) = (state.latitude_rad - site_.latitude_rad) * (radii.meridian_m + site_.height_m);
    z(2) = state.height_m - site_.height_m;
    z.segment<3>(3) = state.v_n;
    h.setZero();
    h.block<3, 3>(0, plugin::core_state::kPosition).setIdentity();
    h.block<3, 3>(3, plugin::core_state::kVelocity).setIdentity();
    r.setZero();
    r.diagonal().head<3>().setConstant(position_sigma_m_ * position_sigma_m_);
    r.diagonal().tail<3>().setConstant(velocity_sigma_mps_ * velocity_sigma_mps_);
    return true;
  }
  // At rest: the fine alignment linearises about zero velocity and gravity (MwdNavigator's
  // reference trajectory), not about the measured specific force, whose noise would read as
  // heading information.
  bool states_velocity() const override { return true; }
  bool stated_velocity_n(double, const NavState&, Eigen::Ref<Eigen::Vector3d> v_n,
                         double& sigma_mps) const override {
    v_n.setZero();
    sigma_mps = velocity_sigma_mps_;
    return true;
  }
  std::string describe() const override {
    return fmt::format("alignment_at_rest: position {} m, zero velocity {} m/s", position_sigma_m_,
                       velocity_sigma_mps_);
  }

 private:
  NavState site_;
  double position_sigma_m_;
  double velocity_sigma_mps_;
};

}  // namespace

NavState state_from_initial_config(const plugin::InitialStateConfig& config, double t_s) {
  NavState state;
  state.t_s = t_s;
  state.latitude_rad = config.tie_on.latitude_deg * kRadPerDeg;
  state.longitude_rad = config.tie_on.longitude_deg * kRadPerDeg;
  state.height_m = config.tie_on.height_m;
  state.v_n = vector_of(config.velocity_m_s);
  if (config.attitude) {
    state.q_nb = quaternion_from_mwd({.inclination_rad = config.attitude->inclination_deg * kRadPerDeg,
                                      .toolface_rad = config.attitude->toolface_deg * kRadPerDeg,
                                      .azimuth_rad = config.attitude->azimuth_deg * kRadPerDeg});
  }
  return state;
}

void check_static_span(std::span<const ImuIncrement> span, const plugin::AlignmentConfig& config,
                       double record_start_s) {
  const std::string where = "/initial_state/alignment/static_s";
  const double covered = span.empty() ? 0.0 : span.back().t_s - record_start_s;
  if (covered < config.static_s - 1e-6) {
    throw ConfigError(fmt::format(
        "{}: {} s asked for, but the IMU record holds only {:.6g} s; give a static_s within the "
        "record's still start",
        where, config.static_s, covered));
  }
  const StaticSpread spread = static_spread(span, std::min(kBlock_s, config.static_s / 2.0));
  const double gyro_deg_h = spread.gyro_radps / kRadPerSecondPerDegPerHour;
  if (gyro_deg_h > config.max_gyro_spread_deg_h ||
      spread.accel_mps2 > config.max_accel_spread_m_s2) {
    throw ConfigError(fmt::format(
        "{}: the first {} s are not static: over {} blocks the mean |omega| spreads {:.3g} deg/h "
        "(limit {:.3g}) and the mean |f| {:.3g} m/s^2 (limit {:.3g}); give a static_s that ends "
        "before the tool moves (or raise max_gyro_spread_deg_h / max_accel_spread_m_s2 if this "
        "is sensor noise)",
        where, config.static_s, spread.blocks, gyro_deg_h, config.max_gyro_spread_deg_h,
        spread.accel_mps2, config.max_accel_spread_m_s2));
  }
}

namespace {

// The 1-sigma of a sensor's bias at the start, per body axis: the core bias state's and the
// augmented states' share of the sensor error, diag(M P0_aug M^T) (a flicker bank of 0.5 deg/h
// adds 1.1 deg/h to a core 0.7).
Eigen::Vector3d start_bias_sigma(const Eigen::Vector3d& core_sigma,
                                 const plugin::NoiseModelPlugin& noise) {
  const int n = noise.augmented_size();
  if (n == 0) return core_sigma;
  Eigen::MatrixXd p0 = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd map = Eigen::MatrixXd::Zero(3, n);
  noise.augmented_initial_covariance(p0);
  noise.augmented_sensor_map(map);
  const Eigen::Vector3d augmented = (map * p0 * map.transpose()).diagonal();
  return (core_sigma.array().square() + augmented.array()).sqrt();
}

}  // namespace

AlignedStart align_at_rest(std::span<const ImuIncrement> span, const NavState& site,
                           const plugin::AlignmentConfig& config, const FilterOptions& options,
                           plugin::NoiseModelPlugin& gyro_noise,
                           plugin::NoiseModelPlugin& accel_noise) {
  NavState start = site;
  start.t_s = span.front().t_s - span.front().dt_s;
  start.v_n.setZero();
  const StaticMeans means = static_means(span);
  start.q_nb = coarse_alignment(means, site.latitude_rad);

  FilterOptions fine = options;
  fine.position_sigma_m.setConstant(config.position_sigma_m);
  fine.velocity_sigma_mps.setConstant(config.zero_velocity_sigma_m_s);
  if (config.attitude_sigma_deg) {
    fine.attitude_sigma_rad = vector_of(*config.attitude_sigma_deg) * kRadPerDeg;
  } else {
    // The coarse alignment's errors ARE the sensor biases' (tilt = accel bias / g, heading =
    // gyro bias / the horizontal Earth rate): a prior of that size, independent of the biases'
    // own priors, counts the same uncertainty twice (the heading came out sqrt(2) too sure: an
    // east-west hole at 60 N started 13 deg off at 3.8 sigma). The attitude prior is therefore
    // kCoarsePriorFactor times that budget (uninformative beside the biases, which then set the
    // aligned attitude's sigma), floored so that the linearised filter is not over-confident,
    // capped where the linearisation would not hold.
    const double g = normal_gravity(site.latitude_rad, site.height_m);
    const double horizontal_rate = wgs84::kEarthRate_radps * std::cos(site.latitude_rad);
    const double tilt = std::clamp(
        kCoarsePriorFactor * options.accel_bias_sigma_mps2.maxCoeff() / g, 0.1 * kRadPerDeg,
        2.0 * kRadPerDeg);
    const double heading = std::clamp(
        kCoarsePriorFactor * options.gyro_bias_sigma_radps.head<2>().maxCoeff() / horizontal_rate,
        1.0 * kRadPerDeg, 30.0 * kRadPerDeg);
    fine.attitude_sigma_rad = Eigen::Vector3d(tilt, tilt, heading);
  }
  AtRestAid at_rest(start, config.position_sigma_m, config.zero_velocity_sigma_m_s);
  const FineAlignmentResult result =
      fine_alignment(start, span, gyro_noise, accel_noise, {&at_rest}, fine);

  AlignedStart aligned{result.state, options};
  aligned.state.v_n.setZero();
  FilterOptions& out = aligned.options;
  out.position_sigma_m = result.position_sigma_m;
  out.velocity_sigma_mps = result.velocity_sigma_mps;
  out.attitude_sigma_rad = result.attitude_sigma_rad;
  out.accel_bias_sigma_mps2 = result.accel_bias_sigma_mps2;
  out.gyro_bias_sigma_radps = result.gyro_bias_sigma_radps;
  out.initial_accel_bias_mps2 = result.accel_bias_b;
  out.initial_gyro_bias_radps = result.gyro_bias_b;
  // With the correlations: the heading and the horizontal gyro biases are known together far
  // better than apart, and the run must not count that information a second time.
  out.initial_core_covariance = result.core_covariance;
  // And whole: the run continues the alignment's filter (its augmented states and their
  // correlations with the rest), which a start from the core block alone would reset.
  out.whole_start = result.whole;
  out.static_gyrocompass = FilterOptions::StaticGyrocompass{
      means.omega_ib_b, options.initial_gyro_bias_radps,
      start_bias_sigma(options.gyro_bias_sigma_radps, gyro_noise)};
  return aligned;
}

void apply_initial_error(const plugin::InitialErrorConfig& error, NavState& state,
                         FilterOptions& options) {
  Eigen::Vector3d position = vector_of(error.position_m);
  Eigen::Vector3d velocity = vector_of(error.velocity_m_s);
  Eigen::Vector3d attitude = vector_of(error.attitude_deg) * kRadPerDeg;
  Eigen::Vector3d gyro_bias = vector_of(error.gyro_bias_deg_h) * kRadPerSecondPerDegPerHour;
  Eigen::Vector3d accel_bias = vector_of(error.accel_bias_m_s2);
  if (error.draw_seed) {
    Xoshiro256StarStar engine(*error.draw_seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    const auto draw = [&](const Eigen::Vector3d& sigma) {
      Eigen::Vector3d x;
      for (int i = 0; i < 3; ++i) x(i) = sigma(i) * normal(engine);
      return x;
    };
    position += draw(options.position_sigma_m);
    velocity += draw(options.velocity_sigma_mps);
    attitude += draw(options.attitude_sigma_rad);
    gyro_bias += draw(options.gyro_bias_sigma_radps);
    accel_bias += draw(options.accel_bias_sigma_mps2);
  }
  const EarthRadii radii = earth_radii(state.latitude_rad);
  state.longitude_rad +=
      position.x() / ((radii.transverse_m + state.height_m) * std::cos(state.latitude_rad));
  state.latitude_rad += position.y() / (radii.meridian_m + state.height_m);
  state.height_m += position.z();
  state.v_n += velocity;
  // C_nb_estimate = (I - [phi x]) C_nb_true = Rot(-phi) C_nb_true to first order.
  if (attitude.norm() > 0.0) {
    state.q_nb =
        (Eigen::Quaterniond(Eigen::AngleAxisd(-attitude.norm(), attitude.normalized())) *
         state.q_nb)
            .normalized();
  }
  options.initial_gyro_bias_radps += gyro_bias;
  options.initial_accel_bias_mps2 += accel_bias;
  if (options.whole_start) {
    options.whole_start->gyro_bias_radps += gyro_bias;
    options.whole_start->accel_bias_mps2 += accel_bias;
  }
}

FilterStart filter_start(const plugin::RunConfig& config, const NavState& start,
                         const FilterOptions& options) {
  FilterStart result{start, options};
  if (config.initial_error) {
    apply_initial_error(*config.initial_error, result.estimate, result.options);
  }
  return result;
}

}  // namespace stochnav
