// Wavelet-variance benchmark. Prints, measured in one run on this machine, the whole process
// `stochnav wv` (classical, streamed; and --robust) beside its anchor, `stochnav allan` (OADEV,
// octave taus) on the same record: a raw float64 record of 1e7 samples and a CSV of 2e6 rows.
// Usage: wv_bench [samples]   (default 10,000,000)

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "gyro_like_record.hpp"
#include "timing.hpp"

namespace {

using stochnav::bench::gyro_like_record;
using stochnav::bench::write_csv_record;
using stochnav::bench::write_float64_record;

double cli_seconds(const std::string& arguments, int repeats = 3) {
  return stochnav::bench::cli_seconds(STOCHNAV_CLI_PATH, arguments, repeats);
}

void compare(const std::string& what, const std::string& input) {
  const double allan = cli_seconds("allan " + input + " --taus octave --format csv");
  const double wv = cli_seconds("wv " + input + " --format csv");
  const double robust = cli_seconds("wv " + input + " --robust --format csv", 1);
  fmt::print("{}\n", what);
  fmt::print("  anchor, stochnav allan (OADEV octave): {:.3f} s\n", allan);
  fmt::print(
      "  stochnav wv (classical, streamed):     {:.3f} s = {:.2f}x the anchor (goal: comparable)\n",
      wv, wv / allan);
  fmt::print("  stochnav wv --robust:                  {:.3f} s = {:.2f}x the anchor\n\n", robust,
             robust / allan);
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t samples = argc > 1 ? std::stoul(argv[1]) : 10'000'000;
  const double rate_hz = 100.0;
  const auto dir = std::filesystem::temp_directory_path() / "stochnav_wv_bench";
  std::filesystem::create_directories(dir);
  const std::vector<double> values = gyro_like_record(samples);
  const auto f64_path = (dir / "record.f64").string();
  write_float64_record(f64_path, values);
  const std::size_t csv_rows = std::min<std::size_t>(samples, 2'000'000);
  const auto csv_path = (dir / "record.csv").string();
  write_csv_record(csv_path, values, csv_rows, rate_hz);
  fmt::print("Haar wavelet variance, whole process, against stochnav allan on the same record\n\n");
  compare(fmt::format("raw float64, {} samples at {} Hz", samples, rate_hz),
          fmt::format("--input '{}' --rate {}", f64_path, rate_hz));
  compare(fmt::format("CSV, {} rows (t, gyro_x)", csv_rows),
          fmt::format("--input '{}' --column gyro_x", csv_path));
  std::filesystem::remove_all(dir);
  return 0;
}
