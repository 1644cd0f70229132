// Embedding the stochnav runtime without the CLI: load noise-model plugins, build (or fit) the
// models, let the runtime lay out the error state, and propagate the filter covariance P
// through the plugins' Phi and Q over a simulated static hour.
//
//   embed_runtime                      gyro: "gauss_markov" fitted to a simulated 10-minute
//                                      static calibration record; accel: "white" from params
//   embed_runtime RUN_CONFIG.json      the noise models of a run config (plugins found in the
//                                      config's folder, $STOCHNAV_PLUGIN_PATH, the package)
//   --check                            exit 1 unless every augmented block keeps its stationary
//                                      covariance and P stays symmetric positive definite
//
// The error-state model is the static, stationary part of the 15-state ESKF (ENU, body = nav):
//   dr' = dv,  dv' = f_n x phi + db_a + M_a x_a + w_a,  phi' = -w_ie_n x phi - (db_g + M_g x_g +
//   w_g),
// discretised as Phi = I + F dt with the plugins' exact augmented blocks. The lead's filter
// (filter/) replaces this loop; the plugin calls are the ones it makes.

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/model/noise_model.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/plugin/runtime.hpp"
#include "stochnav/plugin/state_layout.hpp"
#include "stochnav/sim/noise_generator.hpp"
#include "stochnav/version.hpp"

namespace sp = stochnav::plugin;

