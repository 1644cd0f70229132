// Cost of augmented states: the MWD navigator (INS at 100 Hz, P propagated every 0.1 s, 1 Hz
// static-position updates) per IMU epoch with a 15-state filter (white-noise models) against
// the same with ~100 augmented states: the `augmented` plugin with a 0.5 deg/h flicker floor
// for the gyros and 2e-4 m/s^2 for the accelerometers, each the simulator's bank (2 components
// per decade, tau0 = 0.01 s, band up to the 36-h record of the drilling scenario, as the oracle
// plugin builds it). Prints the cost per epoch and its ratio to the 15-state filter (goal
// <= 5x) with the covariance products by blocks (FilterOptions::structured_covariance, the
// default) and with the dense products of earlier versions, measured in one run, and the heap
// allocations per epoch (goal: none once running). The same model declared time-varying (the
// oracle plugin with a white-noise schedule) shows the cost of refreshing Phi_t and Q_t at
// every interval instead of once.
// CPU time of this thread, best of three interleaved runs (other processes share the cores).
// Usage: augmented_state_bench [seconds of record per 15-state run (default 20,000)] [--profile]
//   --profile: runs the augmented filter by blocks only, for a profiler.

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <memory>
#include <string>

#include "stochnav/filter/mwd_navigator.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/plugin/plugin_registry.hpp"

// Counts heap allocations (malloc is what Eigen and operator new call) by interposing glibc's.
namespace {
std::atomic<std::uint64_t> allocations{0};
}  // namespace
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) noexcept {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}

namespace {

using namespace stochnav;

constexpr double kRateHz = 100.0;
constexpr double kRecordS = 36.0 * 3600.0;  // the drilling scenario: the flicker band's end

NavState site() {
  NavState state;
  state.latitude_rad = 39.9778 * std::numbers::pi / 180;
  state.longitude_rad = 116.3448 * std::numbers::pi / 180;
  state.height_m = 50.0;
  state.q_nb =
      quaternion_from_mwd({.inclination_rad = 1.2, .toolface_rad = 0.5, .azimuth_rad = 2.0});
  return state;
}

struct Plugins {
  std::shared_ptr<plugin::NoiseModelPlugin> gyro, accel;
};

plugin::NoiseModelContext context(plugin::SensorGroup group) {
  return {.group = group, .imu_rate_hz = kRateHz, .params_pointer = "/noise"};
}

Plugins white(const plugin::PluginRegistry& registry) {
  return {registry.create_noise_model("white", {{"N", 0.005}, {"K", 0.001}},
                                      context(plugin::SensorGroup::kGyro), "/g"),
          registry.create_noise_model("white", {{"N", 0.03}}, context(plugin::SensorGroup::kAccel),
                                      "/a")};
}

Plugins augmented(const plugin::PluginRegistry& registry) {
  const auto params = [](const nlohmann::json& terms, const char* units) {
    return nlohmann::json{{"model", {{"units", units}, {"rate_hz", kRateHz}, {"terms", terms}}},
                          {"flicker_band_max_s", kRecordS},
                          {"flicker_components_per_decade", 2}};
  };
  // Per axis: gyro 14 bank states, a Gauss-Markov state and a ramp (2 x 2 block); accelerometer
  // 14 bank states and an oscillator (2 x 2 block).
  const nlohmann::json gyro = {{{"type", "angle_random_walk"}, {"N", 0.3}},
                               {{"type", "bias_instability"}, {"B", 0.5}},
                               {{"type", "gauss_markov"}, {"sigma", 0.5}, {"tau_c", 30}},
                               {{"type", "rate_ramp"}, {"R", 0.1}}};
  const nlohmann::json accel = {
      {{"type", "angle_random_walk"}, {"N", 5e-4}},
      {{"type", "bias_instability"}, {"B", 2e-4}},
      {{"type", "sinusoid"}, {"amplitude", 1e-4}, {"frequency_hz", 0.02}}};
  return {registry.create_noise_model("augmented", params(gyro, "deg/h"),
                                      context(plugin::SensorGroup::kGyro), "/g"),
          registry.create_noise_model("augmented", params(accel, "m/s^2"),
                                      context(plugin::SensorGroup::kAccel), "/a")};
}

// The same model declared time-varying (as the oracle plugin is when its white noise follows a
// schedule): the navigator then asks for Phi and Qd at every interval and checks their pattern.
class TimeVarying final : public plugin::NoiseModelPlugin {
 public:
  explicit TimeVarying(std::shared_ptr<plugin::NoiseModelPlugin> model)
      : NoiseModelPlugin(model->group()), model_(std::move(model)) {}
  std::string_view type() const override { return model_->type(); }
  int augmented_size() const override { return model_->augmented_size(); }
  bool time_varying() const override { return true; }
  void white_noise_covariance(double t_s, double dt_s,
                              Eigen::Ref<Eigen::MatrixXd> q_white) const override {
    model_->white_noise_covariance(t_s, dt_s, q_white);
  }
  void bias_walk_covariance(double t_s, double dt_s,
                            Eigen::Ref<Eigen::MatrixXd> q_bias) const override {
    model_->bias_walk_covariance(t_s, dt_s, q_bias);
  }
  void augmented_transition(double t_s, double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                            Eigen::Ref<Eigen::MatrixXd> q_d) const override {
    model_->augmented_transition(t_s, dt_s, phi, q_d);
  }
  void augmented_initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const override {
    model_->augmented_initial_covariance(p0);
  }
  void augmented_sensor_map(Eigen::Ref<Eigen::MatrixXd> map) const override {
    model_->augmented_sensor_map(map);
  }
  nlohmann::json params() const override { return model_->params(); }
  std::string describe() const override { return model_->describe(); }
  bool equals(const NoiseModelPlugin& other, double rel_tol) const override {
    return model_->equals(other, rel_tol);
  }

