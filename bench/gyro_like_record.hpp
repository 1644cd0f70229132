#pragma once
// The benchmarks' synthetic gyro record: a 0.4 offset, a slow random walk and white noise
// (arbitrary units), seeded, so every benchmark times the same kind of data.

#include <fmt/format.h>

#include <cstddef>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace stochnav::bench {

inline std::vector<double> gyro_like_record(std::size_t samples) {
  std::mt19937_64 engine(42);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> values(samples);
  double walk = 0.0;
  for (double& y : values) {
    walk += 1e-4 * normal(engine);
    y = 0.4 + walk + 0.04 * normal(engine);
  }
  return values;
}

/// Writes the values as raw float64 (native byte order): what `--input X.f64 --rate R` reads.
inline void write_float64_record(const std::string& path, const std::vector<double>& values) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(values.data()),
             static_cast<std::streamsize>(values.size() * sizeof(double)));
}

/// Writes the first `rows` values as a CSV with columns t (s, at rate_hz) and gyro_x.
inline void write_csv_record(const std::string& path, const std::vector<double>& values,
                             std::size_t rows, double rate_hz) {
  std::ofstream csv(path);
  csv << "t,gyro_x\n";
  for (std::size_t i = 0; i < rows; ++i) {
    csv << fmt::format("{:.2f},{:.17g}\n", static_cast<double>(i) / rate_hz, values[i]);
  }
}

}  // namespace stochnav::bench
