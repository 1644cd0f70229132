// Navigation filter benchmark: strapdown INS plus the 15-state error-state Kalman filter at a
// 100 Hz IMU with 1 Hz static-position updates, white-noise plugins loaded through the plugin
// registry as `stochnav run` does. Prints epochs per second on one core with the default
// covariance interval (0.1 s) and with P propagated at every IMU epoch, in memory (no parsing,
// no output: the filter alone), and the peak memory after 1 M and after 5 M epochs (flat:
// nothing grows with the record's length). Against KF-GINS, whose figure is a whole process
// (parse and output included), compare like for like with bench/nav_whole_process.py.
// Usage: navigation_bench [epochs]   (default 2,000,000)

#include <sys/resource.h>

#include <fmt/format.h>

#include <chrono>

#include "stochnav/filter/mwd_navigator.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/plugin/plugin_registry.hpp"

namespace {

using namespace stochnav;

constexpr double kRateHz = 100.0;

NavState site() {
  NavState state;
  state.latitude_rad = 39.9778 * std::numbers::pi / 180;
  state.longitude_rad = 116.3448 * std::numbers::pi / 180;
  state.height_m = 50.0;
  state.q_nb = quaternion_from_mwd({.inclination_rad = 1.2, .toolface_rad = 0.5, .azimuth_rad = 2.0});
  return state;
}

struct Plugins {
  std::shared_ptr<plugin::NoiseModelPlugin> gyro, accel;
  std::shared_ptr<plugin::AidPlugin> aid;
};

Plugins load_plugins(const plugin::PluginRegistry& registry, const NavState& initial) {
  plugin::NoiseModelContext gyro_context{.group = plugin::SensorGroup::kGyro,
                                         .imu_rate_hz = kRateHz, .params_pointer = "/gyro"};
  plugin::NoiseModelContext accel_context{.group = plugin::SensorGroup::kAccel,
                                          .imu_rate_hz = kRateHz, .params_pointer = "/accel"};
  static const plugin::AidData no_data;
  plugin::AidContext aid_context{.params_pointer = "/aid", .data = &no_data,
                                 .initial_state = initial};
  return {registry.create_noise_model("white", {{"N", 0.005}, {"K", 0.001}}, gyro_context, "/g"),
          registry.create_noise_model("white", {{"N", 0.03}}, accel_context, "/a"),
          registry.create_aid("static_position", {{"nis_gate", false}}, aid_context, "/s")};
}

double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// Runs `epochs` IMU epochs of a stationary tool; returns epochs per second.
double run(const Plugins& plugins, const NavState& initial, const FilterOptions& options,
           std::uint64_t epochs) {
  MwdNavigator navigator(initial, *plugins.gyro, *plugins.accel, {plugins.aid.get()}, options);
  const Eigen::Matrix3d c_bn = initial.q_nb.toRotationMatrix().transpose();
  const Eigen::Vector3d omega_b = c_bn * earth_rate_n(initial.latitude_rad);
  const Eigen::Vector3d f_b = -(c_bn * gravity_n(initial.latitude_rad, initial.height_m));
  const double dt = 1.0 / kRateHz;
  const auto start = std::chrono::steady_clock::now();
  ImuIncrement increment;
  increment.dt_s = dt;
  for (std::uint64_t k = 1; k <= epochs; ++k) {
    increment.t_s = static_cast<double>(k) * dt;
    // A small deterministic wobble so nothing is constant-folded.
    const double wobble = 1e-7 * static_cast<double>(k % 7);
    increment.delta_theta_b = (omega_b + Eigen::Vector3d::Constant(wobble * 1e-3)) * dt;
    increment.delta_v_b = (f_b + Eigen::Vector3d::Constant(wobble)) * dt;
    navigator.step(increment);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!navigator.health().ok()) fmt::print("  (filter health trouble!)\n");
  return static_cast<double>(epochs) / seconds;
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t epochs = argc > 1 ? std::stoull(argv[1]) : 2'000'000;
  const NavState initial = site();
  const plugin::PluginRegistry registry(plugin::default_search_path());
  const Plugins plugins = load_plugins(registry, initial);

  fmt::print("MWD navigator: INS + 15-state ESKF, {} Hz IMU, 1 Hz static-position updates, "
             "{} epochs, one core\n\n", kRateHz, epochs);
  FilterOptions interval;
  const double default_rate = run(plugins, initial, interval, epochs);
  fmt::print("covariance every 0.1 s (default): {:>10.0f} epochs/s (in memory)\n",
             default_rate);
  FilterOptions every_epoch;
  every_epoch.covariance_interval_s = 0.0;
  const double every_rate = run(plugins, initial, every_epoch, epochs / 4);
  fmt::print("covariance every IMU epoch:       {:>10.0f} epochs/s (in memory)\n\n",
             every_rate);

  run(plugins, initial, interval, 1'000'000);
  const double after_1m = peak_memory_mb();
  run(plugins, initial, interval, 5'000'000);
  fmt::print("peak memory after 1 M epochs: {:.1f} MB; after 5 M more: {:.1f} MB (flat)\n",
             after_1m, peak_memory_mb());
  return 0;
}
