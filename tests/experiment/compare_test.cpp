// `stochnav compare` end to end on a tiny experiment (the paper's random-vibration scenario cut to
// 150 s): results.json carries "fitted", "consistency" and "pairs" with the right values; the
// sign test against exact binomial values; sweeps set the right pointers and write one folder
// per level; noise_variance_scale scales the simulated noise; bad variants fail before any
// simulation; relative --out and a bare experiment file name work.

#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "json_file.hpp"
#include "run_cli.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/comparison.hpp"
#include "stochnav/experiment/experiment_config.hpp"
#include "shipped_experiment.hpp"
#include "temp_dir.hpp"
#include "tiny_comparison.hpp"

namespace stochnav {
namespace {

using testing::read_json;
using testing::run_cli;
using testing::TempDir;
namespace fs = std::filesystem;

// The paper's random-vibration scenario, 150 s: 60 s static, 5 + 20 + 5 s vibration, 60 s
// static.
nlohmann::json short_scenario() {
  std::ifstream in(std::string(STOCHNAV_SOURCE_DIR) +
                   "/configs/scenarios/paper_random_vibration.json");
  nlohmann::json scenario = nlohmann::json::parse(in);
  auto& phases = scenario["vibration_table"]["phases"];
  const double durations[] = {60, 5, 20, 5, 60};
  for (std::size_t i = 0; i < phases.size(); ++i) phases[i]["duration_s"] = durations[i];
  return scenario;
}

// Three variants on the short scenario: the classic datasheet filter, a white model fitted with
// a random walk on the first 60 s, the oracle.
nlohmann::json tiny_experiment(int seeds) {
  nlohmann::json experiment = {{"data", {{"scenario_config", "scenario.json"}, {"seeds", seeds}}},
                               {"baseline", "classic"},
                               {"aids", stochnav::testing::static_position_aids()},
                               {"filter", stochnav::testing::vibration_table_filter()},
                               {"variants", stochnav::testing::tiny_comparison_variants()}};
  return experiment;
}

// Writes the scenario and the experiment into `dir`; returns the experiment's path.
fs::path write_experiment(const TempDir& dir, const nlohmann::json& experiment,
                          const nlohmann::json& scenario = short_scenario()) {
  std::ofstream(dir.path() / "scenario.json") << scenario.dump();
  const fs::path file = dir.path() / "experiment.json";
  std::ofstream(file) << experiment.dump(1);
  return file;
}

TEST(SignTest, ExactBinomialValues) {
  EXPECT_DOUBLE_EQ(sign_test_p_value(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(sign_test_p_value(3, 0), 0.25);              // 2 * 1/8
  EXPECT_DOUBLE_EQ(sign_test_p_value(5, 0), 0.0625);            // 2 / 32
  EXPECT_NEAR(sign_test_p_value(9, 1), 22.0 / 1024.0, 1e-12);   // 2 * 11 / 1024
  EXPECT_NEAR(sign_test_p_value(1, 9), 22.0 / 1024.0, 1e-12);   // symmetric
  EXPECT_NEAR(sign_test_p_value(8, 2), 112.0 / 1024.0, 1e-12);  // 2 * 56 / 1024
  EXPECT_DOUBLE_EQ(sign_test_p_value(5, 5), 1.0);
  EXPECT_NEAR(sign_test_p_value(20, 0), 2.0 / 1048576.0, 1e-15);
}

TEST(CompareCli, ResultsCarryFittedConsistencyAndPairs) {
  const TempDir dir;
  nlohmann::json experiment = tiny_experiment(2);
  experiment["pairs"] = nlohmann::json::array({nlohmann::json::array({"white_tuned", "classic"}),
                                               nlohmann::json::array({"oracle", "white_tuned"})});
  const fs::path file = write_experiment(dir, experiment);
  const auto run =
      run_cli("compare '" + file.string() + "' --out '" + dir.file("out") + "'", dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json results = read_json(dir.path() / "out" / "results.json");
  ASSERT_EQ(results["variants"].size(), 3u);
  for (const auto& variant : results["variants"]) {
    SCOPED_TRACE(variant["name"].get<std::string>());
    // fitted: one entry per seed with both groups' params.
    ASSERT_EQ(variant["fitted"].size(), 2u);
    EXPECT_TRUE(variant["fitted"][0]["gyro"].is_object());
    EXPECT_TRUE(variant["fitted"][0]["accel"].is_object());
    // consistency: NEES bounds as chi2(9 N) / N for the N samples over both seeds.
    const auto& consistency = variant["consistency"];
    ASSERT_TRUE(consistency.is_object());
    const double samples = consistency["nees_samples"].get<double>();
    EXPECT_GT(samples, 100.0);
    const boost::math::chi_squared_distribution<double> sum(9.0 * samples);
    EXPECT_NEAR(consistency["nees_bounds"][0].get<double>(),
                boost::math::quantile(sum, 0.025) / samples, 1e-9);
    EXPECT_NEAR(consistency["nees_bounds"][1].get<double>(),
                boost::math::quantile(sum, 0.975) / samples, 1e-9);
    EXPECT_LT(consistency["nees_bounds"][0].get<double>(), 9.0);
    EXPECT_GT(consistency["nees_bounds"][1].get<double>(), 9.0);
    // Per variant: the samples-weighted mean of the seeds' NEES means.
    double weighted = 0.0, total = 0.0;
    for (const auto& seed : consistency["per_seed"]) {
      weighted += seed["nees_mean"].get<double>() * seed["nees_samples"].get<double>();
      total += seed["nees_samples"].get<double>();
    }
    EXPECT_NEAR(consistency["nees_mean"].get<double>(), weighted / total, 1e-9 * weighted);
    EXPECT_DOUBLE_EQ(total, samples);
    for (const auto& [metric, share] : consistency["inside_3sigma"].items()) {
      EXPECT_GE(share.get<double>(), 0.0) << metric;
      EXPECT_LE(share.get<double>(), 1.0) << metric;
    }
    ASSERT_EQ(consistency["aids"].size(), 1u);
    EXPECT_EQ(consistency["aids"][0]["dof"], 6);
    EXPECT_TRUE(consistency["aids"][0]["nis_mean"].is_number());
    EXPECT_TRUE(consistency.contains("optimistic"));
  }
  // The datasheet filter is far too confident; the oracle is not.
  EXPECT_TRUE(results["variants"][0]["consistency"]["optimistic"].get<bool>());
  EXPECT_FALSE(results["variants"][2]["consistency"]["optimistic"].get<bool>());
  // The fitted white model reports its fit quality per axis.
  const auto& quality = results["variants"][1]["fitted"][0]["fit_quality"]["gyro"];
  ASSERT_TRUE(quality.is_object());
  EXPECT_TRUE(quality["x"]["dof"].is_number());
  EXPECT_TRUE(quality["x"]["chi_square_per_dof"].is_number());
  EXPECT_TRUE(quality["x"].contains("method"));
  EXPECT_TRUE(results["variants"][0]["fitted"][0]["fit_quality"]["gyro"].is_null());
  // Pairs: the difference of the per-seed max abs errors, wins and the sign test.
  ASSERT_EQ(results["pairs"].size(), 2u);
  const auto& pair = results["pairs"][0];
  EXPECT_EQ(pair["a"], "white_tuned");
  EXPECT_EQ(pair["b"], "classic");
  for (const auto& [metric, stats] : pair["metrics"].items()) {
    const auto& a = results["variants"][1]["metrics"][metric]["per_seed"];
    const auto& b = results["variants"][0]["metrics"][metric]["per_seed"];
    std::size_t a_wins = 0, b_wins = 0;
    for (std::size_t s = 0; s < 2; ++s) {
      const double diff = a[s].get<double>() - b[s].get<double>();
      EXPECT_DOUBLE_EQ(stats["per_seed_diff"][s].get<double>(), diff) << metric;
      a_wins += diff < 0.0;
      b_wins += diff > 0.0;
    }
    EXPECT_EQ(stats["a_wins"].get<std::size_t>(), a_wins) << metric;
    EXPECT_EQ(stats["b_wins"].get<std::size_t>(), b_wins) << metric;
    EXPECT_DOUBLE_EQ(stats["sign_test_p"].get<double>(), sign_test_p_value(a_wins, b_wins));
  }
  // table.md: the consistency table, the verdicts and the pairs.
  std::ifstream table_in(dir.path() / "out" / "table.md");
  const std::string table((std::istreambuf_iterator<char>(table_in)), {});
  EXPECT_NE(table.find("classic (OPTIMISTIC)"), std::string::npos) << table;
  EXPECT_NE(table.find("NEES mean [bounds]"), std::string::npos);
  EXPECT_NE(table.find("white_tuned - classic"), std::string::npos);
}

TEST(CompareCli, DefaultPairsAreEveryVariantAgainstTheBaseline) {
  const TempDir dir;
  const fs::path file = write_experiment(dir, tiny_experiment(1));
  const ExperimentConfig config = read_experiment_config(file);
  ASSERT_EQ(config.pairs.size(), 2u);
  EXPECT_EQ(config.pairs[0], std::make_pair(std::string("white_tuned"), std::string("classic")));
  EXPECT_EQ(config.pairs[1], std::make_pair(std::string("oracle"), std::string("classic")));
  nlohmann::json bad = tiny_experiment(1);
  bad["pairs"] = nlohmann::json::array({nlohmann::json::array({"white_tuned", "nope"})});
  std::ofstream(file) << bad.dump();
  try {
    read_experiment_config(file);
    ADD_FAILURE() << "an unknown variant in pairs was accepted";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("/pairs/0/1"), std::string::npos) << error.what();
  }
}

TEST(CompareSweep, LevelsSetTheirPointers) {
  const TempDir dir;
  nlohmann::json experiment = tiny_experiment(1);
  experiment["sweep"] = {
      {"name", "N"},
      {"set", {"/scenario/noise_variance_scale/gyro", "/variants/0/noise/gyro/params/N"}},
      {"values", {2.0, 8.0}}};
  const fs::path file = write_experiment(dir, experiment);
  const ExperimentConfig config = read_experiment_config(file);
  ASSERT_TRUE(config.sweep);
  for (std::size_t level = 0; level < 2; ++level) {
    const double value = level == 0 ? 2.0 : 8.0;
    const ExperimentConfig at = sweep_level(config, level);
    EXPECT_FALSE(at.sweep);
    EXPECT_EQ(at.scenario_sweep_values["/noise_variance_scale/gyro"], value);
    EXPECT_EQ(at.variants[0].run_config["noise"]["gyro"]["params"]["N"], value);
    // Untouched: the other variants.
    EXPECT_FALSE(at.variants[1].run_config["noise"]["gyro"]["params"].contains("N"));
  }
  // A pointer outside the two roots is refused.
  experiment["sweep"]["set"] = {"/baseline"};
  std::ofstream(file) << experiment.dump();
  try {
    read_experiment_config(file);
    ADD_FAILURE() << "a sweep pointer outside /scenario and /variants was accepted";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("/sweep/set/0"), std::string::npos) << error.what();
  }
}

TEST(CompareSweep, WritesOneFolderPerLevelAndSweepJson) {
  const TempDir dir;
  nlohmann::json experiment = tiny_experiment(1);
  experiment["variants"].erase(2);  // classic and white_tuned only
  experiment["sweep"] = {{"name", "gyro variance x"},
                         {"set", {"/scenario/noise_variance_scale/gyro"}},
                         {"values", {1, 100}}};
  const fs::path file = write_experiment(dir, experiment);
  const auto run =
      run_cli("compare '" + file.string() + "' --out '" + dir.file("out") + "'", dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json sweep = read_json(dir.path() / "out" / "sweep.json");
  ASSERT_EQ(sweep["levels"].size(), 2u);
  EXPECT_EQ(sweep["levels"][1]["value"], 100);
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "level_0" / "results.json"));
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "level_1" / "table.md"));
  // The white model fitted on the static phase sees the larger static noise of level 1.
  const auto n_of = [&](std::size_t level) {
    return sweep["levels"][level]["results"]["variants"][1]["fitted"][0]["gyro"]["N"][0]
        .get<double>();
  };
  EXPECT_GT(n_of(1), n_of(0));
  EXPECT_FALSE(fs::exists(dir.path() / "out" / ".scenarios"));
}

