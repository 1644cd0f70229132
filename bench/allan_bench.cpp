// Allan-variance engine benchmark. Prints, measured in one run on this machine:
//  1. OADEV at octave taus on 1e7 samples (load + compute) against the numpy anchor
//     ../shared/tools/numpy_oadev.py (allantools' estimator), with the largest relative
//     difference of the numbers;
//  2. DAVAR (window 50,000, step 5,000) on the same record against one OADEV pass, and against
//     the naive per-window recomputation;
//  3. CSV parsing throughput.
// Usage: allan_bench [samples]   (default 10,000,000)

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "stochnav/io/record.hpp"
#include "stochnav/stats/davar.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/phase.hpp"
#include "gyro_like_record.hpp"
#include "timing.hpp"

namespace {

using stochnav::bench::best_seconds;
using stochnav::bench::gyro_like_record;
using stochnav::bench::write_csv_record;
using stochnav::bench::write_float64_record;

std::string run_command(const std::string& command) {
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return {};
  std::string out;
  std::array<char, 4096> chunk{};
  while (std::fgets(chunk.data(), chunk.size(), pipe) != nullptr) out += chunk.data();
  ::pclose(pipe);
  return out;
}

std::vector<stochnav::DeviationPoint> oadev_octave(const stochnav::Record& record) {
  const auto phase = stochnav::phase_from_rate(record.values, record.tau0());
  const auto m = stochnav::averaging_factors(stochnav::Deviation::kOadev,
                                             stochnav::TauSpacing::kOctave, phase.size());
  const auto values =
      stochnav::deviation_values(stochnav::Deviation::kOadev, phase, record.tau0(), m);
  std::vector<stochnav::DeviationPoint> points;
  for (std::size_t i = 0; i < m.size(); ++i) {
    points.push_back({.m = m[i], .tau_s = static_cast<double>(m[i]) * record.tau0(),
                      .deviation = values[i]});
  }
  return points;
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t samples = argc > 1 ? std::stoul(argv[1]) : 10'000'000;
  const double rate_hz = 100.0;
  const auto dir = std::filesystem::temp_directory_path() / "stochnav_allan_bench";
  std::filesystem::create_directories(dir);
  const auto f64_path = (dir / "record.f64").string();
  const std::vector<double> values = gyro_like_record(samples);
  write_float64_record(f64_path, values);

  fmt::print("Allan-variance engine, {} samples at {} Hz\n\n", samples, rate_hz);

  // 1. OADEV, octave taus: load + compute, as the numpy script measures itself.
  stochnav::ReadOptions read{.path = f64_path, .rate_hz = rate_hz};
  std::vector<stochnav::DeviationPoint> ours;
  const double oadev_seconds = best_seconds([&] { ours = oadev_octave(stochnav::read_record(read)); });
  const stochnav::Record record = stochnav::read_record(read);
  const double compute_seconds = best_seconds([&] { ours = oadev_octave(record); });
  fmt::print("OADEV octave ({} taus): load+compute {:.4f} s, compute only {:.4f} s\n", ours.size(),
             oadev_seconds, compute_seconds);

  const std::string script =
      (std::filesystem::path(STOCHNAV_SOURCE_DIR) / "../shared/tools/numpy_oadev.py").string();
  double numpy_seconds = std::nan("");
  if (std::filesystem::exists(script)) {
    double best = INFINITY;
    nlohmann::json anchor;
    for (int i = 0; i < 3; ++i) {
      const std::string out = run_command("/usr/bin/python3 '" + script + "' '" + f64_path + "' " +
                                          std::to_string(rate_hz));
      if (out.empty()) break;
      anchor = nlohmann::json::parse(out);
      best = std::min(best, anchor["seconds"].get<double>());
    }
    if (!anchor.is_null()) {
      numpy_seconds = best;
      double worst = 0.0;
      const auto& adev = anchor["adev"];
      for (std::size_t i = 0; i < std::min(adev.size(), ours.size()); ++i) {
        worst = std::max(worst, std::abs(ours[i].deviation / adev[i].get<double>() - 1.0));
      }
      fmt::print("numpy anchor (numpy_oadev.py): {:.4f} s, {} taus, largest relative difference "
                 "{:.2e}\n", numpy_seconds, adev.size(), worst);
      fmt::print("  speed-up over numpy: {:.1f}x (goal >= 10x)\n\n", numpy_seconds / oadev_seconds);
    }
  }
  if (std::isnan(numpy_seconds)) {
    fmt::print("numpy anchor unavailable (needs ../shared/tools/numpy_oadev.py and python3-numpy)\n\n");
  }

  // 2. DAVAR with window 50,000 and step 5,000 against one OADEV pass and the naive method.
  const stochnav::DavarOptions davar_options{.window = 50'000, .step = 5'000};
  stochnav::DavarResult davar;
  const double davar_seconds =
      best_seconds([&] { davar = stochnav::dynamic_allan_deviation(record, davar_options); });
  const double naive_seconds = best_seconds(
      [&] {
        for (std::size_t k = 0; k < davar.time_s.size(); ++k) {
          const std::span<const double> window(record.values.data() + k * davar_options.step,
                                               davar_options.window);
          const auto phase = stochnav::phase_from_rate(window, record.tau0());
          for (std::size_t m : davar.m) {
            volatile double sink = stochnav::deviation_value(stochnav::Deviation::kOadev, phase,
                                                             record.tau0(), m);
            (void)sink;
          }
        }
      },
      1);
  fmt::print("DAVAR window {} step {}: {} windows x {} taus in {:.4f} s\n", davar_options.window,
             davar_options.step, davar.time_s.size(), davar.m.size(), davar_seconds);
  fmt::print("  cost relative to one OADEV pass (compute only): {:.2f}x (goal <= 2x)\n",
             davar_seconds / compute_seconds);
  fmt::print("  naive per-window recomputation: {:.4f} s, speed-up {:.1f}x\n\n", naive_seconds,
             naive_seconds / davar_seconds);

  // 3. CSV parsing throughput (t and one value column).
  const std::size_t csv_rows = std::min<std::size_t>(samples, 2'000'000);
  const auto csv_path = (dir / "record.csv").string();
  write_csv_record(csv_path, values, csv_rows, rate_hz);
  const double csv_bytes = static_cast<double>(std::filesystem::file_size(csv_path));
  const double csv_seconds =
      best_seconds([&] { (void)stochnav::read_record({.path = csv_path, .column = "gyro_x"}); });
  fmt::print("CSV parsing: {:.1f} MB in {:.3f} s = {:.1f} MB/s\n", csv_bytes / 1e6, csv_seconds,
             csv_bytes / 1e6 / csv_seconds);
  std::filesystem::remove_all(dir);
  return 0;
}
