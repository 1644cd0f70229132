// Embedding the stochnav runtime without the CLI: a host navigation stack loads noise-model and
// aid plugins, builds (or fits) the models, and drives the MWD navigation filter
// (filter/mwd_navigator.hpp) from its own IMU loop: the filter the CLI's `run` uses, with the
// state layout and covariance bookkeeping done by the runtime.
//
//   embed_runtime                      gyro: "gauss_markov" fitted to a simulated 10-minute
//                                      static calibration record; accel: "white" from params
//   embed_runtime RUN_CONFIG.json      the noise models and the filter section (with its
//                                      initial error, if any) of a run config (plugins found in
//                                      the config's folder, $STOCHNAV_PLUGIN_PATH, the package)
//   --align SECONDS                    the host's first SECONDS go to a streaming static
//                                      alignment (experiment/streaming_aligner.hpp) and the
//                                      filter starts from its attitude and biases, not from truth
//   --check                            exit 1 unless every augmented block keeps its stationary
//                                      covariance, the filter stays healthy (P positive
//                                      definite, no rejected update) and the navigation errors
//                                      stay within 4 sigma of the filter's own covariance
//
// The host's IMU: a static hour at 100 Hz at 30 deg latitude, body axes = ENU, measuring Earth
// rate and gravity exactly plus white noise (gyro 0.05 deg/sqrt(h), accel 0.02 m/s/sqrt(h)),
// with a static-position aid at 1 Hz. At the end it prints every sensor-error block's estimate
// by name (MwdNavigator::block_estimate) and judges the errors by the covariance at that epoch
// (covariance_now()).

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <optional>
#include <random>
#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/initial_state.hpp"
#include "stochnav/experiment/streaming_aligner.hpp"
#include "stochnav/filter/mwd_navigator.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/model/noise_model.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/plugin/runtime.hpp"
#include "stochnav/plugin/state_layout.hpp"
#include "stochnav/sim/noise_generator.hpp"
#include "stochnav/version.hpp"

namespace sp = stochnav::plugin;

