// GMWM fit benchmark. Prints, measured in one run on this machine, the whole process
// `stochnav fit --method gmwm` (read a CSV, Haar wavelet variance, fit, JSON) beside the anchors
// of issue #30, the R package gmwm on the same task: a four-term fit of 1e6 samples (R: 3.3 s;
// goal: well under 1 s) and a five-model ranking by WIC (R: 1.7 min; goal: seconds).
// The record: white noise, two Gauss-Markov terms (0.1 s and 10 s), a random walk at 100 Hz.
// With the ADIS16405 record of ../shared/data present, the same fits on its gyro X as well.
// Usage: gmwm_bench [samples]   (default 1,000,000)

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "gyro_like_record.hpp"
#include "timing.hpp"

namespace {

constexpr double kRateHz = 100.0;

/// White (sd 0.04) + GM (sd 0.02, 0.1 s) + GM (sd 0.01, 10 s) + random walk, point-sampled.
std::vector<double> four_term_record(std::size_t samples) {
  std::mt19937_64 engine(30);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double phi1 = std::exp(-1.0 / (kRateHz * 0.1));
  const double phi2 = std::exp(-1.0 / (kRateHz * 10.0));
  double gm1 = 0.0, gm2 = 0.0, walk = 0.0;
  std::vector<double> values(samples);
  for (double& y : values) {
    gm1 = phi1 * gm1 + 0.02 * std::sqrt(1.0 - phi1 * phi1) * normal(engine);
    gm2 = phi2 * gm2 + 0.01 * std::sqrt(1.0 - phi2 * phi2) * normal(engine);
    walk += 2e-5 * normal(engine);
    y = 0.04 * normal(engine) + gm1 + gm2 + walk;
  }
  return values;
}

void run(const std::string& what, const std::string& input) {
  const std::string fit = "fit --method gmwm " + input + " --format json --keep-failed";
  const double four = stochnav::bench::cli_seconds(
      STOCHNAV_CLI_PATH,
      fit + " --terms angle_random_walk,gauss_markov,gauss_markov,rate_random_walk");
  const double ranking = stochnav::bench::cli_seconds(
      STOCHNAV_CLI_PATH,
      fit +
          " --candidates \"angle_random_walk+rate_random_walk;"
          "angle_random_walk+gauss_markov;angle_random_walk+gauss_markov+rate_random_walk;"
          "angle_random_walk+gauss_markov+gauss_markov+rate_random_walk;"
          "quantization+angle_random_walk+gauss_markov+gauss_markov+rate_random_walk\"",
      1);
  fmt::print("{}\n", what);
  fmt::print(
      "  four-term fit (ARW+GM+GM+RW), whole process: {:.3f} s; anchor R gmwm 3.3 s "
      "({:.1f}x faster; goal: well under 1 s)\n",
      four, 3.3 / four);
  fmt::print(
      "  five-model --candidates ranking:              {:.3f} s; anchor R gmwm 102 s "
      "({:.0f}x faster; goal: seconds)\n\n",
      ranking, 102.0 / ranking);
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t samples = argc > 1 ? std::stoul(argv[1]) : 1'000'000;
  const auto dir = std::filesystem::temp_directory_path() / "stochnav_gmwm_bench";
  std::filesystem::create_directories(dir);
  const auto csv_path = (dir / "record.csv").string();
  stochnav::bench::write_csv_record(csv_path, four_term_record(samples), samples, kRateHz);
  fmt::print(
      "GMWM fit, whole process (read CSV, wavelet variance, fit, JSON), best of 3 (the "
      "ranking: 1 run)\n\n");
  run(fmt::format("synthetic CSV, {} rows at {} Hz (white + GM 0.1 s + GM 10 s + random walk)",
                  samples, kRateHz),
      fmt::format("--input '{}' --column gyro_x", csv_path));
  const std::string adis =
      std::string(STOCHNAV_SHARED_DATA_DIR) + "/imu-static/adis16405_imu1_static_100hz.csv";
  if (std::filesystem::exists(adis)) {
    run("ADIS16405 gyro X, 1e6 rows of a 7-column CSV",
        fmt::format("--input '{}' --column gyro_x_dps --unit deg/s", adis));
  } else {
    fmt::print("(ADIS16405 record absent from {}: skipped)\n", STOCHNAV_SHARED_DATA_DIR);
  }
  std::filesystem::remove_all(dir);
  return 0;
}
