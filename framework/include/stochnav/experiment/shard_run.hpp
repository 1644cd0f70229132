#pragma once
// `stochnav compare EXPERIMENT --out DIR --shard K/N`: only the jobs of shard K of N
// (experiment/shard_plan.hpp), each written to DIR/shards/shard-K-of-N/ as soon as its batch
// ends (experiment/shard_files.hpp). A shard runs its jobs level by level in batches of as many
// seeds as it has worker threads (ExperimentConfig::threads, else all cores), each batch a normal
// run_comparison of the level on those seeds, so each seed's numbers are those of the unsharded
// run. Seeds are simulated where the unsharded run simulates them (DIR/.scenarios/, a sweep
// level's DIR/level_<i>/.scenarios/; removed after) so that the results name the same paths.
// A node lost mid-run loses at most the batch in flight: `resume` keeps the job files
// already written and runs only the rest.

#include <filesystem>
#include <string>

#include "stochnav/experiment/experiment_config.hpp"
#include "stochnav/experiment/shard_plan.hpp"

namespace stochnav {

struct ShardRunOptions {
  ShardSpec shard;
  /// Keep this shard's job files from an earlier run (same experiment) and run only the rest;
  /// without it the shard's earlier job files are removed first.
  bool resume = false;
  bool progress = false;
  /// Shell words after `stochnav compare` that rebuild the experiment ('FILE' [--seeds ...]
  /// [--full-scenario]): merge's rerun command for missing shards.
  std::string experiment_arguments;
};

struct ShardRunSummary {
  std::filesystem::path folder;  ///< DIR/shards/shard-K-of-N
  std::size_t jobs = 0;          ///< jobs of the shard
  std::size_t skipped = 0;       ///< already complete (resume)
  double wall_seconds = 0.0;
};

/// Runs the shard. Before anything runs, DIR/shards must hold nothing but shard folders of
/// this experiment (same experiment_hash) split into the same N; else InputError naming the
/// folder at fault and how to fix it. A failing job marks the shard "failed" in its shard.json
/// (with the error) and the error is rethrown.
ShardRunSummary run_shard(const ExperimentConfig& config, const std::filesystem::path& out_dir,
                          const ShardRunOptions& options);

}  // namespace stochnav
