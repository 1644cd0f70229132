// The shipped sweep experiment (configs/experiments/paper_random_vibration_sweep.json) runs as
// a user runs it, shortened: one seed, and the scenario's vibration and final static phases cut
// to 60 s (the 600-s static phase that the fitted variants calibrate on is kept), so that every
// level and every variant of the shipped file goes through `stochnav compare`. Sanitized builds
// (sanitized_build.hpp) run two of the levels.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "json_file.hpp"
#include "run_cli.hpp"
#include "sanitized_build.hpp"
#include "shipped_experiment.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;

using stochnav::testing::read_json;

TEST(ShippedSweep, PaperRandomVibrationSweepRunsEveryLevelAndVariant) {
  nlohmann::json experiment =
      stochnav::testing::shipped_experiment("paper_random_vibration_sweep");
  const stochnav::testing::TempDir dir;
  experiment["data"]["scenario_overrides"] = {{"/vibration_table/phases/2/duration_s", 60},
                                              {"/vibration_table/phases/4/duration_s", 60}};
  if (!stochnav::testing::study_at_full_size()) experiment["sweep"]["values"] = {1, 1000};
  const fs::path file = dir.path() / "sweep.json";
  std::ofstream(file) << experiment.dump();

  const auto run = stochnav::testing::run_cli(
      "compare '" + file.string() + "' --out '" + dir.file("out") + "' --seeds 1", dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;

  std::set<std::string> expected_variants;
  for (const auto& variant : experiment["variants"]) expected_variants.insert(variant["name"]);
  ASSERT_TRUE(expected_variants.contains("classic_variance"));
  const nlohmann::json sweep = read_json(dir.path() / "out" / "sweep.json");
  ASSERT_EQ(sweep["levels"].size(), experiment["sweep"]["values"].size());
  for (std::size_t level = 0; level < sweep["levels"].size(); ++level) {
    const auto& results = read_json(dir.path() / "out" / ("level_" + std::to_string(level)) /
                                    "results.json");
    std::set<std::string> variants;
    for (const auto& variant : results["variants"]) {
      variants.insert(variant["name"]);
      EXPECT_TRUE(variant["metrics"]["lat_err_m"]["mean"].is_number())
          << "level " << level << ", " << variant["name"];
    }
    EXPECT_EQ(variants, expected_variants) << "level " << level;
  }
}

}  // namespace
