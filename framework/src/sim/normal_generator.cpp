#include "stochnav/sim/normal_generator.hpp"

#include <cmath>

namespace stochnav {
namespace {

// Base edge r and common layer area v of the 256-layer ziggurat for exp(-x^2/2)
// (Marsaglia & Tsang, "The ziggurat method for generating random variables", 2000).
constexpr double kBaseEdge = 3.6541528853610088;
constexpr double kLayerArea = 4.92867323399e-3;

double density(double x) { return std::exp(-0.5 * x * x); }

NormalGenerator::Table make_table() {
  NormalGenerator::Table table{};
  table.x[0] = kLayerArea / density(kBaseEdge);
  table.x[1] = kBaseEdge;
  for (std::size_t i = 1; i < 255; ++i) {
    const double next_density = density(table.x[i]) + kLayerArea / table.x[i];
    table.x[i + 1] = std::sqrt(-2.0 * std::log(next_density));
  }
  table.x[256] = 0.0;
  for (std::size_t i = 0; i < table.x.size(); ++i) table.f[i] = density(table.x[i]);
  table.f[0] = 0.0;  // the base layer's rectangle reaches down to y = 0
  return table;
}

std::uint64_t splitmix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace

std::uint64_t derive_stream_seed(std::uint64_t seed, std::uint64_t stream) {
  return splitmix64(splitmix64(seed) ^ splitmix64(stream + 0x632BE59BD9B4E019ULL));
}

const NormalGenerator::Table& NormalGenerator::table() {
  static const Table kTable = make_table();
  return kTable;
}

double NormalGenerator::slow_path(std::size_t layer, double x, bool negative) {
  const Table& t = table();
  while (true) {
    if (layer == 0) {
      // Tail beyond r: Marsaglia (1964), exponential proposals accepted with the normal ratio.
      double a = 0.0;
      double b = 0.0;
      do {
        a = -std::log1p(-uniform()) / kBaseEdge;
        b = -std::log1p(-uniform());
      } while (2.0 * b < a * a);
      x = kBaseEdge + a;
      return negative ? -x : x;
    }
    // Wedge between the inner rectangle and the curve: accept with the exact density.
    const double y = t.f[layer] + uniform() * (t.f[layer + 1] - t.f[layer]);
    if (y < density(x)) return negative ? -x : x;

    const std::uint64_t word = engine_();
    layer = word & 0xFF;
    negative = (word & 0x100) != 0;
    x = static_cast<double>(word >> 11) * 0x1.0p-53 * t.x[layer];
    if (x < t.x[layer + 1]) return negative ? -x : x;
  }
}

}  // namespace stochnav