namespace {

constexpr double kDegPerHour = std::numbers::pi / 180.0 / 3600.0;  // rad/s

/// The models of the default demo: a gyro Gauss-Markov model fitted from simulated data.
sp::RunPlugins demo_plugins(const sp::PluginRegistry& registry) {
  const double deg_rt_h = std::numbers::pi / 180.0 / 60.0;
  const stochnav::NoiseModel truth{stochnav::Unit::kRadPerSecond,
                                   100.0,
                                   {stochnav::AngleRandomWalkTerm{0.05 * deg_rt_h},
                                    stochnav::GaussMarkovTerm{5.0 * kDegPerHour, 20.0}}};
  sp::CalibrationRecord record;
  record.group = sp::SensorGroup::kGyro;
  record.rate_hz = truth.rate_hz;
  record.source = "simulated static calibration";
  for (std::size_t axis = 0; axis < 3; ++axis) {
    record.axes[axis] = stochnav::simulate_noise(truth, 600.0, truth.rate_hz, 7 + axis);
  }
  sp::NoiseModelContext context;
  context.imu_rate_hz = 100.0;
  sp::RunPlugins plugins;
  context.group = sp::SensorGroup::kGyro;
  context.params_pointer = "/noise/gyro/params";
  plugins.gyro =
      registry.fit_noise_model("gauss_markov", record, {}, context, "/noise/gyro/plugin");
  context.group = sp::SensorGroup::kAccel;
  context.params_pointer = "/noise/accel/params";
  plugins.accel = registry.create_noise_model("white", {{"N", 0.02}, {"K", 0.001}}, context,
                                              "/noise/accel/plugin");
  plugins.layout = sp::assign_state_layout(*plugins.gyro, *plugins.accel);
  return plugins;
}

/// Propagates the augmented block alone and returns max |P - P0| / max |P0| after `steps`.
double stationarity_error(const sp::NoiseModelPlugin& model, double dt, int steps) {
  const int n = model.augmented_size();
  if (n == 0) return 0.0;
  Eigen::MatrixXd p0(n, n), phi(n, n), q_d(n, n);
  model.augmented_initial_covariance(p0);
  Eigen::MatrixXd p = p0;
  for (int k = 0; k < steps; ++k) {
    model.augmented_transition(k * dt, dt, phi, q_d);
    p = phi * p * phi.transpose() + q_d;
  }
  return (p - p0).cwiseAbs().maxCoeff() / p0.cwiseAbs().maxCoeff();
}

int run(int argc, char** argv) {
  std::string config_path;
  bool check = false;
  double align_s = 0.0;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--check") {
      check = true;
    } else if (argument == "--align" && i + 1 < argc) {
      align_s = std::stod(argv[++i]);
    } else {
      config_path = argument;
    }
  }
  std::printf("stochnav %s, plugin API %u\n", std::string(stochnav::kVersion).c_str(),
              sp::kPluginApiVersion);

  sp::RunPlugins plugins;
  std::optional<sp::RunConfig> config;
  if (config_path.empty()) {
    const sp::PluginRegistry registry(sp::default_search_path());
    plugins = demo_plugins(registry);
  } else {
    config = sp::read_embedded_run_config(config_path);  // the host feeds the IMU: no "data"
    const sp::PluginRegistry registry(sp::default_search_path(config->config_dir));
    plugins = sp::build_run_plugins(*config, registry, sp::AidData(), stochnav::NavState(), 100.0);
  }
  std::printf("gyro:  %s\naccel: %s\nerror state: %d states\n", plugins.gyro->describe().c_str(),
              plugins.accel->describe().c_str(), plugins.layout.size());

  // The host's static hour.
  const double rate_hz = 100.0, duration_s = 3600.0, dt = 1.0 / rate_hz;
  stochnav::NavState truth;
  truth.latitude_rad = 30.0 * std::numbers::pi / 180.0;
  truth.height_m = 50.0;
  const Eigen::Vector3d omega_ib_b = stochnav::earth_rate_n(truth.latitude_rad);  // body = ENU
  const Eigen::Vector3d f_ib_b = -stochnav::gravity_n(truth.latitude_rad, truth.height_m);
  const double gyro_sigma = 0.05 * std::numbers::pi / 180.0 / 60.0 * std::sqrt(dt);  // rad
  const double accel_sigma = 0.02 / 60.0 * std::sqrt(dt);                            // m/s

  const sp::PluginRegistry registry(sp::default_search_path());
  const sp::AidData no_aid_data;
  sp::AidContext aid_context;
  aid_context.params_pointer = "/aids/0/params";
  aid_context.data = &no_aid_data;
  aid_context.initial_state = truth;
  const auto aid = registry.create_aid("static_position",
                                       {{"sigma_position_m", 0.01}, {"sigma_velocity_mps", 0.001}},
                                       aid_context, "/aids/0/plugin");

  std::mt19937_64 rng(42);
  std::normal_distribution<double> normal;
  long k = 0;  // the host's epoch counter
  const auto next_epoch = [&] {
    stochnav::ImuIncrement increment;
    increment.t_s = static_cast<double>(++k) * dt;
    increment.dt_s = dt;
    for (int i = 0; i < 3; ++i) {
      increment.delta_theta_b[i] = omega_ib_b[i] * dt + gyro_sigma * normal(rng);
      increment.delta_v_b[i] = f_ib_b[i] * dt + accel_sigma * normal(rng);
    }
    return increment;
  };

  // The start: the true state, or a static alignment over the host's first align_s seconds.
  // Then the config's filter section and initial error as `stochnav run` applies them; without
  // a config the documented defaults (P propagated every 0.1 s).
  stochnav::NavState start_state = truth;
  stochnav::FilterOptions start_options =
      config ? config->filter.options : stochnav::FilterOptions{};
  if (align_s > 0.0) {
    sp::AlignmentConfig alignment;
    alignment.static_s = align_s;
    stochnav::StreamingAligner aligner(alignment, 0.0);
    while (!aligner.feed(next_epoch())) {
    }
    start_state.t_s = aligner.end_time_s();
    const stochnav::AlignedStart aligned =
        aligner.align(start_state, start_options, *plugins.gyro, *plugins.accel);
    start_state = aligned.state;
    start_options = aligned.options;
    std::printf("aligned over %.0f s: heading sigma %.3f deg\n", aligner.collected_s(),
                aligned.options.attitude_sigma_rad.z() * 180.0 / std::numbers::pi);
  }
  const stochnav::FilterStart start =
      config ? stochnav::filter_start(*config, start_state, start_options)
             : stochnav::FilterStart{start_state, start_options};
  stochnav::MwdNavigator navigator(start.estimate, *plugins.gyro, *plugins.accel, {aid.get()},
                                   start.options);
  const long epochs = std::lround(duration_s * rate_hz);
  while (k < epochs) navigator.step(next_epoch());

  // Every sensor-error block by name: biases, scale factors, the models' augmented states.
  for (const sp::StateBlock& block : navigator.layout().blocks()) {
    if (block.name == "position" || block.name == "velocity" || block.name == "attitude") continue;
    const Eigen::VectorXd estimate = navigator.block_estimate(block.name);
    const Eigen::VectorXd sigma = navigator.block_covariance(block.name).diagonal().cwiseSqrt();
    std::printf("%-28s %2d states, first %+.3e +/- %.3e (SI)\n", block.name.c_str(), block.size,
                block.size > 0 ? estimate[0] : 0.0, block.size > 0 ? sigma[0] : 0.0);
  }

  // Errors against the static truth, with the filter's own sigmas at this epoch.
  namespace cs = sp::core_state;
  const stochnav::NavState& estimate = navigator.state();
  const Eigen::MatrixXd& p = navigator.covariance_now();
  // The filter's attitude error phi (ENU, rad): C_nb_est = (I - [phi x]) C_nb_true, so
  // C_nb_true C_nb_est^T = I + [phi x], a rotation by +phi (filter/error_dynamics.hpp).
  const Eigen::Quaterniond dq = truth.q_nb * estimate.q_nb.conjugate();
  const Eigen::Vector3d attitude_error = 2.0 * dq.vec() * (dq.w() < 0 ? -1.0 : 1.0);
  const Eigen::Vector3d velocity_error = estimate.v_n - truth.v_n;
  double worst_ratio = 0.0;
  for (int i = 0; i < 3; ++i) {
    worst_ratio = std::max(worst_ratio, std::abs(attitude_error[i]) /
                                            std::sqrt(p(cs::kAttitude + i, cs::kAttitude + i)));
    worst_ratio = std::max(worst_ratio, std::abs(velocity_error[i]) /
                                            std::sqrt(p(cs::kVelocity + i, cs::kVelocity + i)));
  }
  const double arcsec = std::numbers::pi / 180.0 / 3600.0;
  std::printf(
      "after %.0f s: attitude error (E, N, U) = (%.2f, %.2f, %.1f) arcsec, "
      "sigma (%.2f, %.2f, %.1f) arcsec\n",
      duration_s, attitude_error[0] / arcsec, attitude_error[1] / arcsec,
      attitude_error[2] / arcsec, std::sqrt(p(cs::kAttitude, cs::kAttitude)) / arcsec,
      std::sqrt(p(cs::kAttitude + 1, cs::kAttitude + 1)) / arcsec,
      std::sqrt(p(cs::kAttitude + 2, cs::kAttitude + 2)) / arcsec);
  const auto& health = navigator.health();
  std::printf("largest |error| / sigma: %.2f; filter health: %s\n", worst_ratio,
              health.ok() ? "ok" : "NOT ok");

  double stationarity = 0.0;
  stationarity = std::max(stationarity, stationarity_error(*plugins.gyro, 0.1, 36000));
  stationarity = std::max(stationarity, stationarity_error(*plugins.accel, 0.1, 36000));
  std::printf("augmented blocks: max relative change of the stationary covariance over 1 h: %.2e\n",
              stationarity);
  if (check && !(stationarity < 1e-9 && health.ok() && worst_ratio < 4.0)) {
    std::fprintf(stderr, "embed_runtime: check failed\n");
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const stochnav::ConfigError& error) {
    std::fprintf(stderr, "embed_runtime: error: %s\n", error.what());
    return 2;
  } catch (const stochnav::InputError& error) {
    std::fprintf(stderr, "embed_runtime: error: %s\n", error.what());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "embed_runtime: internal error: %s\n", error.what());
    return 1;
  }
}