// A run in which a metric is never defined (the toolface and azimuth of a hole that is still
// vertical): the plots draw its panel empty instead of failing (gnuplot refuses a plot without a
// point; compare exited 2 on the shipped drilling experiment cut to its first 15 minutes).
TEST(CompareSweep, AMetricUndefinedThroughoutStillPlots) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "no gnuplot";
  const TempDir dir;
  nlohmann::json experiment = testing::shipped_experiment("drilling_build_hold");
  experiment["data"]["scenario_overrides"] = {{"/drilling/duration_s", 900}};
  experiment["variants"] = {experiment["variants"][0], experiment["variants"][4]};
  experiment["sweep"] = {{"name", "gyro variance x"},
                         {"set", {"/scenario/noise_variance_scale/gyro"}},
                         {"values", {1, 4}}};
  const fs::path file = dir.path() / "vertical.json";
  std::ofstream(file) << experiment.dump();
  const auto run = run_cli("compare '" + file.string() + "' --out '" + dir.file("out") +
                               "' --seeds 1",
                           dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json results = read_json(dir.path() / "out" / "level_0" / "results.json");
  EXPECT_TRUE(results["variants"][0]["metrics"]["toolface_err_deg"]["mean"].is_null() ||
              results["variants"][0]["metrics"]["toolface_err_deg"]["mean"] == 0)
      << "the toolface is defined: the case is not tested";
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "level_0" / "metrics.png"));
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "sweep.png"));
}