namespace {

constexpr double kDegPerHour = std::numbers::pi / 180.0 / 3600.0;  // rad/s
constexpr double kGravity = 9.80665;                               // m/s^2
constexpr double kEarthRate = 7.292115e-5;                         // rad/s

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

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
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--check") {
      check = true;
    } else {
      config_path = argument;
    }
  }
  std::printf("stochnav %s, plugin API %u\n", std::string(stochnav::kVersion).c_str(),
              sp::kPluginApiVersion);

  sp::RunPlugins plugins;
  if (config_path.empty()) {
    const sp::PluginRegistry registry(sp::default_search_path());
    plugins = demo_plugins(registry);
  } else {
    const sp::RunConfig config = sp::read_run_config(config_path);
    const sp::PluginRegistry registry(sp::default_search_path(config.config_dir));
    plugins = sp::build_run_plugins(config, registry, sp::AidData(), stochnav::NavState(), 100.0);
  }
  std::printf("gyro:  %s\naccel: %s\nerror state: %d states\n", plugins.gyro->describe().c_str(),
              plugins.accel->describe().c_str(), plugins.layout.size());

  // Static hour: IMU at 100 Hz, covariance propagated every 10 IMU samples (0.1 s).
  const double dt = 0.1, duration_s = 3600.0, latitude = 30.0 * std::numbers::pi / 180.0;
  const int n = plugins.layout.size();
  const Eigen::Vector3d f_n(0.0, 0.0, kGravity);
  const Eigen::Vector3d w_ie_n(0.0, kEarthRate * std::cos(latitude),
                               kEarthRate * std::sin(latitude));
  namespace cs = sp::core_state;
  const int ga = plugins.gyro->placement().augmented_offset;
  const int aa = plugins.accel->placement().augmented_offset;
  const int ng = plugins.gyro->augmented_size(), na = plugins.accel->augmented_size();

  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(n, n);
  const double deg = std::numbers::pi / 180.0;
  p.block<3, 3>(cs::kPosition, cs::kPosition).diagonal().setConstant(0.01);
  p.block<3, 3>(cs::kVelocity, cs::kVelocity).diagonal().setConstant(1e-4);
  p.block<3, 3>(cs::kAttitude, cs::kAttitude).diagonal() << std::pow(0.05 * deg, 2),
      std::pow(0.05 * deg, 2), std::pow(0.5 * deg, 2);
  p.block<3, 3>(cs::kAccelBias, cs::kAccelBias).diagonal().setConstant(1e-6);
  p.block<3, 3>(cs::kGyroBias, cs::kGyroBias)
      .diagonal()
      .setConstant(std::pow(0.05 * kDegPerHour, 2));
  Eigen::MatrixXd map_g(3, ng), map_a(3, na);
  plugins.gyro->augmented_sensor_map(map_g);
  plugins.accel->augmented_sensor_map(map_a);
  if (ng > 0) plugins.gyro->augmented_initial_covariance(p.block(ga, ga, ng, ng));
  if (na > 0) plugins.accel->augmented_initial_covariance(p.block(aa, aa, na, na));

  // Per-step buffers: sized once, written by the plugins in place (no allocation per step).
  Eigen::MatrixXd phi = Eigen::MatrixXd::Identity(n, n), q = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd tmp(n, n);
  Eigen::Matrix3d qw_g, qw_a, qb_g, qb_a;
  phi.block<3, 3>(cs::kPosition, cs::kVelocity) = Eigen::Matrix3d::Identity() * dt;
  phi.block<3, 3>(cs::kVelocity, cs::kAttitude) = skew(f_n) * dt;
  phi.block<3, 3>(cs::kVelocity, cs::kAccelBias) = Eigen::Matrix3d::Identity() * dt;
  phi.block<3, 3>(cs::kAttitude, cs::kAttitude) -= skew(w_ie_n) * dt;
  phi.block<3, 3>(cs::kAttitude, cs::kGyroBias) = -Eigen::Matrix3d::Identity() * dt;
  if (ng > 0) phi.block(cs::kAttitude, ga, 3, ng) = -map_g * dt;
  if (na > 0) phi.block(cs::kVelocity, aa, 3, na) = map_a * dt;

  const int steps = static_cast<int>(std::lround(duration_s / dt));
  for (int k = 0; k < steps; ++k) {
    const double t = k * dt;
    plugins.gyro->white_noise_covariance(t, dt, qw_g);
    plugins.accel->white_noise_covariance(t, dt, qw_a);
    plugins.gyro->bias_walk_covariance(t, dt, qb_g);
    plugins.accel->bias_walk_covariance(t, dt, qb_a);
    q.block<3, 3>(cs::kVelocity, cs::kVelocity) = qw_a;
    q.block<3, 3>(cs::kAttitude, cs::kAttitude) = qw_g;
    q.block<3, 3>(cs::kAccelBias, cs::kAccelBias) = qb_a;
    q.block<3, 3>(cs::kGyroBias, cs::kGyroBias) = qb_g;
    if (ng > 0) {
      plugins.gyro->augmented_transition(t, dt, phi.block(ga, ga, ng, ng), q.block(ga, ga, ng, ng));
    }
    if (na > 0) {
      plugins.accel->augmented_transition(t, dt, phi.block(aa, aa, na, na),
                                          q.block(aa, aa, na, na));
    }
    tmp.noalias() = phi * p;
    p.noalias() = tmp * phi.transpose();
    p += q;
    if ((k + 1) % 6000 == 0) {
      std::printf("t = %5.0f s: sigma east/north/up %.3g/%.3g/%.3g m, heading %.4g deg\n",
                  (k + 1) * dt, std::sqrt(p(0, 0)), std::sqrt(p(1, 1)), std::sqrt(p(2, 2)),
                  std::sqrt(p(cs::kAttitude + 2, cs::kAttitude + 2)) / deg);
    }
  }

  const double gyro_drift = stationarity_error(*plugins.gyro, 0.01, 100000);
  const double accel_drift = stationarity_error(*plugins.accel, 0.01, 100000);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (p + p.transpose()));
  std::printf("augmented stationarity error: gyro %.2e, accel %.2e; min eigenvalue of P %.3e\n",
              gyro_drift, accel_drift, eigen.eigenvalues().minCoeff());
  if (check &&
      (gyro_drift > 1e-8 || accel_drift > 1e-8 || !(eigen.eigenvalues().minCoeff() > 0.0))) {
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
