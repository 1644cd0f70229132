#pragma once
// The benchmarks' synthetic gyro record: a 0.4 offset, a slow random walk and white noise
// (arbitrary units), seeded, so every benchmark times the same kind of data.

#include <cstddef>
#include <random>
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

}  // namespace stochnav::bench