 private:
  std::shared_ptr<plugin::NoiseModelPlugin> model_;
};

double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

struct Measurement {
  double seconds_per_epoch = std::numeric_limits<double>::infinity();
  double allocations_per_epoch = 0.0;  // after the first simulated minute
  int states = 0;
};

// Runs `epochs` IMU epochs of a stationary tool; keeps the best time per epoch in `best`.
void run(const Plugins& plugins, plugin::AidPlugin& aid, bool structured, std::uint64_t epochs,
         Measurement& best) {
  const NavState initial = site();
  FilterOptions options;
  options.structured_covariance = structured;
  MwdNavigator navigator(initial, *plugins.gyro, *plugins.accel, {&aid}, options);
  const Eigen::Matrix3d c_bn = initial.q_nb.toRotationMatrix().transpose();
  const Eigen::Vector3d omega_b = c_bn * earth_rate_n(initial.latitude_rad);
  const Eigen::Vector3d f_b = -(c_bn * gravity_n(initial.latitude_rad, initial.height_m));
  const double dt = 1.0 / kRateHz;
  ImuIncrement increment;
  increment.dt_s = dt;
  const std::uint64_t warm_up = 6000;  // one minute: every scratch matrix has met its size
  double start = 0.0;
  std::uint64_t allocations_at_start = 0;
  for (std::uint64_t k = 1; k <= warm_up + epochs; ++k) {
    if (k == warm_up + 1) {
      allocations_at_start = allocations.load();
      start = thread_cpu_seconds();
    }
    increment.t_s = static_cast<double>(k) * dt;
    // A small deterministic wobble so nothing is constant-folded.
    const double wobble = 1e-7 * static_cast<double>(k % 7);
    increment.delta_theta_b = (omega_b + Eigen::Vector3d::Constant(wobble * 1e-3)) * dt;
    increment.delta_v_b = (f_b + Eigen::Vector3d::Constant(wobble)) * dt;
    navigator.step(increment);
  }
  const double seconds = thread_cpu_seconds() - start;
  if (!navigator.health().ok()) fmt::print("  (filter health trouble!)\n");
  best.seconds_per_epoch = std::min(best.seconds_per_epoch, seconds / static_cast<double>(epochs));
  best.allocations_per_epoch = std::max(
      best.allocations_per_epoch,
      static_cast<double>(allocations.load() - allocations_at_start) / static_cast<double>(epochs));
  best.states = static_cast<int>(navigator.covariance().rows());
}

}  // namespace

