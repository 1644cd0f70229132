// Navigation filter benchmark: strapdown INS plus the error-state Kalman filter at a 100 Hz IMU
// with 1 Hz static-position updates, noise plugins loaded through the plugin registry as
// `stochnav run` does, for three layouts: the 15 core states (white noise); 21 states, the core
// and the gyro and accelerometer scale factors (KF-GINS's state vector, the goal of DESIGN.md:
// 10x KF-GINS's 76k epochs/s with P every epoch); 21 states, the core and 6 first-order
// Gauss-Markov states (the gauss_markov plugin on both sensors). Prints epochs per second on
// one core with the default covariance interval (0.1 s) and with P propagated at every IMU
// epoch, in memory (no parsing, no output: the filter alone), beside the goal, and the peak
// memory after 1 M and after 5 M epochs (flat: nothing grows with the record's length).
// Against KF-GINS, whose figure is a whole process (parse and output included), compare like
// for like with bench/nav_whole_process.py.
// Usage: navigation_bench [epochs] [layout]   (default 2,000,000; layout: 15, 21sf or 21gm runs
// that layout only, with P every epoch, for a profiler)

#include <sys/resource.h>

#include <fmt/format.h>

#include <ctime>
#include <string>

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

// The noise plugin `type` on both sensors with the given parameters, and the aid.
Plugins load_plugins(const plugin::PluginRegistry& registry, const NavState& initial,
                     const char* type, const nlohmann::json& gyro_params,
                     const nlohmann::json& accel_params) {
  plugin::NoiseModelContext gyro_context{.group = plugin::SensorGroup::kGyro,
                                         .imu_rate_hz = kRateHz, .params_pointer = "/gyro"};
  plugin::NoiseModelContext accel_context{.group = plugin::SensorGroup::kAccel,
                                          .imu_rate_hz = kRateHz, .params_pointer = "/accel"};
  static const plugin::AidData no_data;
  plugin::AidContext aid_context{.params_pointer = "/aid", .data = &no_data,
                                 .initial_state = initial};
  return {registry.create_noise_model(type, gyro_params, gyro_context, "/g"),
          registry.create_noise_model(type, accel_params, accel_context, "/a"),
          registry.create_aid("static_position", {{"nis_gate", false}}, aid_context, "/s")};
}

struct Case {
  const char* name;
  Plugins plugins;
  FilterOptions options;  // covariance_interval_s set per measurement
};

double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// CPU time of this thread (s): steadier than wall time while other processes share the cores.
double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Runs `epochs` IMU epochs of a stationary tool; returns epochs per CPU second.
double run(const Plugins& plugins, const NavState& initial, const FilterOptions& options,
           std::uint64_t epochs) {
  MwdNavigator navigator(initial, *plugins.gyro, *plugins.accel, {plugins.aid.get()}, options);
  const Eigen::Matrix3d c_bn = initial.q_nb.toRotationMatrix().transpose();
  const Eigen::Vector3d omega_b = c_bn * earth_rate_n(initial.latitude_rad);
  const Eigen::Vector3d f_b = -(c_bn * gravity_n(initial.latitude_rad, initial.height_m));
  const double dt = 1.0 / kRateHz;
  const double start = thread_cpu_seconds();
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
  const double seconds = thread_cpu_seconds() - start;
  if (!navigator.health().ok()) fmt::print("  (filter health trouble!)\n");
  return static_cast<double>(epochs) / seconds;
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t epochs = argc > 1 ? std::stoull(argv[1]) : 2'000'000;
  const NavState initial = site();
  const plugin::PluginRegistry registry(plugin::default_search_path());
  const Plugins white = load_plugins(registry, initial, "white", {{"N", 0.005}, {"K", 0.001}},
                                     {{"N", 0.03}});
  const Plugins gauss_markov =
      load_plugins(registry, initial, "gauss_markov",
                   {{"sigma", 0.5}, {"tau_c", 300.0}, {"N", 0.005}, {"K", 0.001}},
                   {{"sigma", 0.7}, {"tau_c", 100.0}, {"N", 0.03}});
  FilterOptions scale_factors;
  scale_factors.gyro_scale_factor_sigma.setConstant(100e-6);
  scale_factors.accel_scale_factor_sigma.setConstant(100e-6);
  const Case cases[] = {{"15 states (core)", white, FilterOptions{}},
                        {"21 states (core + scale factors)", white, scale_factors},
                        {"21 states (core + 6 Gauss-Markov)", gauss_markov, FilterOptions{}}};

  if (argc > 2) {
    const std::string only = argv[2];
    const std::size_t index = only == "15" ? 0 : only == "21sf" ? 1 : only == "21gm" ? 2 : 3;
    if (index == 3) {
      fmt::print(stderr, "unknown layout '{}': 15, 21sf or 21gm\n", only);
      return 2;
    }
    FilterOptions every_epoch = cases[index].options;
    every_epoch.covariance_interval_s = 0.0;
    fmt::print("{}, P every epoch: {:.0f} epochs/s\n", cases[index].name,
               run(cases[index].plugins, initial, every_epoch, epochs));
    return 0;
  }

  fmt::print("MWD navigator: INS + ESKF, {} Hz IMU, 1 Hz static-position updates, {} epochs "
             "(every-epoch cases a quarter), in memory (no parsing, no output), per second of this "
             "thread's CPU time\n"
             "goal (DESIGN.md): 21 states with P every epoch >= 760k epochs/s whole process "
             "(10x KF-GINS's 76k)\n\n",
             kRateHz, epochs);
  fmt::print("{:<36}{:>20}{:>20}{:>22}\n", "layout", "P every 0.1 s (def.)", "P every epoch",
             "every epoch / 760k");
  for (const Case& layout : cases) {
    FilterOptions interval = layout.options;
    const double default_rate = run(layout.plugins, initial, interval, epochs);
    FilterOptions every_epoch = layout.options;
    every_epoch.covariance_interval_s = 0.0;
    const double every_rate = run(layout.plugins, initial, every_epoch, epochs / 4);
    fmt::print("{:<36}{:>20.0f}{:>20.0f}{:>22.2f}\n", layout.name, default_rate, every_rate,
               every_rate / 760e3);
  }

  run(white, initial, FilterOptions{}, 1'000'000);
  const double after_1m = peak_memory_mb();
  run(white, initial, FilterOptions{}, 5'000'000);
  fmt::print("\npeak memory after 1 M epochs: {:.1f} MB; after 5 M more: {:.1f} MB (flat)\n",
             after_1m, peak_memory_mb());
  return 0;
}
