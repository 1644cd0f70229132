#include "stochnav/experiment/shard_plan.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdlib>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

// A whole number written with digits only (no sign, no spaces), or nullopt.
std::optional<std::size_t> whole_number(std::string_view text) {
  std::size_t value = 0;
  if (text.empty()) return std::nullopt;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::size_t environment_number(const EnvironmentLookup& environment, const std::string& name) {
  const std::optional<std::string> text = environment(name);
  const std::optional<std::size_t> value = text ? whole_number(*text) : std::nullopt;
  if (!value) {
    throw ConfigError(
        fmt::format("--shard auto: {}={} is not a whole number; unset it or give "
                    "--shard K/N",
                    name, text.value_or("")));
  }
  return *value;
}

ShardSpec checked(ShardSpec shard, const std::string& source, const std::string& fix) {
  if (shard.count == 0) {
    throw ConfigError(fmt::format("{}: the shard count N is 0; give N >= 1 ({})", source, fix));
  }
  if (shard.index >= shard.count) {
    throw ConfigError(fmt::format(
        "{}: shard index {} is not below the shard count {} (shards are numbered 0 to {}); {}",
        source, shard.index, shard.count, shard.count - 1, fix));
  }
  return shard;
}

}  // namespace

ShardSpec parse_shard_spec(std::string_view text) {
  const std::string source = fmt::format("--shard {}", text);
  const std::size_t slash = text.find('/');
  const auto index = whole_number(text.substr(0, slash));
  const auto count =
      slash == std::string_view::npos ? std::nullopt : whole_number(text.substr(slash + 1));
  if (!index || !count) {
    throw ConfigError(source + ": expected K/N (shard K of N, K from 0 to N-1, e.g. 0/4) or auto");
  }
  const std::string fix = *count == 0
                              ? std::string("e.g. 0/4 to 3/4 for four shards")
                              : fmt::format("use 0/{} to {}/{}", *count, *count - 1, *count);
  return checked({*index, *count}, source, fix);
}

EnvironmentLookup process_environment() {
  return [](const std::string& name) -> std::optional<std::string> {
    const char* value = std::getenv(name.c_str());
    if (value == nullptr) return std::nullopt;
    return std::string(value);
  };
}

ShardSpec shard_spec_from_environment(const EnvironmentLookup& environment,
                                      std::optional<std::size_t> shards_option) {
  if (environment("SLURM_ARRAY_TASK_ID")) {
    const std::size_t task = environment_number(environment, "SLURM_ARRAY_TASK_ID");
    if (shards_option) {
      return checked({task, *shards_option},
                     fmt::format("--shard auto: SLURM_ARRAY_TASK_ID={} with --shards {}", task,
                                 *shards_option),
                     fmt::format("submit the array as --array=0-{} for --shards {}",
                                 *shards_option == 0 ? 0 : *shards_option - 1, *shards_option));
    }
    const std::size_t low = environment("SLURM_ARRAY_TASK_MIN")
                                ? environment_number(environment, "SLURM_ARRAY_TASK_MIN")
                                : 0;
    std::optional<std::size_t> span;
    if (environment("SLURM_ARRAY_TASK_MAX")) {
      const std::size_t high = environment_number(environment, "SLURM_ARRAY_TASK_MAX");
      if (high >= low) span = high - low + 1;
    }
    std::optional<std::size_t> count;
    if (environment("SLURM_ARRAY_TASK_COUNT")) {
      count = environment_number(environment, "SLURM_ARRAY_TASK_COUNT");
    }
    if (!count && !span) {
      throw ConfigError(
          "--shard auto: SLURM_ARRAY_TASK_ID is set but neither SLURM_ARRAY_TASK_COUNT nor "
          "SLURM_ARRAY_TASK_MAX is; give the shard count with --shards N");
    }
    if (count && span && *count != *span) {
      throw ConfigError(fmt::format(
          "--shard auto: the Slurm array has gaps (SLURM_ARRAY_TASK_COUNT={} but tasks {} to {}); "
          "number the tasks 0 to N-1 and pass --shards N",
          *count, low, low + *span - 1));
    }
    if (task < low) {
      throw ConfigError(fmt::format(
          "--shard auto: SLURM_ARRAY_TASK_ID={} is below SLURM_ARRAY_TASK_MIN={}; pass --shards N",
          task, low));
    }
    return checked({task - low, count ? *count : *span},
                   fmt::format("--shard auto: Slurm array task {}", task),
                   "check the job's --array");
  }
  if (environment("JOB_COMPLETION_INDEX")) {
    const std::size_t index = environment_number(environment, "JOB_COMPLETION_INDEX");
    if (!shards_option) {
      throw ConfigError(
          "--shard auto: JOB_COMPLETION_INDEX (Kubernetes Indexed Job) gives the index but not "
          "the count; add --shards N with N = the Job's completions");
    }
    return checked({index, *shards_option},
                   fmt::format("--shard auto: JOB_COMPLETION_INDEX={} with --shards {}", index,
                               *shards_option),
                   "set --shards to the Job's completions");
  }
  throw ConfigError(
      "--shard auto: neither SLURM_ARRAY_TASK_ID (Slurm job array) nor JOB_COMPLETION_INDEX "
      "(Kubernetes Indexed Job) is set; run it as an array task or give --shard K/N");
}

std::vector<ComparisonJob> comparison_jobs(std::size_t levels,
                                           const std::vector<std::uint64_t>& seeds) {
  std::vector<ComparisonJob> jobs;
  for (std::size_t level = 0; level < levels; ++level) {
    for (std::size_t s = 0; s < seeds.size(); ++s) {
      jobs.push_back({jobs.size(), level, s, seeds[s]});
    }
  }
  return jobs;
}

std::size_t shard_of_job(std::size_t job_id, std::size_t shard_count) {
  return job_id % shard_count;
}

std::vector<ComparisonJob> jobs_of_shard(const std::vector<ComparisonJob>& jobs, ShardSpec shard) {
  std::vector<ComparisonJob> mine;
  for (const auto& job : jobs) {
    if (shard_of_job(job.id, shard.count) == shard.index) mine.push_back(job);
  }
  return mine;
}

std::string shard_folder_name(ShardSpec shard) {
  return fmt::format("shard-{}-of-{}", shard.index, shard.count);
}

std::optional<ShardSpec> parse_shard_folder_name(std::string_view name) {
  constexpr std::string_view kPrefix = "shard-";
  constexpr std::string_view kMiddle = "-of-";
  if (name.substr(0, kPrefix.size()) != kPrefix) return std::nullopt;
  name.remove_prefix(kPrefix.size());
  const std::size_t middle = name.find(kMiddle);
  if (middle == std::string_view::npos) return std::nullopt;
  const auto index = whole_number(name.substr(0, middle));
  const auto count = whole_number(name.substr(middle + kMiddle.size()));
  if (!index || !count || *count == 0 || *index >= *count) return std::nullopt;
  return ShardSpec{*index, *count};
}

}  // namespace stochnav