int main(int argc, char** argv) {
  const double record_s = argc > 1 ? std::stod(argv[1]) : 20000.0;
  const auto epochs = static_cast<std::uint64_t>(record_s * kRateHz);
  const plugin::PluginRegistry registry(plugin::default_search_path());
  static const plugin::AidData no_data;
  const auto aid = registry.create_aid(
      "static_position", {{"nis_gate", false}},
      {.params_pointer = "/aid", .data = &no_data, .initial_state = site()}, "/s");
  const Plugins small = white(registry);
  const Plugins large = augmented(registry);
  const Plugins varying{std::make_shared<TimeVarying>(large.gyro),
                        std::make_shared<TimeVarying>(large.accel)};

  Measurement white_structured, white_dense, augmented_structured, augmented_dense,
      varying_structured;
  if (argc > 2 && std::string(argv[2]) == "--profile") {
    run(large, *aid, true, epochs, augmented_structured);
    fmt::print("augmented, by blocks: {:.2f} us/epoch\n",
               1e6 * augmented_structured.seconds_per_epoch);
    return 0;
  }
  for (int repeat = 0; repeat < 3; ++repeat) {
    run(small, *aid, true, epochs, white_structured);
    run(small, *aid, false, epochs, white_dense);
    run(large, *aid, true, epochs / 4, augmented_structured);
    run(varying, *aid, true, epochs / 4, varying_structured);
    run(large, *aid, false, epochs / 200, augmented_dense);
  }

  fmt::print(
      "MWD navigator per IMU epoch: INS at {} Hz, P every 0.1 s, 1 Hz static-position updates; "
      "thread CPU time, best of 3\n",
      kRateHz);
  fmt::print(
      "augmented: gyro B = 0.5 deg/h, accel B = 2e-4 m/s^2 flicker banks (2 per decade, "
      "0.01 s to {:.0f} h), gyro Gauss-Markov and ramp, accel sinusoid: {} + {} states\n\n",
      kRecordS / 3600.0, large.gyro->augmented_size(), large.accel->augmented_size());
  const auto line = [&](const char* name, const Measurement& m) {
    fmt::print(
        "{:<34} n = {:>3}  {:>9.2f} us/epoch  {:>6.1f}x the 15-state filter  "
        "{:.2g} allocations/epoch\n",
        name, m.states, 1e6 * m.seconds_per_epoch,
        m.seconds_per_epoch / white_structured.seconds_per_epoch, m.allocations_per_epoch);
  };
  line("15 states, by blocks (default)", white_structured);
  line("15 states, dense products", white_dense);
  line("augmented, by blocks (default)", augmented_structured);
  line("augmented, time-varying, by blocks", varying_structured);
  line("augmented, dense products (old)", augmented_dense);
  fmt::print(
      "\ngoal: augmented by blocks <= 5x the 15-state filter; a {:.0f}-h record at "
      "100 Hz: {:.0f} s by blocks, {:.0f} s dense, {:.0f} s with 15 states\n",
      kRecordS / 3600.0, kRecordS * kRateHz * augmented_structured.seconds_per_epoch,
      kRecordS * kRateHz * augmented_dense.seconds_per_epoch,
      kRecordS * kRateHz * white_structured.seconds_per_epoch);
  return 0;
}
