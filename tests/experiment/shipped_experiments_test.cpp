// The shipped comparative experiments (configs/experiments/*.json; the sweep has its own test,
// shipped_sweep_test.cpp) run as a user runs them, with one seed, and every run is checked
// against its own 3-sigma bounds through the comparison's consistency verdict:
// - drilling_build_hold: every variant must be consistent (the field job: a model that reports
//   itself healthy while its error leaves its bounds is the failure that matters most);
// - the paper's two experiments: the bounds (`oracle`, `oracle_gyro`) must be consistent, so the
//   shared accelerometer model is fair to every gyro model, and the datasheet `classic` must be
//   flagged (the screen can fail);
// - the estimators_* experiments (docs/gmwm.md, "Does a better estimator give a better filter?"):
//   the Allan-fitted and GMWM-fitted variants agree or disagree as the docs say.
// In sanitized builds (sanitized_build.hpp) the scenarios are cut short by overrides (the drilling
// run to 45 min started 5 m above the kickoff: the alignment, the first stands, the start of the
// build and the first vibration episode; the paper tables' long phases to 60 s) and the check
// that needs the whole run (the datasheet model flagged) is left to the full size.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
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
using stochnav::testing::study_at_full_size;

/// Runs the shipped experiment `name` with one seed (its scenario changed by
/// `sanitized_overrides`, JSON pointer -> value, in sanitized builds); returns results.json's
/// "variants", after checking that every variant of the file ran with a healthy filter.
/// `always_shortened`: the overrides apply in every build (a study whose findings the short run
/// shows, kept to seconds in the release suite).
nlohmann::json run_shipped(const std::string& name, const stochnav::testing::TempDir& dir,
                           const nlohmann::json& sanitized_overrides,
                           bool always_shortened = false) {
  fs::path config = fs::path(STOCHNAV_SOURCE_DIR) / "configs" / "experiments" / (name + ".json");
  if (always_shortened || !study_at_full_size()) {
    nlohmann::json experiment = stochnav::testing::shipped_experiment(name);
    experiment["data"]["scenario_overrides"].update(sanitized_overrides);
    config = dir.path() / (name + ".json");
    std::ofstream(config) << experiment.dump();
  }
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
  for (const auto& variant :
       run_shipped("drilling_build_hold", dir,
                   {{"/drilling/duration_s", 2700}, {"/drilling/start_md_m", 495}})) {
    EXPECT_FALSE(optimistic(variant))
        << variant["name"] << ": " << variant["consistency"]["optimistic_reason"];
  }
}

TEST(ShippedExperiments, PaperExperimentsBoundsAreConsistentAndTheDatasheetModelIsFlagged) {
  const std::map<std::string, nlohmann::json> sanitized_overrides = {
      {"paper_random_vibration",
       {{"/vibration_table/phases/2/duration_s", 60}, {"/vibration_table/phases/4/duration_s", 60}}},
      {"paper_fixed_frequency",
       {{"/vibration_table/phases/2/duration_s", 60},
        {"/vibration_table/phases/4/duration_s", 60},
        {"/vibration_table/phases/6/duration_s", 60}}}};
  for (const auto& [name, overrides] : sanitized_overrides) {
    const stochnav::testing::TempDir dir;
    for (const auto& variant : run_shipped(name, dir, overrides)) {
      const std::string variant_name = variant["name"];
      if (variant_name == "oracle" || variant_name == "oracle_gyro") {
        EXPECT_FALSE(optimistic(variant))
            << name << ": " << variant_name << ": " << variant["consistency"]["optimistic_reason"];
      }
      if (variant_name == "classic" && study_at_full_size()) {
        EXPECT_TRUE(optimistic(variant)) << name;
      }
    }
  }
}

