#pragma once
// How `stochnav compare --shard K/N` splits an experiment: the jobs, which shard runs which, and
// the shard index and count read from a batch engine's environment (`--shard auto`).
//
// A job is the scenario simulation of one seed at one sweep level plus every variant on it.
// Jobs are numbered level-major: job = level * seeds + seed_index (a plain experiment has one
// level). Shard K of N runs the jobs with job % N == K: deterministic, the counts of any two
// shards differ by at most one, and every shard gets seeds of every level (levels may differ in
// cost, seeds of one level hardly do).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace stochnav {

/// Shard `index` of `count` (0 <= index < count).
struct ShardSpec {
  std::size_t index = 0;
  std::size_t count = 1;
};

struct ComparisonJob {
  std::size_t id = 0;          ///< level * seeds + seed_index
  std::size_t level = 0;       ///< sweep level (0 without a sweep)
  std::size_t seed_index = 0;  ///< index into the experiment's seeds
  std::uint64_t seed = 0;
};

/// "K/N" as given to --shard. Throws ConfigError ("--shard TEXT: problem; fix") when TEXT is
/// not two whole numbers, N is 0 or K >= N.
ShardSpec parse_shard_spec(std::string_view text);

/// The value of an environment variable, nullopt when unset.
using EnvironmentLookup = std::function<std::optional<std::string>(const std::string& name)>;
EnvironmentLookup process_environment();

/// --shard auto. Slurm job array (SLURM_ARRAY_TASK_ID set): with `shards_option` (--shards N),
/// K = SLURM_ARRAY_TASK_ID and the array must be numbered 0..N-1 (a rerun of some tasks, e.g.
/// --array=1,3, keeps N); without it, K = TASK_ID - TASK_MIN and N = SLURM_ARRAY_TASK_COUNT (or
/// TASK_MAX - TASK_MIN + 1), and the array must have no gaps. Kubernetes Indexed Job
/// (JOB_COMPLETION_INDEX set): K = that index, N = --shards (required). Throws ConfigError
/// naming the variable or option at fault.
ShardSpec shard_spec_from_environment(const EnvironmentLookup& environment,
                                      std::optional<std::size_t> shards_option);

/// Every job of an experiment with `levels` sweep levels (1 without a sweep) and these seeds.
std::vector<ComparisonJob> comparison_jobs(std::size_t levels,
                                           const std::vector<std::uint64_t>& seeds);

/// The shard that runs job `job_id` of a split into `shard_count` shards.
std::size_t shard_of_job(std::size_t job_id, std::size_t shard_count);

/// The jobs of `shard`, in job order.
std::vector<ComparisonJob> jobs_of_shard(const std::vector<ComparisonJob>& jobs, ShardSpec shard);

/// "shard-K-of-N", the shard's folder under DIR/shards/; and back (nullopt for another name).
std::string shard_folder_name(ShardSpec shard);
std::optional<ShardSpec> parse_shard_folder_name(std::string_view name);

}  // namespace stochnav
