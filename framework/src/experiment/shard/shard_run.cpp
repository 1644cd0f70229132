#include "stochnav/experiment/shard_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <thread>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/temporary_files.hpp"
#include "stochnav/experiment/comparison.hpp"
#include "stochnav/experiment/experiment_hash.hpp"
#include "stochnav/experiment/shard_files.hpp"

namespace stochnav {
namespace {

namespace fs = std::filesystem;

// DIR/shards may hold only shard folders of this experiment, split into as many shards as this
// run. A shard folder without shard.json yet is another shard starting: no verdict.
void check_shards_folder(const fs::path& out_dir, const std::string& hash, ShardSpec shard) {
  const fs::path root = shards_folder(out_dir);
  std::error_code error;
  if (!fs::is_directory(root, error)) return;
  for (const auto& entry : fs::directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    const std::optional<ShardSpec> other = parse_shard_folder_name(name);
    if (!other || !entry.is_directory()) {
      throw InputError(fmt::format(
          "{}: not a shard folder of stochnav compare (expected shard-K-of-N/); remove it or "
          "choose another --out",
          entry.path().string()));
    }
    if (other->count != shard.count) {
      throw InputError(fmt::format(
          "{}: this output folder holds a split into {} shards, this run is shard {}/{}: the two "
          "splits would write the same jobs; use --shard K/{}, or remove {} to start over",
          entry.path().string(), other->count, shard.index, shard.count, other->count,
          root.string()));
    }
    if (!fs::exists(shard_record_path(entry.path()))) continue;
    const ShardRecord record = read_shard_record(entry.path());
    if (record.manifest.experiment_hash != hash) {
      throw InputError(fmt::format(
          "{}: from another experiment (config hash {}, this one {}: the experiment, its "
          "scenario or --seeds changed); choose another --out, or remove {} to start over",
          entry.path().string(), record.manifest.experiment_hash, hash, root.string()));
    }
  }
}

ShardManifest manifest_of(const ExperimentConfig& config, const std::string& hash,
                          const std::string& experiment_arguments) {
  ShardManifest manifest;
  manifest.experiment_hash = hash;
  manifest.experiment_file = fs::absolute(config.file).string();
  manifest.experiment_arguments = experiment_arguments;
  manifest.description = config.description;
  manifest.baseline = config.baseline;
  manifest.pairs = config.pairs;
  manifest.seeds = config.seeds;
  manifest.levels = config.sweep ? config.sweep->values.size() : 1;
  manifest.sweep = config.sweep;
  return manifest;
}

// The job ids whose files this shard already holds, whole and of this experiment.
std::vector<std::size_t> complete_jobs(const fs::path& shard_dir, const std::string& hash,
                                       const std::vector<ComparisonJob>& mine) {
  std::vector<std::size_t> done;
  for (const auto& job : mine) {
    const fs::path file = shard_dir / job_file_name(job.id);
    if (!fs::exists(file)) continue;
    try {
      const JobRecord record = read_job_record(file);
      if (record.experiment_hash == hash && record.job.id == job.id) done.push_back(job.id);
    } catch (const InputError&) {
      // damaged (e.g. written by another version): run the job again
    }
  }
  return done;
}

// Keeps DIR/.scenarios (or DIR/level_<i>/.scenarios) in place while this shard simulates its
// seeds there: run_comparison removes the folder when it is empty, and another shard's seeds go
// into it at the same time. The hold is a file named after the shard, made before the first
// seed and removed after the last (and by the signal cleanup).
class ScenarioFolderHold final {
 public:
  ScenarioFolderHold(const fs::path& comparison_dir, ShardSpec shard)
      : folder_(comparison_dir / ".scenarios"),
        file_(folder_ / (shard_folder_name(shard) + ".running")),
        registration_(file_) {
    // Another shard may remove the empty folder between our mkdir and our write: try again.
    for (int attempt = 0; attempt < 20; ++attempt) {
      std::error_code error;
      create_directories_before_cleanup(folder_, error);
      if (!error) create_file_before_cleanup(file_, error);
      if (!error) return;
    }
    throw InputError(folder_.string() + ": cannot write there; check that --out is writable");
  }
  ~ScenarioFolderHold() {
    std::error_code ignored;
    fs::remove(file_, ignored);
    fs::remove(folder_, ignored);  // only when empty
  }
  ScenarioFolderHold(const ScenarioFolderHold&) = delete;
  ScenarioFolderHold& operator=(const ScenarioFolderHold&) = delete;

