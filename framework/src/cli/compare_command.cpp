// stochnav compare EXPERIMENT.json --out DIR: filter variants x Monte-Carlo seeds
// (experiment/comparison.hpp); with --shard K/N only shard K's jobs (experiment/shard_run.hpp);
// stochnav compare merge DIR: the shards combined (experiment/shard_merge.hpp).

#include <fmt/format.h>

#include <charconv>
#include <cstdlib>
#include <memory>
#include <optional>

#include "command_support.hpp"
#include "commands.hpp"
#include "standard_output.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/comparison.hpp"
#include "stochnav/experiment/shard_files.hpp"
#include "stochnav/experiment/shard_merge.hpp"
#include "stochnav/experiment/shard_run.hpp"
#include "stochnav/io/atomic_file.hpp"

namespace stochnav::cli {
namespace {

struct CompareArguments {
  std::string experiment;
  std::string out;
  std::vector<std::uint64_t> seeds;
  bool full_scenario = false;
  std::string shard;                  ///< "K/N", "auto" or empty (unsharded)
  std::optional<std::size_t> shards;  ///< --shards N, with --shard auto
  bool resume = false;
};

// The words after `stochnav compare` that rebuild this experiment (merge's rerun command).
std::string experiment_arguments(const CompareArguments& arguments) {
  std::string words = shell_quoted(std::filesystem::absolute(arguments.experiment).string());
  if (!arguments.seeds.empty()) {
    words += fmt::format(" --seeds {}", fmt::join(arguments.seeds, " "));
  }
  if (arguments.full_scenario) words += " --full-scenario";
  return words;
}

// A Slurm task runs on the CPUs it was given, not on every core of a shared node (threads do
// not change the results).
void use_slurm_allocation(ExperimentConfig& config) {
  const char* cpus = std::getenv("SLURM_CPUS_PER_TASK");
  if (config.threads != 0 || cpus == nullptr) return;
  unsigned count = 0;
  const std::string_view text(cpus);
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), count);
  if (error == std::errc() && end == text.data() + text.size() && count > 0) config.threads = count;
}

void run_sharded(const CompareArguments& arguments, ExperimentConfig config) {
  use_slurm_allocation(config);
  ShardRunOptions options;
  options.shard = arguments.shard == "auto"
                      ? shard_spec_from_environment(process_environment(), arguments.shards)
                      : parse_shard_spec(arguments.shard);
  options.resume = arguments.resume;
  options.progress = true;
  options.experiment_arguments = experiment_arguments(arguments);
  const ShardRunSummary summary = run_shard(config, arguments.out, options);
  write_standard_output(fmt::format(
      "shard {}/{}: {} job(s) run, {} already complete, in {:.1f} s; wrote {}\n"
      "when every shard is done: stochnav compare merge {}\n",
      options.shard.index, options.shard.count, summary.jobs - summary.skipped, summary.skipped,
      summary.wall_seconds, summary.folder.string(), shell_quoted(arguments.out)));
}

void run_unsharded(const CompareArguments& arguments, const ExperimentConfig& config) {
  if (config.sweep) {
    const nlohmann::json sweep = run_sweep(config, arguments.out, true);
    write_standard_output(fmt::format(
        "wrote {}/sweep.json, sweep.png, sweep_pairs.png and {} level folders (level_<i>/)\n",
        arguments.out, sweep["levels"].size()));
    return;
  }
  OutputFolder folder(arguments.out);  // one writer from the first run to the last file
  const ComparisonResult result = run_comparison(config, arguments.out, true);
  write_comparison(result, config, arguments.out);
  folder.keep();
  write_standard_output(fmt::format(
      "{}\nwrote {}/results.json, table.md, metrics.png, errors_<variant>.png ({} s)\n",
      comparison_table(result, config), arguments.out, result.wall_seconds));
}

void add_merge_command(CLI::App& compare) {
  auto out = std::make_shared<std::string>();
  CLI::App* merge = compare.add_subcommand(
      "merge", "Combine the shards of DIR/shards/ into DIR's results.json, table.md and plots");
  merge->add_option("dir", *out, "The --out folder of the shards")->required();
  merge->callback([out] {
    const MergeSummary summary = merge_shards(*out);
    write_standard_output(
        (summary.sweep ? std::string() : summary.table + '\n') +
        fmt::format("merged {} shard(s), {} job(s): wrote {}\n", summary.shards, summary.jobs,
                    summary.sweep ? *out + "/sweep.json, sweep.png and level_<i>/"
                                  : *out + "/results.json, table.md and plots"));
  });
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto arguments = std::make_shared<CompareArguments>();
  CLI::App* command = app.add_subcommand(
      "compare", "Compare filter variants (noise models) on the same data over Monte-Carlo seeds");
  // Not required() here: `compare merge DIR` has no experiment; checked in the callback.
  command->add_option("experiment", arguments->experiment, "Experiment config (JSON)");
  command->add_option("--out", arguments->out, "Output folder (required; not with merge)");
  command->add_option("--seeds", arguments->seeds,
                      "Override the experiment's seeds (simulated data only), e.g. --seeds 1 2 3")
      ->check(whole_number());
  command->add_flag("--full-scenario", arguments->full_scenario,
                    "Simulate the scenario as its config says, ignoring the experiment's "
                    "data/scenario_overrides (e.g. the whole 36 h drilling run)");
  command->add_option("--shard", arguments->shard,
                      "Run only shard K of N (K/N, K from 0 to N-1) into DIR/shards/, or 'auto' "
                      "from SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX; then compare merge DIR");
  command
      ->add_option("--shards", arguments->shards,
                   "With --shard auto: the shard count N (needed for JOB_COMPLETION_INDEX; "
                   "with Slurm, the array is then numbered 0..N-1)")
      ->check(positive_count());
  command->add_flag("--resume", arguments->resume,
                    "With --shard: keep the shard's jobs already complete, run only the rest");
  add_merge_command(*command);
  command->callback([command, arguments] {
    if (command->get_subcommand("merge")->parsed()) {
      if (!arguments->experiment.empty() || !arguments->out.empty()) {
        throw ConfigError(
            "compare merge DIR: takes only the folder; drop the experiment and --out");
      }
      return;
    }
    if (arguments->experiment.empty()) {
      throw ConfigError(
          "compare: missing EXPERIMENT.json; usage: stochnav compare "
          "EXPERIMENT.json --out DIR, or stochnav compare merge DIR");
    }
    if (arguments->out.empty()) {
      throw ConfigError("compare: --out DIR is required; give the output folder");
    }
    if (arguments->shards && arguments->shard != "auto") {
      throw ConfigError(
          "--shards: only with --shard auto; give --shard K/N alone, or --shard "
          "auto --shards N");
    }
    if (arguments->resume && arguments->shard.empty()) {
      throw ConfigError("--resume: only with --shard K/N or --shard auto (a sharded run)");
    }
    ExperimentConfig config = read_experiment_config(arguments->experiment);
    if (arguments->full_scenario) config.scenario_overrides = nlohmann::json::object();
    if (!arguments->seeds.empty()) {
      if (!config.scenario_config) {
        throw ConfigError("--seeds: the experiment's data is not simulated; drop --seeds");
      }
      config.seeds = arguments->seeds;
    }
    check_work_limits(config);
    if (arguments->shard.empty()) {
      run_unsharded(*arguments, config);
    } else {
      run_sharded(*arguments, config);
    }
  });
}

}  // namespace stochnav::cli
