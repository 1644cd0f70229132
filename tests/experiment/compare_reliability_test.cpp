// `stochnav compare` when things go wrong: a run failing after the seeds were simulated leaves
// neither OUT/.scenarios nor an output folder it created; absurd requests (seeds beyond the
// limit, repeated or negative seeds) are refused before anything runs; SIGTERM in the middle of
// the simulations leaves nothing behind.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "run_cli.hpp"
#include "spawn_cli.hpp"
#include "temp_dir.hpp"
#include "tiny_comparison.hpp"

namespace stochnav {
namespace {

using testing::run_cli;
using testing::TempDir;
namespace fs = std::filesystem;

// A vibration table holding still for `seconds`, the shipped sensors.
nlohmann::json still_table(double seconds) {
  std::ifstream in(std::string(STOCHNAV_SOURCE_DIR) +
                   "/configs/scenarios/paper_fixed_frequency.json");
  nlohmann::json scenario = nlohmann::json::parse(in);
  scenario["vibration_table"]["phases"] = {
      {{"name", "static"}, {"duration_s", seconds}, {"motion", "static"}}};
  return scenario;
}

nlohmann::json experiment(const nlohmann::json& seeds) {
  const nlohmann::json white = {{"plugin", "white"}, {"params", {{"N", 0.03}}}};
  return {
      {"data", {{"scenario_config", "scenario.json"}, {"seeds", seeds}}},
      {"baseline", "classic"},
      {"aids",
       {{{"plugin", "static_position"},
         {"params", {{"sigma_position_m", 0.01}, {"sigma_velocity_mps", 0.3}}}}}},
      {"filter", stochnav::testing::vibration_table_filter()},
      {"variants",
       {{{"name", "classic"},
         {"noise",
          {{"gyro", {{"plugin", "white"}, {"params", {{"N", 3.33e-5}}}}}, {"accel", white}}}}}}};
}

fs::path write(const TempDir& dir, const nlohmann::json& experiment_json,
               const nlohmann::json& scenario) {
  std::ofstream(dir.path() / "scenario.json") << scenario.dump();
  std::ofstream(dir.path() / "experiment.json") << experiment_json.dump();
  return dir.path() / "experiment.json";
}

std::string compare(const fs::path& file, const fs::path& out, const std::string& extra = "") {
  return "compare '" + file.string() + "' --out '" + out.string() + "'" + extra;
}

// Aid data the simulated scenario does not have: the runs fail, after the simulation.
nlohmann::json failing_after_simulation() {
  nlohmann::json e = experiment(2);
  e["aids"].push_back({{"plugin", "position_fix"}, {"params", nlohmann::json::object()}});
  return e;
}

TEST(CompareFailure, RunFailureLeavesNoScenariosAndNoCreatedFolder) {
  const TempDir dir;
  const fs::path file = write(dir, failing_after_simulation(), still_table(20));
  const fs::path out = dir.path() / "new" / "out";
  const auto result = run_cli(compare(file, out), dir.path());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
  EXPECT_NE(result.err.find("seed"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(dir.path() / "new")) << "a failed compare left the folder it created";
}

TEST(CompareFailure, ExistingOutputFolderStaysWithoutScenarios) {
  const TempDir dir;
  const fs::path file = write(dir, failing_after_simulation(), still_table(20));
  const fs::path out = dir.path() / "out";
  fs::create_directories(out);
  std::ofstream(out / "notes.txt") << "mine";
  const auto result = run_cli(compare(file, out), dir.path());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
  EXPECT_FALSE(fs::exists(out / ".scenarios"));
  EXPECT_FALSE(fs::exists(out / "results.json"));
}

// A comparison into a folder that held an earlier one: the earlier results and the plot of a
// variant this one does not have are gone; the user's own files stay.
TEST(CompareFolder, AnEarlierComparisonIsReplacedWhole) {
  const TempDir dir;
  const fs::path file = write(dir, experiment(1), still_table(20));
  const fs::path out = dir.path() / "out";
  fs::create_directories(out);
  std::ofstream(out / "results.json") << R"({"variants": [{"name": "retired"}]})";
  std::ofstream(out / "errors_retired.png") << "an earlier plot";
  std::ofstream(out / "notes.txt") << "mine";
  const auto result = run_cli(compare(file, out), dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_FALSE(fs::exists(out / "errors_retired.png"));
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
  std::ifstream in(out / "results.json");
  const nlohmann::json results = nlohmann::json::parse(in);
  EXPECT_EQ(results["variants"][0]["name"], "classic");
}

struct RefusedCase {
  std::string name;
  nlohmann::json seeds;  // the experiment's data/seeds
  std::string extra;     // more command-line options
  std::string fragment;  // in the message
};
void PrintTo(const RefusedCase& c, std::ostream* os) { *os << c.name; }

class CompareRefused : public ::testing::TestWithParam<RefusedCase> {};

TEST_P(CompareRefused, UpFrontWithExitTwoAndNothingWritten) {
  const RefusedCase& c = GetParam();
  const TempDir dir;
  // A scenario long enough that simulating it first would be noticed.
  const fs::path file = write(dir, experiment(c.seeds), still_table(100000));
  const auto start = std::chrono::steady_clock::now();
  const auto result = run_cli(compare(file, dir.path() / "out", c.extra), dir.path());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_NE(result.err.find(c.fragment), std::string::npos) << result.err;
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
  EXPECT_LT(seconds, 20.0) << "refused only after work";
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CompareRefused,
    ::testing::Values(
        RefusedCase{"million_seeds_in_config", 1000000, "", "above the limit of 1000"},
        RefusedCase{"seed_list_beyond_limit", nlohmann::json(std::vector<int>(1001, 0)), "",
                    "above the limit of 1000"},
        RefusedCase{"negative_seeds_option", 1, " --seeds -3", "--seeds"},
        RefusedCase{"huge_seed_option", 1, " --seeds 99999999999999999999999", "--seeds"},
        RefusedCase{"repeated_seeds_option", 1, " --seeds 4 4", "twice"}),
    [](const ::testing::TestParamInfo<RefusedCase>& case_info) { return case_info.param.name; });

TEST(CompareSignal, SigtermDuringTheSimulationsLeavesNothing) {
  const TempDir dir;
  // Long enough to be caught simulating: 3 seeds of 2 h at 100 Hz.
  const fs::path file = write(dir, experiment(3), still_table(7200));
  const fs::path out = dir.path() / "out";
  testing::BackgroundCli cli({"compare", file.string(), "--out", out.string()});
  ASSERT_TRUE(cli.started());
  const bool simulating = testing::eventually(
      [&] {
        std::error_code ignored;
        return fs::exists(out / ".scenarios" / "seed_1" / "imu.csv", ignored) ||
               (fs::exists(out / ".scenarios", ignored) &&
                !fs::is_empty(out / ".scenarios", ignored));
      },
      30.0);
  ASSERT_TRUE(simulating) << "compare never started simulating";
  cli.signal(SIGTERM);
  const int status = cli.wait();
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "status " << status;
  EXPECT_FALSE(fs::exists(out)) << "SIGTERM left the output folder compare created";
}

}  // namespace
}  // namespace stochnav
