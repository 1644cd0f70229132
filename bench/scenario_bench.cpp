// Scenario generator and strapdown benchmark. Prints, measured in one run on this machine:
//  1. IMU epochs/s of the scenario generator (exact increments + sensor errors, no output) for the
//     shipped configurations: paper fixed frequency (sine), paper random vibration (256
//     sinusoids), drilling (Gauss-Legendre sub-quadrature), goal >= 1M epochs/s;
//  2. end-to-end `simulate scenario` throughput, CSV files included;
//  3. strapdown updates/s (StrapdownIntegrator::update on simulated drilling increments).
// Usage: scenario_bench [epochs]   (default 2,000,000 per measurement)

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "stochnav/ins/strapdown.hpp"
#include "stochnav/scenario/scenario_config_json.hpp"
#include "stochnav/scenario/scenario_simulator.hpp"
#include "stochnav/scenario/scenario_writer.hpp"
#include "timing.hpp"

namespace {

using stochnav::bench::best_seconds;

stochnav::ScenarioConfig load(const std::string& name) {
  std::ifstream in(std::string(STOCHNAV_SOURCE_DIR) + "/configs/scenarios/" + name);
  return stochnav::scenario_config_from_json(nlohmann::json::parse(in), name);
}

// Epochs/s of the generator over `epochs` epochs starting at `skip_s` into the scenario.
double generator_rate(const stochnav::ScenarioConfig& config, std::uint64_t epochs,
                      bool sensor_errors) {
  double checksum = 0.0;
  std::uint64_t n = 0;
  const double seconds = best_seconds(
      [&] {
        stochnav::ScenarioSimulator simulator(config, 1, sensor_errors);
        stochnav::ScenarioEpoch epoch;
        n = std::min(epochs, simulator.epoch_count());
        for (std::uint64_t k = 0; k < n; ++k) {
          simulator.next(epoch);
          checksum += epoch.measured.delta_v_b.x();
        }
      },
      2);
  if (checksum == 42.0) std::printf(" ");  // keep the loop
  return static_cast<double>(n) / seconds;
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t epochs = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 2000000;
  fmt::print("scenario generator, {} epochs each (exact increments + sensor errors, no I/O)\n",
             epochs);
  const auto fixed = load("paper_fixed_frequency.json");
  const auto random = load("paper_random_vibration.json");
  auto drilling = load("drilling_build_hold.json");
  for (const auto& [name, config] :
       {std::pair<const char*, const stochnav::ScenarioConfig*>{"paper_fixed_frequency", &fixed},
        {"paper_random_vibration", &random},
        {"drilling_build_hold", &drilling}}) {
    const double rate = generator_rate(*config, epochs, true);
    const double motion_only = generator_rate(*config, epochs, false);
    fmt::print("  {:24s} {:8.3f} M epochs/s  (goal >= 1 M/s: {}); true motion alone {:.3f} M/s\n",
               name, rate / 1e6, rate >= 1e6 ? "met" : "NOT met", motion_only / 1e6);
  }

  // End to end with the four files, on the fixed-frequency table cut to `epochs` epochs.
  {
    auto config = fixed;
    auto& phases = config.vibration_table->phases;
    phases.resize(2);
    phases[0].duration_s = 60.0;
    phases[1].duration_s = static_cast<double>(epochs) / config.imu.rate_hz - 60.0;
    const auto out = std::filesystem::temp_directory_path() / "stochnav_scenario_bench";
    stochnav::ScenarioOutputOptions options;
    options.out_dir = out;
    options.seed = 1;
    const auto summary = stochnav::write_scenario_outputs(config, options);
    const auto bytes = std::filesystem::file_size(out / "imu.csv");
    fmt::print("simulate scenario end to end (imu.csv {:.0f} MB, truth at 10 Hz): {:.3f} M "
               "epochs/s\n",
               static_cast<double>(bytes) / 1e6,
               static_cast<double>(summary.epochs) / summary.seconds / 1e6);
    std::filesystem::remove_all(out);
  }

  // Strapdown updates on precomputed drilling increments (rotating tool in the build).
  {
    drilling.drilling->start_md_m = 600.0;
    stochnav::ScenarioSimulator simulator(drilling, 1);
    const std::size_t n = std::min<std::uint64_t>(epochs, 2000000);
    std::vector<stochnav::ImuIncrement> increments(n);
    stochnav::ScenarioEpoch epoch;
    for (auto& increment : increments) {
      simulator.next(epoch);
      increment = epoch.measured;
    }
    const auto initial = simulator.initial_truth();
    stochnav::NavState state;
    state.latitude_rad = initial.latitude_rad;
    state.longitude_rad = initial.longitude_rad;
    state.height_m = initial.height_m;
    state.q_nb = Eigen::Quaterniond(initial.C_nb);
    double checksum = 0.0;
    const double seconds = best_seconds([&] {
      stochnav::StrapdownIntegrator ins(state);
      for (const auto& increment : increments) ins.update(increment);
      checksum += ins.state().height_m;
    });
    fmt::print("strapdown update: {:.3f} M updates/s ({} updates){}\n",
               static_cast<double>(n) / seconds / 1e6, n, checksum == 42.0 ? " " : "");
  }
  return 0;
}
