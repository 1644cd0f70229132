// `stochnav compare --shard K/N` and `stochnav compare merge` end to end on a tiny experiment
// (the paper's random-vibration scenario cut to 150 s): merged shards equal the unsharded run
// bit for bit (plain and sweep); --shard auto reads Slurm and Kubernetes indices; missing and
// failed shards are named with the command that reruns them and nothing is written; --resume
// skips complete jobs; every bad input is one line and exit code 2.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "json_file.hpp"
#include "run_cli.hpp"
#include "temp_dir.hpp"
#include "tiny_comparison.hpp"

namespace stochnav {
namespace {

using testing::CliResult;
using testing::run_cli;
using testing::read_json;
using testing::TempDir;
namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::size_t line_count(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// Three variants (a datasheet white model, a white model fitted on the first 60 s, the oracle)
// on the shipped random-vibration scenario shortened to 150 s; `seeds` Monte-Carlo seeds.
nlohmann::json tiny_overridden_experiment(int seeds) {
  nlohmann::json overrides = nlohmann::json::object();
  const int durations[] = {60, 5, 20, 5, 60};
  for (int i = 0; i < 5; ++i) {
    overrides["/vibration_table/phases/" + std::to_string(i) + "/duration_s"] = durations[i];
  }
  return {{"data",
           {{"scenario_config",
             std::string(STOCHNAV_SOURCE_DIR) + "/configs/scenarios/paper_random_vibration.json"},
            {"seeds", seeds},
            {"scenario_overrides", overrides}}},
          {"baseline", "classic"},
          {"aids", stochnav::testing::static_position_aids()},
          {"variants", stochnav::testing::tiny_comparison_variants()}};
}

// Runs `env ENVIRONMENT stochnav ARGUMENTS` (ENVIRONMENT: "-u NAME" and "NAME=VALUE" words):
// exactly the engine variables a test wants, whatever the environment ctest runs in.
CliResult run_cli_with_environment(const std::string& environment, const std::string& arguments,
                                   const fs::path& scratch) {
  const fs::path err_path = scratch / "stderr_env.txt";
  const std::string command =
      "env -u SLURM_ARRAY_TASK_ID -u SLURM_ARRAY_TASK_COUNT "
      "-u SLURM_ARRAY_TASK_MIN -u SLURM_ARRAY_TASK_MAX "
      "-u JOB_COMPLETION_INDEX " +
      environment + " '" STOCHNAV_CLI_PATH "' " + arguments + " 2> '" + err_path.string() + "'";
  CliResult result;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> chunk{};
  while (std::fgets(chunk.data(), chunk.size(), pipe) != nullptr) result.out += chunk.data();
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.err = read_text(err_path);
  return result;
}

class ShardedCompare : public ::testing::Test {
 protected:
  void write_experiment(const nlohmann::json& experiment) {
    std::ofstream(experiment_) << experiment.dump(1);
  }
  CliResult stochnav(const std::string& arguments) { return run_cli(arguments, dir_.path()); }
  // `stochnav compare EXPERIMENT --out OUT EXTRA`.
  CliResult compare(const std::string& out, const std::string& extra) {
    return stochnav("compare '" + experiment_.string() + "' --out '" + dir_.file(out) + "' " +
                    extra);
  }
  CliResult merge(const std::string& out) {
    return stochnav("compare merge '" + dir_.file(out) + "'");
  }
  fs::path path(const std::string& name) const { return dir_.path() / name; }

  // The unsharded run into `out`, moved to `reference` so that the sharded run can use the same
  // folder (results name the seeds' scenario folders under it).
  void run_reference(const std::string& out, const std::string& reference) {
    const CliResult run = compare(out, "");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    fs::rename(path(out), path(reference));
  }
  void run_shards(const std::string& out, std::size_t count) {
    for (std::size_t k = 0; k < count; ++k) {
      const CliResult run =
          compare(out, "--shard " + std::to_string(k) + "/" + std::to_string(count));
      ASSERT_EQ(run.exit_code, 0) << run.err;
    }
  }
  void expect_error_line(const CliResult& run, const std::string& part) {
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_EQ(line_count(run.err), 1u) << run.err;
    EXPECT_NE(run.err.find(part), std::string::npos) << run.err;
  }

  TempDir dir_;
  fs::path experiment_ = dir_.path() / "experiment.json";
};

// results.json of the two folders agree in everything but wall_seconds, each per-seed value
// bit for bit; table.md and the plots are the same bytes.
void expect_same_comparison(const fs::path& reference, const fs::path& merged) {
  nlohmann::json expected = read_json(reference / "results.json");
  nlohmann::json actual = read_json(merged / "results.json");
  ASSERT_EQ(expected["variants"].size(), actual["variants"].size());
  std::size_t compared = 0;
  for (std::size_t v = 0; v < expected["variants"].size(); ++v) {
    for (const auto& [metric, summary] : expected["variants"][v]["metrics"].items()) {
      const auto& mine = actual["variants"][v]["metrics"][metric]["per_seed"];
      ASSERT_EQ(summary["per_seed"].size(), mine.size());
      for (std::size_t s = 0; s < mine.size(); ++s, ++compared) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(summary["per_seed"][s].get<double>()),
                  std::bit_cast<std::uint64_t>(mine[s].get<double>()))
            << metric << " seed " << s;
      }
    }
  }
  EXPECT_GT(compared, 0u);
  expected.erase("wall_seconds");
  actual.erase("wall_seconds");
  EXPECT_EQ(expected.dump(1), actual.dump(1));
  EXPECT_EQ(read_text(reference / "table.md"), read_text(merged / "table.md"));
  for (const auto& entry : fs::directory_iterator(reference)) {
    if (entry.path().extension() != ".png") continue;
    SCOPED_TRACE(entry.path().filename().string());
    ASSERT_TRUE(fs::exists(merged / entry.path().filename()));
    EXPECT_EQ(read_text(entry.path()), read_text(merged / entry.path().filename()));
  }
}

TEST_F(ShardedCompare, MergedEqualsUnshardedBitForBit) {
  write_experiment(tiny_overridden_experiment(4));
  run_reference("out", "reference");
  run_shards("out", 3);
  // Jobs go round robin: shard 0 of 3 runs jobs 0 and 3.
  EXPECT_TRUE(fs::exists(path("out/shards/shard-0-of-3/job_0.json")));
  EXPECT_TRUE(fs::exists(path("out/shards/shard-0-of-3/job_3.json")));
  EXPECT_TRUE(fs::exists(path("out/shards/shard-2-of-3/job_2.json")));
  EXPECT_FALSE(fs::exists(path("out/.scenarios")));  // the seeds' data are removed
  EXPECT_FALSE(fs::exists(path("out/results.json")));
  const CliResult merged = merge("out");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(merged.out.find("merged 3 shard(s), 4 job(s)"), std::string::npos) << merged.out;
  expect_same_comparison(path("reference"), path("out"));
}

TEST_F(ShardedCompare, SweepMergedEqualsUnshardedBitForBit) {
  nlohmann::json experiment = tiny_overridden_experiment(2);
  experiment["sweep"] = {{"name", "gyro noise variance x"},
                         {"set", {"/scenario/noise_variance_scale/gyro"}},
                         {"values", {1, 10}}};
  write_experiment(experiment);
  run_reference("out", "reference");
  run_shards("out", 3);
  const CliResult merged = merge("out");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  nlohmann::json expected = read_json(path("reference/sweep.json"));
  nlohmann::json actual = read_json(path("out/sweep.json"));
  ASSERT_EQ(actual["levels"].size(), 2u);
  for (auto* sweep : {&expected, &actual}) {
    for (auto& level : (*sweep)["levels"]) level["results"].erase("wall_seconds");
  }
  EXPECT_EQ(expected.dump(1), actual.dump(1));
  for (const char* level : {"level_0", "level_1"}) {
    SCOPED_TRACE(level);
    expect_same_comparison(path("reference") / level, path("out") / level);
  }
  for (const char* plot : {"sweep.png", "sweep_pairs.png"}) {
    if (fs::exists(path("reference") / plot)) {
      EXPECT_EQ(read_text(path("reference") / plot), read_text(path("out") / plot)) << plot;
    }
  }
}

TEST_F(ShardedCompare, AutoReadsSlurmArrayAndKubernetesIndex) {
  write_experiment(tiny_overridden_experiment(3));
  const std::string arguments =
      "compare '" + experiment_.string() + "' --out '" + dir_.file("out") + "' --shard auto";
  const CliResult slurm = run_cli_with_environment(
      "SLURM_ARRAY_TASK_ID=0 SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_TASK_MIN=0 "
      "SLURM_ARRAY_TASK_MAX=1",
      arguments, dir_.path());
  ASSERT_EQ(slurm.exit_code, 0) << slurm.err;
  EXPECT_TRUE(fs::exists(path("out/shards/shard-0-of-2/shard.json")));
  const CliResult kubernetes =
      run_cli_with_environment("JOB_COMPLETION_INDEX=1", arguments + " --shards 2", dir_.path());
  ASSERT_EQ(kubernetes.exit_code, 0) << kubernetes.err;
  EXPECT_TRUE(fs::exists(path("out/shards/shard-1-of-2/shard.json")));
  const CliResult merged = merge("out");
  EXPECT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(read_json(path("out/results.json"))["seeds"].size(), 3u);
  // Outside any array task, and a Kubernetes index without the count: one line, exit 2.
  expect_error_line(run_cli_with_environment("", arguments, dir_.path()),
                    "neither SLURM_ARRAY_TASK_ID");
  expect_error_line(run_cli_with_environment("JOB_COMPLETION_INDEX=1", arguments, dir_.path()),
                    "add --shards N");
  expect_error_line(
      run_cli_with_environment("JOB_COMPLETION_INDEX=1", arguments + " --shards 0", dir_.path()),
      "--shards");
}

TEST_F(ShardedCompare, MissingShardIsNamedWithItsRerunCommandAndNothingIsWritten) {
  write_experiment(tiny_overridden_experiment(3));
  for (const char* shard : {"0/3", "2/3"}) {
    ASSERT_EQ(compare("out", std::string("--shard ") + shard).exit_code, 0);
  }
  const CliResult merged = merge("out");
  expect_error_line(merged, "1 of 3 shards incomplete: shard 1 (not started)");
  EXPECT_NE(merged.err.find("--shard K/3 --resume` for K in 1"), std::string::npos) << merged.err;
  EXPECT_NE(merged.err.find("sbatch --array=1 "), std::string::npos) << merged.err;
  for (const char* file : {"results.json", "table.md", "metrics.png", "errors_classic.png"}) {
    EXPECT_FALSE(fs::exists(path("out") / file)) << file;
  }
  // The command the message gives, for K = 1, completes the experiment.
  const std::size_t open = merged.err.find("`stochnav ") + 10;
  std::string rerun = merged.err.substr(open, merged.err.find('`', open) - open);
  const std::size_t k = rerun.find("K/3");
  ASSERT_NE(k, std::string::npos) << rerun;
  rerun = rerun.substr(0, k) + "1" + rerun.substr(k + 1);
  const CliResult rerun_result = stochnav(rerun);
  ASSERT_EQ(rerun_result.exit_code, 0) << rerun << "\n" << rerun_result.err;
  EXPECT_EQ(merge("out").exit_code, 0);
  EXPECT_TRUE(fs::exists(path("out/results.json")));
}

TEST_F(ShardedCompare, FailedShardIsNamedAndResumeCompletesIt) {
  write_experiment(tiny_overridden_experiment(2));
  ASSERT_EQ(compare("out", "--shard 0/2").exit_code, 0);
  // Shard 1 cannot simulate its seed: a file where its scenario folder goes.
  std::ofstream(path("out/.scenarios")) << "in the way";
  const CliResult failed = compare("out", "--shard 1/2");
  EXPECT_EQ(failed.exit_code, 2) << failed.err;
  EXPECT_EQ(read_json(path("out/shards/shard-1-of-2/shard.json"))["status"], "failed");
  const CliResult merged = merge("out");
  expect_error_line(merged, "shard 1 (failed, 0 of 1 jobs done: ");
  EXPECT_FALSE(fs::exists(path("out/results.json")));
  fs::remove(path("out/.scenarios"));
  const CliResult resumed = compare("out", "--shard 1/2 --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(merge("out").exit_code, 0);
}

TEST_F(ShardedCompare, ResumeRunsOnlyTheJobsNotComplete) {
  write_experiment(tiny_overridden_experiment(4));
  ASSERT_EQ(compare("out", "--shard 0/2").exit_code, 0);  // jobs 0 and 2
  const fs::path kept = path("out/shards/shard-0-of-2/job_0.json");
  const fs::path lost = path("out/shards/shard-0-of-2/job_2.json");
  const std::string kept_text = read_text(kept);
  const auto kept_time = fs::last_write_time(kept);
  fs::remove(lost);
  const CliResult resumed = compare("out", "--shard 0/2 --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("1 job(s) run, 1 already complete"), std::string::npos) << resumed.out;
  EXPECT_TRUE(fs::exists(lost));
  EXPECT_EQ(fs::last_write_time(kept), kept_time);
  EXPECT_EQ(read_text(kept), kept_text);
  // Without --resume the shard starts over.
  const CliResult again = compare("out", "--shard 0/2");
  EXPECT_NE(again.out.find("2 job(s) run, 0 already complete"), std::string::npos) << again.out;
}

TEST_F(ShardedCompare, BadShardOptionsAreOneLineAndExitCode2) {
  write_experiment(tiny_overridden_experiment(2));
  expect_error_line(compare("out", "--shard 3/3"), "--shard 3/3: shard index 3 is not below");
  expect_error_line(compare("out", "--shard 0/0"), "--shard 0/0: the shard count N is 0");
  expect_error_line(compare("out", "--shard two/3"), "--shard two/3: expected K/N");
  expect_error_line(compare("out", "--shard 0/2 --shards 2"), "--shards: only with --shard auto");
  expect_error_line(compare("out", "--resume"), "--resume: only with --shard");
  expect_error_line(stochnav("compare --out '" + dir_.file("out") + "'"),
                    "compare: missing EXPERIMENT.json");
  expect_error_line(stochnav("compare '" + experiment_.string() + "'"), "--out DIR is required");
  expect_error_line(stochnav("compare merge '" + dir_.file("nowhere") + "'"), "no shards");
  EXPECT_FALSE(fs::exists(path("out")));
}

TEST_F(ShardedCompare, ForeignFolderInShardsIsRefused) {
  write_experiment(tiny_overridden_experiment(2));
  fs::create_directories(path("out/shards/notes"));
  expect_error_line(compare("out", "--shard 0/2"), "out/shards/notes: not a shard folder");
  expect_error_line(merge("out"), "out/shards/notes: not a shard folder");
  fs::remove(path("out/shards/notes"));
  ASSERT_EQ(compare("out", "--shard 0/2").exit_code, 0);
  std::ofstream(path("out/shards/shard-0-of-2/shard.json")) << "{\"not\": \"a shard\"}";
  expect_error_line(merge("out"), "shard-0-of-2/shard.json: not a shard record");
}

TEST_F(ShardedCompare, ShardsOfAnotherExperimentAreRefused) {
  write_experiment(tiny_overridden_experiment(2));
  ASSERT_EQ(compare("out", "--shard 0/2").exit_code, 0);
  // Other seeds make another experiment: refused before it runs.
  expect_error_line(compare("out", "--shard 1/2 --seeds 1 2 3"), "from another experiment");
  // A folder of another experiment copied in is refused by merge.
  ASSERT_EQ(compare("other", "--shard 1/2 --seeds 1 2 3").exit_code, 0);
  fs::copy(path("other/shards/shard-1-of-2"), path("out/shards/shard-1-of-2"));
  expect_error_line(merge("out"), "come from different experiments");
  EXPECT_FALSE(fs::exists(path("out/results.json")));
}

TEST_F(ShardedCompare, TwoShardsWritingTheSameJobAreRefused) {
  write_experiment(tiny_overridden_experiment(4));
  ASSERT_EQ(compare("out", "--shard 0/2").exit_code, 0);  // jobs 0, 2
  expect_error_line(compare("out", "--shard 0/3"), "would write the same jobs");
  // Shards of two splits started at the same time: merge finds job 0 twice.
  ASSERT_EQ(compare("other", "--shard 0/3").exit_code, 0);  // jobs 0, 3
  fs::copy(path("other/shards/shard-0-of-3"), path("out/shards/shard-0-of-3"));
  expect_error_line(merge("out"), "job 0 was written by two shards");
  EXPECT_FALSE(fs::exists(path("out/results.json")));
}

}  // namespace
}  // namespace stochnav
