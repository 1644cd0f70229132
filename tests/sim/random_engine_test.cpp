#include "stochnav/sim/random_engine.hpp"

#include <gtest/gtest.h>

#include <array>

namespace stochnav {
namespace {

TEST(Xoshiro256StarStar, ReferenceOutputsFromAnExplicitState) {
  // The reference C implementation (xoshiro256starstar.c) started at s = {1, 2, 3, 4}.
  auto engine = Xoshiro256StarStar::from_state(1, 2, 3, 4);
  EXPECT_EQ(engine(), 11520u);
  EXPECT_EQ(engine(), 0u);
  EXPECT_EQ(engine(), 1509978240u);
  EXPECT_EQ(engine(), 1215971899390074240u);
}

TEST(Xoshiro256StarStar, SeededBySplitMix64) {
  // SplitMix64 from 0 gives 0xe220a8397b1dcdaf, 0x6e789e6aa1b965f4, 0x06c45d188009454f, ...;
  // those are the state words, and the first output is rotl(s1 * 5, 7) * 9.
  Xoshiro256StarStar seeded(0);
  auto explicit_state = Xoshiro256StarStar::from_state(
      0xe220a8397b1dcdafULL, 0x6e789e6aa1b965f4ULL, 0x06c45d188009454fULL,
      0xf88bb8a8724c81ecULL);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(seeded(), explicit_state()) << i;
}

TEST(Xoshiro256StarStar, BitsAreBalanced) {
  Xoshiro256StarStar engine(99);
  std::array<int, 64> ones{};
  constexpr int kWords = 200000;
  for (int i = 0; i < kWords; ++i) {
    const std::uint64_t word = engine();
    for (int b = 0; b < 64; ++b) ones[b] += static_cast<int>((word >> b) & 1u);
  }
  // Each bit is 1 with probability 1/2: 5 sigma of a binomial(200000, 1/2) is about 1118.
  for (int b = 0; b < 64; ++b) EXPECT_NEAR(ones[b], kWords / 2, 1118) << "bit " << b;
}

}  // namespace
}  // namespace stochnav