// The scheduled gyro noise of a short static table with and without a variance factor of 16:
// the white-noise level (the standard deviation of the increments, where the ARW dominates)
// scales by sqrt(16) = 4; moving_noise_variance_scale does not touch a static phase.
TEST(NoiseVarianceScale, ScalesTheSimulatedAngleRandomWalkBySqrt) {
  const TempDir dir;
  nlohmann::json scenario = short_scenario();
  scenario["vibration_table"]["phases"] = {
      {{"name", "static"}, {"duration_s", 60}, {"motion", "static"}}};
  scenario["sensors"]["gyro"]["noise"]["terms"] = nlohmann::json::array();
  scenario["sensors"]["gyro"]["scheduled_noise"]["terms"][0]["N"] = 0.05;
  scenario["sensors"]["gyro"]["turn_on_bias_sigma_dph"] = 0.0;
  const auto simulate = [&](const std::string& name, double factor,
                            const std::string& key = "noise_variance_scale") {
    nlohmann::json config = scenario;
    if (factor != 1.0) config[key] = {{"gyro", factor}};
    std::ofstream(dir.path() / (name + ".json")) << config.dump();
    const auto run = run_cli(
        "simulate scenario '" + dir.file(name + ".json") + "' --out '" + dir.file(name) + "'",
        dir.path());
    EXPECT_EQ(run.exit_code, 0) << run.err;
    // Sample standard deviation of the gyro x angle increments about their mean (static: the
    // noise).
    std::ifstream in(dir.path() / name / "imu.csv");
    std::string line;
    std::getline(in, line);
    std::size_t column = 0;
    {
      std::size_t start = 0, index = 0;
      while (true) {
        const std::size_t comma = line.find(',', start);
        const std::string name_i = line.substr(start, comma - start);
        if (name_i == "dtheta_x") {
          column = index;
          break;
        }
        if (comma == std::string::npos) break;
        start = comma + 1;
        ++index;
      }
    }
    EXPECT_GT(column, 0u) << line;
    double sum = 0.0, squares = 0.0;
    std::size_t count = 0;
    while (std::getline(in, line)) {
      std::size_t start = 0;
      for (std::size_t i = 0; i < column; ++i) start = line.find(',', start) + 1;
      const double value = std::stod(line.substr(start));
      sum += value;
      squares += value * value;
      ++count;
    }
    const double mean = sum / static_cast<double>(count);
    return std::sqrt(squares / static_cast<double>(count) - mean * mean);
  };
  const double plain = simulate("plain", 1.0);
  const double scaled = simulate("scaled", 16.0);
  EXPECT_NEAR(scaled / plain, 4.0, 0.15);
  // The moving-phase factor leaves a static record alone.
  EXPECT_DOUBLE_EQ(simulate("moving", 16.0, "moving_noise_variance_scale"), plain);
  // And in scenario.json (what the oracle reads): the phase scale is sqrt(16).
  const nlohmann::json truth = read_json(dir.path() / "scaled" / "scenario.json");
  EXPECT_NE(truth.dump().find("\"gyro_noise_scale\":4.0"), std::string::npos);
}