// Does a better estimator give a better filter (docs/gmwm.md)? Where the model can describe the
// noise (white noise and a flicker floor: `augmented` with those terms) the Allan fit and GMWM
// agree to about 1 % and the filter is the same and consistent; where it cannot (one
// Gauss-Markov term for a flicker floor) the two estimators weigh the misfit differently, and
// both filters are optimistic.
TEST(ShippedExperiments, EstimatorsAgreeWhereTheModelDescribesTheNoise) {
  const stochnav::testing::TempDir dir;
  std::map<std::string, nlohmann::json> by_name;
  for (const auto& variant :
       run_shipped("estimators_random_vibration", dir,
                   {{"/vibration_table/phases/2/duration_s", 60},
                    {"/vibration_table/phases/4/duration_s", 60}})) {
    by_name[variant["name"]] = variant;
  }
  ASSERT_EQ(by_name.size(), 4u);
  for (const char* name : {"augmented_avar", "augmented_gmwm"}) {
    EXPECT_FALSE(optimistic(by_name[name]))
        << name << ": " << by_name[name]["consistency"]["optimistic_reason"];
  }
  const double avar = by_name["augmented_avar"]["metrics"]["azimuth_err_deg"]["mean"];
  const double gmwm = by_name["augmented_gmwm"]["metrics"]["azimuth_err_deg"]["mean"];
  EXPECT_NEAR(gmwm, avar, 0.05 * avar);
  if (study_at_full_size()) {
    for (const char* name : {"gauss_markov_avar", "gauss_markov_gmwm"}) {
      EXPECT_TRUE(optimistic(by_name[name])) << name;
    }
  }
}

std::map<std::string, nlohmann::json> by_name(const nlohmann::json& variants) {
  std::map<std::string, nlohmann::json> named;
  for (const auto& variant : variants) named[variant["name"]] = variant;
  return named;
}

/// Per axis "x", "y", "z" of the gyro fit quality of a variant's first seed (the davar plugin's
/// under "rate_random_walk_fit").
nlohmann::json gyro_fit_quality(const nlohmann::json& variant) {
  const nlohmann::json& quality = variant["fitted"][0]["fit_quality"]["gyro"];
  return quality.contains("rate_random_walk_fit") ? quality["rate_random_walk_fit"] : quality;
}

double mean_chi_square_per_dof(const nlohmann::json& variant) {
  double sum = 0.0;
  for (const char* axis : {"x", "y", "z"}) {
    sum += gyro_fit_quality(variant)[axis]["chi_square_per_dof"].get<double>();
  }
  return sum / 3.0;
}

// The same question on the paper's fixed-frequency experiment (docs/gmwm.md): white noise and the
// flicker floor (`augmented`) fitted either way give the same, consistent filter; N + K
// (`white_tuned`, and `davar_causal`'s K) fails its fit by both estimators (no term for the
// floor), and both fall back to the floor-matched rule, which reads the Allan variance: the same
// N and K whatever the estimator; one Gauss-Markov term is put at a shorter correlation time and
// a smaller sigma by GMWM (which trusts the short scales), with the better fit statistic.
TEST(ShippedExperiments, EstimatorsOnTheFixedFrequencyExperiment) {
  const stochnav::testing::TempDir dir;
  auto named = by_name(run_shipped("estimators_fixed_frequency", dir,
                                   {{"/vibration_table/phases/2/duration_s", 60},
                                    {"/vibration_table/phases/4/duration_s", 60},
                                    {"/vibration_table/phases/6/duration_s", 60}}));
  ASSERT_EQ(named.size(), 8u);
  const double avar = named["augmented_avar"]["metrics"]["azimuth_err_deg"]["mean"];
  const double gmwm = named["augmented_gmwm"]["metrics"]["azimuth_err_deg"]["mean"];
  EXPECT_NEAR(gmwm, avar, 0.05 * avar);
  for (const char* stem : {"white_tuned", "davar_causal"}) {
    const std::string a = std::string(stem) + "_avar", g = std::string(stem) + "_gmwm";
    for (const char* axis : {"x", "y", "z"}) {
      for (const auto& name : {a, g}) {
        EXPECT_EQ(gyro_fit_quality(named[name])[axis]["method"], "floor_matched") << name;
      }
    }
    EXPECT_EQ(named[a]["fitted"][0]["gyro"]["K"], named[g]["fitted"][0]["gyro"]["K"]) << stem;
  }
  const auto& gm_avar = named["gauss_markov_avar"]["fitted"][0]["gyro"];
  const auto& gm_gmwm = named["gauss_markov_gmwm"]["fitted"][0]["gyro"];
  for (std::size_t axis = 0; axis < 3; ++axis) {
    EXPECT_LT(gm_gmwm["tau_c"][axis].get<double>(), gm_avar["tau_c"][axis].get<double>());
    EXPECT_LT(gm_gmwm["sigma"][axis].get<double>(), gm_avar["sigma"][axis].get<double>());
  }
  EXPECT_LT(mean_chi_square_per_dof(named["gauss_markov_gmwm"]),
            mean_chi_square_per_dof(named["gauss_markov_avar"]));
  if (study_at_full_size()) {
    for (const char* name : {"augmented_avar", "augmented_gmwm"}) {
      EXPECT_FALSE(optimistic(named[name]))
          << name << ": " << named[name]["consistency"]["optimistic_reason"];
    }
    for (const char* name : {"gauss_markov_avar", "gauss_markov_gmwm"}) {
      EXPECT_TRUE(optimistic(named[name])) << name;
    }
  }
}

