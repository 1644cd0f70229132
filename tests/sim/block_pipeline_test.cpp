#include "stochnav/sim/block_pipeline.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "stochnav/sim/normal_generator.hpp"

namespace stochnav {
namespace {

// Three streams of normals; the blocks seen by the consumer must not depend on the threads.
std::vector<std::vector<double>> consume(unsigned threads, std::size_t blocks) {
  std::vector<NormalGenerator> sources{NormalGenerator(1), NormalGenerator(2),
                                       NormalGenerator(3)};
  std::vector<BlockPipeline::Stream> streams;
  for (auto& source : sources) {
    streams.push_back([&source](std::span<double> out) {
      for (double& x : out) x = source();
    });
  }
  BlockPipeline pipeline(std::move(streams), 100, threads);
  std::vector<std::vector<double>> seen(3);
  for (std::size_t b = 0; b < blocks; ++b) {
    pipeline.advance();
    for (std::size_t s = 0; s < 3; ++s) {
      const auto block = pipeline.current(s);
      EXPECT_EQ(block.size(), 100u);
      seen[s].insert(seen[s].end(), block.begin(), block.end());
    }
  }
  return seen;
}

TEST(BlockPipeline, SameSamplesWhateverTheThreadCount) {
  const auto synchronous = consume(0, 25);
  NormalGenerator reference(2);
  for (double x : synchronous[1]) ASSERT_EQ(x, reference());  // stream order kept
  for (unsigned threads : {1u, 2u, 3u, 8u}) {
    EXPECT_EQ(consume(threads, 25), synchronous) << threads << " threads";
  }
}

TEST(BlockPipeline, StopsCleanlyWithBlocksUnconsumed) {
  for (unsigned threads : {0u, 2u}) {
    const auto seen = consume(threads, 1);  // producers are a block ahead when destroyed
    EXPECT_EQ(seen[0].size(), 100u);
  }
}

}  // namespace
}  // namespace stochnav
