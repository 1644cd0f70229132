#pragma once
// A fixed, documented source of standard normal numbers, so a seed gives the same record
// wherever stochnav runs (std::normal_distribution is implementation-defined, so it is not used).
//
// Engine: xoshiro256** (sim/random_engine.hpp, fully specified), seeded with one 64-bit value.
// Transform: the Marsaglia-Tsang ziggurat with 256 layers. Each draw takes one 64-bit word:
// bits 0-7 pick the layer, bit 8 the sign, bits 11-63 a 53-bit uniform; rare draws outside
// the layer's inner rectangle fall back to the exact wedge test (extra words) or, in the base
// layer, to Marsaglia's exponential tail method. The layer table is computed once from the
// layer area v and base edge r below with std::exp/std::log, so records are bit-identical on
// any platform whose libm rounds those the same way (glibc everywhere we run).

#include <array>
#include <bit>
#include <cstdint>

#include "stochnav/sim/random_engine.hpp"

namespace stochnav {

/// A 64-bit seed for sub-stream `stream` of `seed` (SplitMix64 finalizer over both), so each
/// noise term, and each component within a term, draws from its own independent engine.
std::uint64_t derive_stream_seed(std::uint64_t seed, std::uint64_t stream);

class NormalGenerator final {
 public:
  explicit NormalGenerator(std::uint64_t seed) : engine_(seed), table_(&table()) {}

  /// One standard normal deviate (mean 0, variance 1).
  double operator()() {
    const std::uint64_t word = engine_();
    const std::size_t layer = word & 0xFF;
    const double uniform = static_cast<double>(word >> 11) * 0x1.0p-53;  // [0, 1)
    const double x = uniform * table_->x[layer];
    // Sign by flipping the sign bit (bit 8 moved to bit 63): a branch on a random bit would be
    // mispredicted half the time and cost more than the rest of the draw.
    if (x < table_->x[layer + 1]) [[likely]] {
      return std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) ^ ((word & 0x100) << 55));
    }
    return slow_path(layer, x, (word & 0x100) != 0);
  }

  /// A uniform deviate in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  /// The underlying engine, for tests.
  Xoshiro256StarStar& engine() { return engine_; }

  /// Ziggurat layer table: x[0] = v / f(r) (the base layer's equal-area width), x[1] = r,
  /// f(x[i+1]) = f(x[i]) + v / x[i], x[256] = 0, with f(x) = exp(-x^2 / 2).
  struct Table {
    std::array<double, 257> x;
    std::array<double, 257> f;  ///< f(x[i])
  };
  static const Table& table();

 private:
  double slow_path(std::size_t layer, double x, bool negative);

  Xoshiro256StarStar engine_;
  const Table* table_;
};

}  // namespace stochnav
