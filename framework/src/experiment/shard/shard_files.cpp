#include "stochnav/experiment/shard_files.hpp"

#include <fmt/format.h>

#include <fstream>

#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/run_result_json.hpp"
#include "stochnav/io/atomic_file.hpp"

namespace stochnav {
namespace {

namespace fs = std::filesystem;

nlohmann::json read_shard_json(const fs::path& file, const std::string& what) {
  std::ifstream in(file);
  if (!in) {
    throw InputError(file.string() + ": cannot be read; rerun the shard that writes this " + what);
  }
  nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  if (json.is_discarded() || !json.is_object() || json.value("format", "") != kShardFormat) {
    throw InputError(file.string() + ": not a " + what + " of stochnav compare --shard (" +
                     kShardFormat + "); remove it, or rerun the shard that writes it");
  }
  return json;
}

nlohmann::json manifest_json(const ShardManifest& manifest) {
  nlohmann::json sweep = nullptr;
  if (manifest.sweep) {
    sweep = {{"name", manifest.sweep->name},
             {"set", manifest.sweep->set},
             {"values", manifest.sweep->values}};
  }
  return {{"experiment_hash", manifest.experiment_hash},
          {"experiment_file", manifest.experiment_file},
          {"experiment_arguments", manifest.experiment_arguments},
          {"description", manifest.description},
          {"baseline", manifest.baseline},
          {"pairs", manifest.pairs},
          {"seeds", manifest.seeds},
          {"levels", manifest.levels},
          {"sweep", sweep}};
}

ShardManifest manifest_from_json(const nlohmann::json& json) {
  ShardManifest manifest;
  manifest.experiment_hash = json.at("experiment_hash").get<std::string>();
  manifest.experiment_file = json.at("experiment_file").get<std::string>();
  manifest.experiment_arguments = json.at("experiment_arguments").get<std::string>();
  manifest.description = json.at("description").get<std::string>();
  manifest.baseline = json.at("baseline").get<std::string>();
  manifest.pairs = json.at("pairs").get<std::vector<std::pair<std::string, std::string>>>();
  manifest.seeds = json.at("seeds").get<std::vector<std::uint64_t>>();
  manifest.levels = json.at("levels").get<std::size_t>();
  if (!json.at("sweep").is_null()) {
    const auto& sweep = json.at("sweep");
    manifest.sweep = ExperimentSweep{sweep.at("name").get<std::string>(),
                                     sweep.at("set").get<std::vector<std::string>>(),
                                     sweep.at("values").get<std::vector<nlohmann::json>>()};
  }
  return manifest;
}

}  // namespace

fs::path shards_folder(const fs::path& out_dir) { return out_dir / "shards"; }

fs::path shard_folder(const fs::path& out_dir, ShardSpec shard) {
  return shards_folder(out_dir) / shard_folder_name(shard);
}

fs::path shard_record_path(const fs::path& shard_dir) { return shard_dir / "shard.json"; }

std::string job_file_name(std::size_t job_id) { return fmt::format("job_{}.json", job_id); }

std::optional<std::size_t> parse_job_file_name(const std::string& name) {
  constexpr std::string_view kPrefix = "job_";
  constexpr std::string_view kSuffix = ".json";
  if (name.size() <= kPrefix.size() + kSuffix.size() || !name.starts_with(kPrefix) ||
      !name.ends_with(kSuffix)) {
    return std::nullopt;
  }
  const std::string digits =
      name.substr(kPrefix.size(), name.size() - kPrefix.size() - kSuffix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return std::stoull(digits);
}

void write_shard_record(const fs::path& shard_dir, const ShardRecord& record) {
  const nlohmann::json json = {{"format", kShardFormat},
                               {"shard", record.shard.index},
                               {"shards", record.shard.count},
                               {"status", record.status},
                               {"error", record.error},
                               {"jobs", record.jobs},
                               {"experiment", manifest_json(record.manifest)}};
  write_file_atomically(shard_record_path(shard_dir), json.dump(1) + "\n");
}

ShardRecord read_shard_record(const fs::path& shard_dir) {
  const fs::path file = shard_record_path(shard_dir);
  const nlohmann::json json = read_shard_json(file, "shard record");
  try {
    ShardRecord record;
    record.shard = {json.at("shard").get<std::size_t>(), json.at("shards").get<std::size_t>()};
    record.status = json.at("status").get<std::string>();
    record.error = json.at("error").get<std::string>();
    record.jobs = json.at("jobs").get<std::vector<std::size_t>>();
    record.manifest = manifest_from_json(json.at("experiment"));
    return record;
  } catch (const nlohmann::json::exception& error) {
    throw InputError(file.string() + ": damaged shard record (" + error.what() +
                     "); remove the shard's folder and rerun the shard");
  }
}

void write_job_record(const fs::path& shard_dir, const JobRecord& record, bool with_error_series) {
  nlohmann::json variants = nlohmann::json::array();
  for (const auto& variant : record.variants) {
    variants.push_back({{"name", variant.name},
                        {"noise_model", variant.noise_model},
                        {"run", run_result_to_json(variant.run, with_error_series)}});
  }
  const nlohmann::json json = {{"format", kShardFormat},
                               {"experiment_hash", record.experiment_hash},
                               {"job", record.job.id},
                               {"level", record.job.level},
                               {"seed_index", record.job.seed_index},
                               {"seed", record.job.seed},
                               {"wall_seconds", record.wall_seconds},
                               {"variants", variants}};
  write_file_atomically(shard_dir / job_file_name(record.job.id), json.dump() + "\n");
}

JobRecord read_job_record(const fs::path& file) {
  const nlohmann::json json = read_shard_json(file, "job record");
  try {
    JobRecord record;
    record.experiment_hash = json.at("experiment_hash").get<std::string>();
    record.job = {json.at("job").get<std::size_t>(), json.at("level").get<std::size_t>(),
                  json.at("seed_index").get<std::size_t>(), json.at("seed").get<std::uint64_t>()};
    record.wall_seconds = json.at("wall_seconds").get<double>();
    for (const auto& variant : json.at("variants")) {
      record.variants.push_back({variant.at("name").get<std::string>(),
                                 variant.at("noise_model").get<std::string>(),
                                 run_result_from_json(variant.at("run"), file.string())});
    }
    return record;
  } catch (const nlohmann::json::exception& error) {
    throw InputError(file.string() + ": damaged job record (" + error.what() +
                     "); delete it and rerun its shard with --resume");
  }
}

std::string shell_quoted(const std::string& text) {
  if (!text.empty() &&
      text.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789"
                             "_-./=:,+@%") == std::string::npos) {
    return text;
  }
  std::string quoted = "'";
  for (const char c : text) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

}  // namespace stochnav