// And on the drill string (docs/gmwm.md): the two variants of drilling_build_hold.json that fit
// their gyro model on the static alignment, fitted either way. `augmented` (white noise and the
// flicker floor) gives the same filter, consistent, by both estimators; `davar_causal`'s N + K fit
// fails by both and the floor-matched rule gives the same K. The run is always the short one
// (45 min from 5 m above the kickoff: the alignment, where the fits are made, the first stands,
// the start of the build and the first vibration episode).
TEST(ShippedExperiments, EstimatorsOnTheDrillString) {
  const stochnav::testing::TempDir dir;
  auto named = by_name(run_shipped("estimators_drilling_build_hold", dir,
                                   {{"/drilling/duration_s", 2700}, {"/drilling/start_md_m", 495}},
                                   /*always_shortened=*/true));
  ASSERT_EQ(named.size(), 4u);
  // Consistent by both estimators, positions and attitude inside 3 sigma throughout. (The
  // vertical velocity is the margin: 95 % inside, the 12-Hz episode's accelerometer noise above
  // the config's model; without the interval aids' high-passed noise term of fix 7 it was 94 %
  // and the run optimistic: docs/drilling-envelope.md, fix 7.)
  for (const char* name : {"augmented_avar", "augmented_gmwm"}) {
    EXPECT_FALSE(optimistic(named[name]))
        << name << ": " << named[name]["consistency"]["optimistic_reason"];
    const nlohmann::json& inside = named[name]["consistency"]["inside_3sigma"];
    for (const char* quantity : {"lat_err_m", "lon_err_m", "height_err_m", "inclination_err_deg",
                                 "azimuth_err_deg", "toolface_err_deg"}) {
      EXPECT_GE(inside[quantity].get<double>(), 0.99) << name << " " << quantity;
    }
  }
  const double avar = named["augmented_avar"]["metrics"]["azimuth_err_deg"]["mean"];
  const double gmwm = named["augmented_gmwm"]["metrics"]["azimuth_err_deg"]["mean"];
  EXPECT_NEAR(gmwm, avar, 0.05 * avar);
  for (const char* name : {"davar_causal_avar", "davar_causal_gmwm"}) {
    for (const char* axis : {"x", "y", "z"}) {
      EXPECT_EQ(gyro_fit_quality(named[name])[axis]["method"], "floor_matched") << name;
    }
  }
  EXPECT_EQ(named["davar_causal_avar"]["fitted"][0]["gyro"]["K"],
            named["davar_causal_gmwm"]["fitted"][0]["gyro"]["K"]);
}

}  // namespace
