// How `compare --shard` splits an experiment: K/N parsed and checked, --shard auto read from a
// Slurm array's or a Kubernetes Indexed Job's environment, every job in exactly one shard with
// balanced counts, shard folder names read back.

#include "stochnav/experiment/shard_plan.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

EnvironmentLookup fake_environment(std::map<std::string, std::string> variables) {
  return [variables](const std::string& name) -> std::optional<std::string> {
    const auto it = variables.find(name);
    if (it == variables.end()) return std::nullopt;
    return it->second;
  };
}

// The message of the ConfigError `action` throws ("" when it throws none).
template <typename Action>
std::string config_error_of(Action action) {
  try {
    action();
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "";
}

TEST(ShardSpec, ParsesIndexOfCount) {
  const ShardSpec shard = parse_shard_spec("2/5");
  EXPECT_EQ(shard.index, 2u);
  EXPECT_EQ(shard.count, 5u);
  EXPECT_EQ(parse_shard_spec("0/1").count, 1u);
}

TEST(ShardSpec, RefusesIndexNotBelowCountZeroCountAndOtherForms) {
  EXPECT_NE(config_error_of([] { parse_shard_spec("4/4"); }).find("use 0/4 to 3/4"),
            std::string::npos);
  EXPECT_NE(config_error_of([] { parse_shard_spec("0/0"); }).find("count N is 0"),
            std::string::npos);
  for (const char* bad : {"", "3", "1/", "/4", "-1/4", "1/-4", "a/b", "1/4/2", " 1/4", "1.0/4"}) {
    SCOPED_TRACE(bad);
    EXPECT_NE(config_error_of([bad] { parse_shard_spec(bad); }).find("expected K/N"),
              std::string::npos);
  }
}

TEST(ShardSpecFromEnvironment, SlurmArrayIndexAndCount) {
  const ShardSpec shard =
      shard_spec_from_environment(fake_environment({{"SLURM_ARRAY_TASK_ID", "3"},
                                                    {"SLURM_ARRAY_TASK_COUNT", "4"},
                                                    {"SLURM_ARRAY_TASK_MIN", "0"},
                                                    {"SLURM_ARRAY_TASK_MAX", "3"}}),
                                  std::nullopt);
  EXPECT_EQ(shard.index, 3u);
  EXPECT_EQ(shard.count, 4u);
}

TEST(ShardSpecFromEnvironment, SlurmArrayFromMinAndMaxStartingAtOne) {
  const ShardSpec shard =
      shard_spec_from_environment(fake_environment({{"SLURM_ARRAY_TASK_ID", "1"},
                                                    {"SLURM_ARRAY_TASK_MIN", "1"},
                                                    {"SLURM_ARRAY_TASK_MAX", "8"}}),
                                  std::nullopt);
  EXPECT_EQ(shard.index, 0u);
  EXPECT_EQ(shard.count, 8u);
}

TEST(ShardSpecFromEnvironment, SlurmRerunOfSomeTasksKeepsCountFromShardsOption) {
  // sbatch --array=1,3 (a rerun of two lost shards of four): COUNT is 2, but --shards says 4.
  const ShardSpec shard =
      shard_spec_from_environment(fake_environment({{"SLURM_ARRAY_TASK_ID", "3"},
                                                    {"SLURM_ARRAY_TASK_COUNT", "2"},
                                                    {"SLURM_ARRAY_TASK_MIN", "1"},
                                                    {"SLURM_ARRAY_TASK_MAX", "3"}}),
                                  4);
  EXPECT_EQ(shard.index, 3u);
  EXPECT_EQ(shard.count, 4u);
}

TEST(ShardSpecFromEnvironment, SlurmArrayWithGapsNeedsShardsOption) {
  const std::string message = config_error_of([] {
    shard_spec_from_environment(fake_environment({{"SLURM_ARRAY_TASK_ID", "3"},
                                                  {"SLURM_ARRAY_TASK_COUNT", "2"},
                                                  {"SLURM_ARRAY_TASK_MIN", "1"},
                                                  {"SLURM_ARRAY_TASK_MAX", "3"}}),
                                std::nullopt);
  });
  EXPECT_NE(message.find("gaps"), std::string::npos) << message;
  EXPECT_NE(message.find("--shards N"), std::string::npos) << message;
}

TEST(ShardSpecFromEnvironment, SlurmTaskOutsideShardsOptionIsRefused) {
  const std::string message = config_error_of([] {
    shard_spec_from_environment(fake_environment({{"SLURM_ARRAY_TASK_ID", "4"}}), 4);
  });
  EXPECT_NE(message.find("--array=0-3"), std::string::npos) << message;
}

TEST(ShardSpecFromEnvironment, KubernetesIndexNeedsShardsOption) {
  const ShardSpec shard =
      shard_spec_from_environment(fake_environment({{"JOB_COMPLETION_INDEX", "2"}}), 5);
  EXPECT_EQ(shard.index, 2u);
  EXPECT_EQ(shard.count, 5u);
  const std::string message = config_error_of([] {
    shard_spec_from_environment(fake_environment({{"JOB_COMPLETION_INDEX", "2"}}), std::nullopt);
  });
  EXPECT_NE(message.find("--shards N"), std::string::npos) << message;
  EXPECT_NE(config_error_of([] {
              shard_spec_from_environment(fake_environment({{"JOB_COMPLETION_INDEX", "2"}}), 0);
            }).find("count N is 0"),
            std::string::npos);
}

TEST(ShardSpecFromEnvironment, NoEngineOrGarbageIsRefused) {
  EXPECT_NE(config_error_of([] {
              shard_spec_from_environment(fake_environment({}), 4);
            }).find("neither SLURM_ARRAY_TASK_ID"),
            std::string::npos);
  EXPECT_NE(config_error_of([] {
              shard_spec_from_environment(fake_environment({{"SLURM_ARRAY_TASK_ID", "x"}}), 4);
            }).find("SLURM_ARRAY_TASK_ID=x is not a whole number"),
            std::string::npos);
}

TEST(ShardAssignment, EveryJobInExactlyOneShardWithBalancedCounts) {
  const std::vector<std::uint64_t> seeds = {11, 12, 13, 14, 15, 16, 17};
  const std::vector<ComparisonJob> jobs = comparison_jobs(3, seeds);
  ASSERT_EQ(jobs.size(), 21u);
  for (std::size_t count : {1u, 2u, 4u, 5u, 21u, 30u}) {
    SCOPED_TRACE(count);
    std::multiset<std::size_t> seen;
    std::size_t fewest = jobs.size(), most = 0;
    std::set<std::size_t> levels_of_first_shard;
    for (std::size_t k = 0; k < count; ++k) {
      const auto mine = jobs_of_shard(jobs, {k, count});
      fewest = std::min(fewest, mine.size());
      most = std::max(most, mine.size());
      for (const auto& job : mine) {
        seen.insert(job.id);
        EXPECT_EQ(shard_of_job(job.id, count), k);
        if (k == 0) levels_of_first_shard.insert(job.level);
      }
      EXPECT_EQ(mine.size(), jobs_of_shard(jobs, {k, count}).size());  // deterministic
    }
    EXPECT_EQ(seen.size(), jobs.size());
    for (const auto& job : jobs) EXPECT_EQ(seen.count(job.id), 1u);
    EXPECT_LE(most - fewest, 1u);
    // With fewer shards than seeds per level, each shard gets seeds of every level.
    if (count < seeds.size()) {
      EXPECT_EQ(levels_of_first_shard.size(), 3u);
    }
  }
}

TEST(ShardAssignment, JobsAreLevelMajorWithTheirSeeds) {
  const auto jobs = comparison_jobs(2, {5, 9});
  ASSERT_EQ(jobs.size(), 4u);
  EXPECT_EQ(jobs[3].id, 3u);
  EXPECT_EQ(jobs[3].level, 1u);
  EXPECT_EQ(jobs[3].seed_index, 1u);
  EXPECT_EQ(jobs[3].seed, 9u);
  EXPECT_EQ(jobs[2].seed, 5u);
}

TEST(ShardFolderName, RoundTripsAndRejectsOthers) {
  EXPECT_EQ(shard_folder_name({3, 8}), "shard-3-of-8");
  const auto back = parse_shard_folder_name("shard-3-of-8");
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->index, 3u);
  EXPECT_EQ(back->count, 8u);
  for (const char* other : {"shard-8-of-8", "shard-0-of-0", "shard-1-of-", "shards", "junk",
                            "shard-1-of-2x", ".shard-1-of-2"}) {
    EXPECT_FALSE(parse_shard_folder_name(other).has_value()) << other;
  }
}

}  // namespace
}  // namespace stochnav
