#pragma once
// The files of a sharded `stochnav compare` (experiment/shard_run.hpp writes them,
// experiment/shard_merge.hpp reads them), all under DIR/shards/:
//
//   shard-K-of-N/shard.json   {"format": kShardFormat, "shard": K, "shards": N,
//                              "status": "running" | "complete" | "failed", "error": message
//                              of a failed shard, "jobs": [job ids of the shard],
//                              "experiment": ShardManifest (below)}
//   shard-K-of-N/job_<id>.json   one per finished job: {"format", "experiment_hash", "job",
//                              "level", "seed_index", "seed", "wall_seconds" (the job's share
//                              of its batch's wall time), "variants": [{"name", "noise_model",
//                              "run": experiment/run_result_json.hpp}]} (the first seed's runs
//                              keep their error series, for the plots)
//
// Every file is written atomically (io/atomic_file.hpp): a job file is whole or absent.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "stochnav/experiment/comparison.hpp"
#include "stochnav/experiment/shard_plan.hpp"

namespace stochnav {

inline constexpr const char* kShardFormat = "stochnav compare shard 1";

/// What `compare merge` needs of the experiment, so that it reads no file but the shards'.
struct ShardManifest {
  std::string experiment_hash;       ///< experiment/experiment_hash.hpp
  std::string experiment_file;       ///< absolute path (table.md names its file name)
  std::string experiment_arguments;  ///< shell words after `stochnav compare` that rebuild the
                                     ///< experiment: 'FILE' [--seeds ...] [--full-scenario]
  std::string description;
  std::string baseline;
  std::vector<std::pair<std::string, std::string>> pairs;
  std::vector<std::uint64_t> seeds;
  std::size_t levels = 1;  ///< sweep levels, 1 without a sweep
  std::optional<ExperimentSweep> sweep;
};

struct ShardRecord {
  ShardSpec shard;
  std::string status;  ///< "running", "complete" or "failed"
  std::string error;   ///< why a failed shard failed
  std::vector<std::size_t> jobs;
  ShardManifest manifest;
};

struct VariantRun {
  std::string name;
  std::string noise_model;
  NavigationRunResult run;
};

struct JobRecord {
  std::string experiment_hash;
  ComparisonJob job;
  double wall_seconds = 0.0;
  std::vector<VariantRun> variants;  ///< in the experiment's variant order
};

std::filesystem::path shards_folder(const std::filesystem::path& out_dir);
std::filesystem::path shard_folder(const std::filesystem::path& out_dir, ShardSpec shard);
std::filesystem::path shard_record_path(const std::filesystem::path& shard_dir);

/// "job_<id>.json", and back (nullopt for another name, e.g. a temporary file).
std::string job_file_name(std::size_t job_id);
std::optional<std::size_t> parse_job_file_name(const std::string& name);

void write_shard_record(const std::filesystem::path& shard_dir, const ShardRecord& record);
/// Throws InputError naming the file when it cannot be read or is not a shard record.
ShardRecord read_shard_record(const std::filesystem::path& shard_dir);

/// `with_error_series`: keep the runs' error series (the experiment's first seed).
void write_job_record(const std::filesystem::path& shard_dir, const JobRecord& record,
                      bool with_error_series);
/// Throws InputError naming the file when it cannot be read or is not a job record.
JobRecord read_job_record(const std::filesystem::path& file);

/// `text` quoted for a POSIX shell when it needs to be.
std::string shell_quoted(const std::string& text);

}  // namespace stochnav