 private:
  fs::path folder_;
  fs::path file_;
  TemporaryPath registration_;
};

void remove_job_files(const fs::path& shard_dir) {
  for (const auto& entry : fs::directory_iterator(shard_dir)) {
    if (parse_job_file_name(entry.path().filename().string())) fs::remove(entry.path());
  }
}

// The jobs of `mine` not in `done`, by level, in job order.
std::map<std::size_t, std::vector<ComparisonJob>> pending_jobs_by_level(
    const std::vector<ComparisonJob>& mine, const std::vector<std::size_t>& done) {
  std::map<std::size_t, std::vector<ComparisonJob>> pending;
  for (const auto& job : mine) {
    if (std::find(done.begin(), done.end(), job.id) == done.end()) {
      pending[job.level].push_back(job);
    }
  }
  return pending;
}

// One job file per seed of a batch: run_comparison's result on the batch's seeds, in order.
void write_batch_records(const fs::path& shard_dir, const std::string& hash,
                         const std::vector<ComparisonJob>& batch, const ComparisonResult& result) {
  for (std::size_t b = 0; b < batch.size(); ++b) {
    JobRecord record;
    record.experiment_hash = hash;
    record.job = batch[b];
    record.wall_seconds = result.wall_seconds / static_cast<double>(batch.size());
    for (const auto& variant : result.variants) {
      record.variants.push_back({variant.name, variant.noise_model, variant.runs[b]});
    }
    // compare plots the errors over time of the first seed only.
    write_job_record(shard_dir, record, batch[b].seed_index == 0);
  }
}

}  // namespace

ShardRunSummary run_shard(const ExperimentConfig& config, const fs::path& out_dir_given,
                          const ShardRunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path out_dir = fs::absolute(out_dir_given);
  const std::string hash = experiment_hash(config);
  check_shards_folder(out_dir, hash, options.shard);

  const std::size_t level_count = config.sweep ? config.sweep->values.size() : 1;
  const std::vector<ComparisonJob> mine =
      jobs_of_shard(comparison_jobs(level_count, config.seeds), options.shard);

  ShardRunSummary summary;
  summary.folder = shard_folder(out_dir, options.shard);
  summary.jobs = mine.size();
  std::error_code error;
  create_directories_before_cleanup(summary.folder, error);
  if (error) {
    throw InputError(summary.folder.string() + ": cannot create the shard folder (" +
                     error.message() + "); choose another --out");
  }
  if (!options.resume) remove_job_files(summary.folder);
  const std::vector<std::size_t> done =
      options.resume ? complete_jobs(summary.folder, hash, mine) : std::vector<std::size_t>{};
  summary.skipped = done.size();

  ShardRecord record;
  record.shard = options.shard;
  record.status = "running";
  for (const auto& job : mine) record.jobs.push_back(job.id);
  record.manifest = manifest_of(config, hash, options.experiment_arguments);
  write_shard_record(summary.folder, record);

  const auto pending = pending_jobs_by_level(mine, done);
  const std::size_t batch_size =
      config.threads > 0 ? config.threads : std::max(1u, std::thread::hardware_concurrency());
  try {
    // Every level this shard runs is built and its variants checked before the first job.
    std::map<std::size_t, ExperimentConfig> levels;
    for (const auto& [level, jobs] : pending) {
      levels.emplace(level, config.sweep ? sweep_level(config, level) : config);
      validate_variants(levels.at(level));
    }
    for (const auto& [level, jobs] : pending) {
      // Where the unsharded run simulates this level's seeds, so that paths in the results
      // (the oracle's scenario folder) are the same.
      const fs::path comparison_dir =
          config.sweep ? out_dir / fmt::format("level_{}", level) : out_dir;
      std::optional<ScenarioFolderHold> hold;
      if (config.scenario_config) hold.emplace(comparison_dir, options.shard);
      for (std::size_t first = 0; first < jobs.size(); first += batch_size) {
        const std::vector<ComparisonJob> batch(
            jobs.begin() + static_cast<std::ptrdiff_t>(first),
            jobs.begin() + static_cast<std::ptrdiff_t>(std::min(jobs.size(), first + batch_size)));
        ExperimentConfig part = levels.at(level);
        part.seeds.clear();
        for (const auto& job : batch) part.seeds.push_back(job.seed);
        const ComparisonResult result = run_comparison(part, comparison_dir, options.progress);
        write_batch_records(summary.folder, hash, batch, result);
      }
    }
  } catch (const std::exception& failure) {
    record.status = "failed";
    record.error = failure.what();
    write_shard_record(summary.folder, record);
    throw;
  }
  record.status = "complete";
  write_shard_record(summary.folder, record);
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace stochnav
