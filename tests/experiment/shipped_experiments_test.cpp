// The shipped comparative experiments (configs/experiments/*.json; the sweep has its own test,
// shipped_sweep_test.cpp) run as a user runs them, with one seed, and every run is checked
// against its own 3-sigma bounds through the comparison's consistency verdict:
// - drilling_build_hold: every variant must be consistent (the field job: a model that reports
//   itself healthy while its error leaves its bounds is the failure that matters most);
// - the paper's two experiments: the bounds (`oracle`, `oracle_gyro`) must be consistent, so the
//   shared accelerometer model is fair to every gyro model, and the datasheet `classic` must be
//   flagged (the screen can fail).

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "json_file.hpp"
#include "run_cli.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;

using stochnav::testing::read_json;

/// Runs the shipped experiment `name` with one seed; returns results.json's "variants", after
/// checking that every variant of the file ran with a healthy filter.
nlohmann::json run_shipped(const std::string& name, const stochnav::testing::TempDir& dir) {
  const fs::path config =
      fs::path(STOCHNAV_SOURCE_DIR) / "configs" / "experiments" / (name + ".json");
  const auto run = stochnav::testing::run_cli(
      "compare '" + config.string() + "' --out '" + dir.file("out") + "' --seeds 1", dir.path());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  if (run.exit_code != 0) return nlohmann::json::array();
  std::set<std::string> expected;
  const nlohmann::json shipped = read_json(config);
  for (const auto& variant : shipped["variants"]) expected.insert(variant["name"]);
  const nlohmann::json variants = read_json(dir.path() / "out" / "results.json")["variants"];
  std::set<std::string> ran;
  for (const auto& variant : variants) {
    ran.insert(variant["name"]);
    EXPECT_TRUE(variant["filter_health_ok"].get<bool>()) << name << ": " << variant["name"];
  }
  EXPECT_EQ(ran, expected) << name;
  return variants;
}

bool optimistic(const nlohmann::json& variant) {
  return variant["consistency"]["optimistic"].get<bool>();
}

TEST(ShippedExperiments, DrillingBuildHoldIsConsistentForEveryVariant) {
  const stochnav::testing::TempDir dir;
  for (const auto& variant : run_shipped("drilling_build_hold", dir)) {
    EXPECT_FALSE(optimistic(variant))
        << variant["name"] << ": " << variant["consistency"]["optimistic_reason"];
  }
}

TEST(ShippedExperiments, PaperExperimentsBoundsAreConsistentAndTheDatasheetModelIsFlagged) {
  for (const std::string name : {"paper_random_vibration", "paper_fixed_frequency"}) {
    const stochnav::testing::TempDir dir;
    for (const auto& variant : run_shipped(name, dir)) {
      const std::string variant_name = variant["name"];
      if (variant_name == "oracle" || variant_name == "oracle_gyro") {
        EXPECT_FALSE(optimistic(variant))
            << name << ": " << variant_name << ": " << variant["consistency"]["optimistic_reason"];
      }
      if (variant_name == "classic") {
        EXPECT_TRUE(optimistic(variant)) << name;
      }
    }
  }
}

}  // namespace