TEST(CompareCli, BadVariantFailsBeforeSimulating) {
  const TempDir dir;
  nlohmann::json experiment = tiny_experiment(1);
  // A long scenario: if it were simulated first, the failure would take many seconds.
  nlohmann::json scenario = short_scenario();
  scenario["vibration_table"]["phases"][4]["duration_s"] = 100000;
  experiment["variants"][1]["noise"]["gyro"]["params"]["rate_random_walk"] = "yes";
  const fs::path file = write_experiment(dir, experiment, scenario);
  const auto run =
      run_cli("compare '" + file.string() + "' --out '" + dir.file("out") + "'", dir.path());
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("white_tuned"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("rate_random_walk"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir.path() / "out" / ".scenarios"));
  // A params error of a model built from params, and an unknown plugin, likewise.
  experiment = tiny_experiment(1);
  experiment["variants"][0]["noise"]["gyro"]["params"]["N"] = -1;
  write_experiment(dir, experiment, scenario);
  auto bad = run_cli("compare '" + file.string() + "' --out '" + dir.file("out") + "'", dir.path());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("classic"), std::string::npos) << bad.err;
  experiment = tiny_experiment(1);
  experiment["variants"][0]["noise"]["gyro"]["plugin"] = "no_such_plugin";
  write_experiment(dir, experiment, scenario);
  bad = run_cli("compare '" + file.string() + "' --out '" + dir.file("out") + "'", dir.path());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("no_such_plugin"), std::string::npos) << bad.err;
  // An aid's params too, although the aid data do not exist before the simulation.
  experiment = tiny_experiment(1);
  experiment["aids"][0]["params"]["sigma_position_mm"] = 1.0;
  write_experiment(dir, experiment, scenario);
  bad = run_cli("compare '" + file.string() + "' --out '" + dir.file("out") + "'", dir.path());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("sigma_position_mm"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir.path() / "out" / ".scenarios"));
}

TEST(CompareCli, RelativeOutAndBareExperimentFileName) {
  const TempDir dir;
  nlohmann::json experiment = tiny_experiment(1);
  experiment["variants"].erase(1);  // classic and oracle
  write_experiment(dir, experiment);
  fs::create_directories(dir.path() / "work");
  // run_cli runs in the current directory: a shell cd for both cases. From another folder with
  // a relative --out and the experiment named by a relative path; then a bare file name.
  const std::string cli = STOCHNAV_CLI_PATH;
  const std::string in_work = "cd '" + (dir.path() / "work").string() + "' && '" + cli +
                              "' compare ../experiment.json --out out/x > /dev/null 2>&1";
  EXPECT_EQ(std::system(in_work.c_str()), 0);
  EXPECT_TRUE(fs::exists(dir.path() / "work" / "out" / "x" / "results.json"));
  const std::string bare = "cd '" + dir.path().string() + "' && '" + cli +
                           "' compare experiment.json --out '" + dir.file("bare") +
                           "' > /dev/null 2>&1";
  EXPECT_EQ(std::system(bare.c_str()), 0);
  EXPECT_TRUE(fs::exists(dir.path() / "bare" / "results.json"));
}

}  // namespace
}  // namespace stochnav
