#include "stochnav/experiment/shard_merge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>

#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/comparison.hpp"
#include "stochnav/experiment/shard_files.hpp"

namespace stochnav {
namespace {

namespace fs = std::filesystem;

// One folder of DIR/shards/ as found.
struct FoundShard {
  ShardSpec shard;
  fs::path folder;
  std::optional<ShardRecord> record;          ///< absent: the shard died before writing it
  std::map<std::size_t, fs::path> job_files;  ///< job id -> file
};

std::vector<FoundShard> find_shards(const fs::path& out_dir) {
  const fs::path root = shards_folder(out_dir);
  std::error_code error;
  std::vector<fs::path> entries;
  if (fs::is_directory(root, error)) {
    for (const auto& entry : fs::directory_iterator(root)) entries.push_back(entry.path());
  }
  if (entries.empty()) {
    throw InputError(fmt::format(
        "{}: no shards (expected {}/shard-K-of-N/); run `stochnav compare EXPERIMENT --out {} "
        "--shard K/N` for every K first",
        out_dir.string(), root.string(), shell_quoted(out_dir.string())));
  }
  std::sort(entries.begin(), entries.end());
  std::vector<FoundShard> found;
  for (const auto& path : entries) {
    const std::optional<ShardSpec> shard = parse_shard_folder_name(path.filename().string());
    if (!shard || !fs::is_directory(path)) {
      throw InputError(fmt::format(
          "{}: not a shard folder of stochnav compare (expected shard-K-of-N/); remove it and "
          "merge again",
          path.string()));
    }
    FoundShard one{*shard, path, std::nullopt, {}};
    if (fs::exists(shard_record_path(path))) {
      one.record = read_shard_record(path);
      if (one.record->shard.index != shard->index || one.record->shard.count != shard->count) {
        throw InputError(fmt::format(
            "{}: its shard.json says shard {}/{}; the folder was renamed or copied: remove it "
            "and rerun that shard",
            path.string(), one.record->shard.index, one.record->shard.count));
      }
    }
    for (const auto& entry : fs::directory_iterator(path)) {
      if (auto id = parse_job_file_name(entry.path().filename().string())) {
        one.job_files[*id] = entry.path();
      }
    }
    found.push_back(std::move(one));
  }
  return found;
}

// The manifest all shards agree on; throws when shards of two experiments or two splits meet,
// or one job was written twice.
const ShardManifest& agreed_manifest(const std::vector<FoundShard>& found, std::size_t& count) {
  const FoundShard* reference = nullptr;
  for (const auto& shard : found) {
    if (!shard.record) continue;
    if (reference == nullptr) {
      reference = &shard;
      continue;
    }
    if (shard.record->manifest.experiment_hash != reference->record->manifest.experiment_hash) {
      throw InputError(fmt::format(
          "{} and {} come from different experiments (config hash {} vs {}); remove the "
          "folders of the experiment you do not want and merge again",
          reference->folder.string(), shard.folder.string(),
          reference->record->manifest.experiment_hash, shard.record->manifest.experiment_hash));
    }
  }
  if (reference == nullptr) {
    throw InputError(fmt::format(
        "{}: no shard has written its shard.json yet; wait for the shards to start, or rerun "
        "them",
        shards_folder(found.front().folder.parent_path().parent_path()).string()));
  }
  std::map<std::size_t, const FoundShard*> writer;
  for (const auto& shard : found) {
    for (const auto& [id, file] : shard.job_files) {
      const auto [it, fresh] = writer.emplace(id, &shard);
      if (!fresh) {
        throw InputError(fmt::format(
            "job {} was written by two shards, {} and {} (two splits of one experiment, or a "
            "copied folder); remove the folders of the split you do not want and merge again",
            id, it->second->folder.string(), shard.folder.string()));
      }
    }
  }
  count = reference->shard.count;
  for (const auto& shard : found) {
    if (shard.shard.count != count) {
      throw InputError(fmt::format(
          "{} splits the experiment into {} shards, {} into {}: their jobs overlap; remove the "
          "folders of the split you do not want and merge again",
          reference->folder.string(), count, shard.folder.string(), shard.shard.count));
    }
  }
  return reference->record->manifest;
}

// Why shard `index` is not complete, or "" when it is.
std::string incompleteness(const FoundShard* shard, const std::vector<ComparisonJob>& mine) {
  if (shard == nullptr) return "not started";
  std::size_t present = 0;
  for (const auto& job : mine) present += shard->job_files.count(job.id);
  if (present == mine.size()) return "";
  const std::string progress = fmt::format("{} of {} jobs done", present, mine.size());
  if (!shard->record) return "started, no shard.json";
  if (shard->record->status == "failed") {
    return fmt::format("failed, {}: {}", progress, shard->record->error);
  }
  if (shard->record->status == "running") return progress + ", still running or killed";
  return progress + ", job files missing";
}

// Every job file in the shard that owns it (job % N), or an InputError naming the file.
void check_job_owners(const std::vector<FoundShard>& found, std::size_t job_count,
                      std::size_t count) {
  for (const auto& shard : found) {
    for (const auto& [id, file] : shard.job_files) {
      if (id >= job_count || shard_of_job(id, count) != shard.shard.index) {
        throw InputError(fmt::format(
            "{}: job {} does not belong to shard {}/{} (it has {} jobs, each in shard job % {}); "
            "remove the file and merge again",
            file.string(), id, shard.shard.index, count, job_count, count));
      }
    }
  }
}

// Throws, naming every shard not complete and the command that reruns them.
void check_every_shard_complete(const std::vector<FoundShard>& found,
                                const std::vector<ComparisonJob>& jobs, std::size_t count,
                                const ShardManifest& manifest, const fs::path& out_dir) {
  std::map<std::size_t, const FoundShard*> by_index;
  for (const auto& shard : found) by_index[shard.shard.index] = &shard;
  std::vector<std::string> reasons;
  std::vector<std::string> rerun;
  for (std::size_t k = 0; k < count; ++k) {
    const auto it = by_index.find(k);
    const std::string why = incompleteness(it == by_index.end() ? nullptr : it->second,
                                           jobs_of_shard(jobs, {k, count}));
    if (why.empty()) continue;
    reasons.push_back(fmt::format("shard {} ({})", k, why));
    rerun.push_back(std::to_string(k));
  }
  if (reasons.empty()) return;
  throw InputError(fmt::format(
      "{}: {} of {} shards incomplete: {}; rerun them with `stochnav compare {} --out {} "
      "--shard K/{} --resume` for K in {} (Slurm: sbatch --array={} with --shards {}), then "
      "merge again; nothing was written",
      out_dir.string(), reasons.size(), count, fmt::join(reasons, "; "),
      manifest.experiment_arguments, shell_quoted(out_dir.string()), count, fmt::join(rerun, " "),
      fmt::join(rerun, ","), count));
}

// The results of every level, each seed's runs from its job file.
std::vector<ComparisonResult> merged_levels(const std::vector<FoundShard>& found,
                                            const std::vector<ComparisonJob>& jobs,
                                            const ShardManifest& manifest) {
  std::vector<ComparisonResult> levels(manifest.levels);
  for (auto& level : levels) {
    level.baseline = manifest.baseline;
    level.seeds = manifest.seeds;
    level.pairs = manifest.pairs;
  }
  for (const auto& shard : found) {
    for (const auto& [id, file] : shard.job_files) {
      JobRecord record = read_job_record(file);
      const ComparisonJob& expected = jobs[id];
      if (record.experiment_hash != manifest.experiment_hash || record.job.id != id ||
          record.job.level != expected.level || record.job.seed != expected.seed) {
        throw InputError(fmt::format(
            "{}: not job {} of this experiment (config hash {}, level {}, seed {}); delete it "
            "and rerun its shard with --resume",
            file.string(), id, manifest.experiment_hash, expected.level, expected.seed));
      }
      ComparisonResult& level = levels[expected.level];
      if (level.variants.empty()) {
        for (const auto& variant : record.variants) {
          level.variants.push_back({variant.name, variant.noise_model, {}});
          level.variants.back().runs.resize(manifest.seeds.size());
        }
      }
      if (record.variants.size() != level.variants.size()) {
        throw InputError(file.string() +
                         ": another set of variants than the other jobs; delete it and rerun "
                         "its shard with --resume");
      }
      for (std::size_t v = 0; v < record.variants.size(); ++v) {
        if (record.variants[v].name != level.variants[v].name) {
          throw InputError(file.string() + ": variant '" + record.variants[v].name +
                           "' where the other jobs have '" + level.variants[v].name +
                           "'; delete it and rerun its shard with --resume");
        }
        level.variants[v].runs[expected.seed_index] = std::move(record.variants[v].run);
      }
      level.wall_seconds += record.wall_seconds;
    }
  }
  return levels;
}

// What the writers (write_comparison, comparison_table) take of the experiment: its file name
// and description.
ExperimentConfig writers_experiment(const ShardManifest& manifest) {
  ExperimentConfig experiment;
  experiment.file = manifest.experiment_file;
  experiment.description = manifest.description;
  return experiment;
}

// The files of the unsharded run: run_comparison's for a plain experiment, run_sweep's for a
// sweep.
void write_merged(const std::vector<ComparisonResult>& levels, const ShardManifest& manifest,
                  const fs::path& out_dir) {
  const ExperimentConfig experiment = writers_experiment(manifest);
  if (!manifest.sweep) {
    write_comparison(levels.front(), experiment, out_dir);
    return;
  }
  nlohmann::json document = {{"name", manifest.sweep->name},
                             {"set", manifest.sweep->set},
                             {"values", manifest.sweep->values},
                             {"baseline", manifest.baseline},
                             {"levels", nlohmann::json::array()}};
  for (std::size_t i = 0; i < levels.size(); ++i) {
    write_comparison(levels[i], experiment, out_dir / fmt::format("level_{}", i));
    document["levels"].push_back({{"value", manifest.sweep->values[i]},
                                  {"dir", fmt::format("level_{}", i)},
                                  {"results", comparison_json(levels[i])}});
  }
  write_sweep_files(document, out_dir);
}

}  // namespace

MergeSummary merge_shards(const fs::path& out_dir) {
  const std::vector<FoundShard> found = find_shards(out_dir);
  std::size_t count = 0;
  const ShardManifest& manifest = agreed_manifest(found, count);
  const std::vector<ComparisonJob> jobs = comparison_jobs(manifest.levels, manifest.seeds);
  check_job_owners(found, jobs.size(), count);
  check_every_shard_complete(found, jobs, count, manifest, out_dir);
  const std::vector<ComparisonResult> levels = merged_levels(found, jobs, manifest);
  write_merged(levels, manifest, out_dir);
  MergeSummary summary{count, jobs.size(), manifest.sweep.has_value(), ""};
  if (!manifest.sweep)
    summary.table = comparison_table(levels.front(), writers_experiment(manifest));
  return summary;
}

}  // namespace stochnav
