// diagnose --run: the innovation analysis on synthetic innovation sequences with known defects,
// over many seeds (detection and false-alarm rates), and end to end on a filter run of the
// random-vibration scenario.

#include "stochnav/diagnose/innovation_analysis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>

#include "run_cli.hpp"
#include "stochnav/core/errors.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::run_cli;
using testing::TempDir;

// One aid with three components updated at 1 Hz for `duration_s`; u = z / sigma is generated
// by `next(t, component)`; sigma is 1.
template <typename Generator>
AidInnovations synthetic_aid(double duration_s, Generator next) {
  AidInnovations aid{.aid_index = 0, .type = "zupt", .samples = {}};
  for (double t = 1.0; t <= duration_s; t += 1.0) {
    InnovationSample sample{.t_s = t, .accepted = true, .nis = 0.0, .z = {}, .sigma = {}};
    for (int i = 0; i < 3; ++i) {
      sample.z.push_back(next(t, i));
      sample.sigma.push_back(1.0);
      sample.nis += sample.z.back() * sample.z.back();
    }
    aid.samples.push_back(sample);
  }
  return aid;
}

InnovationAnalysis analyse(const AidInnovations& aid) {
  return analyse_innovations({aid}, InnovationAnalysisOptions{});
}

bool has_effect(const InnovationAnalysis& analysis, const std::string& effect) {
  for (const auto& f : analysis.findings) {
    if (f.effect && *f.effect == effect) return true;
  }
  return false;
}

constexpr int kAnalysisSeeds = 40;

TEST(InnovationAnalysis, WhiteUnitInnovationsRaiseNoFalseAlarm) {
  int alarms = 0;
  for (int seed = 0; seed < kAnalysisSeeds; ++seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal;
    const auto analysis = analyse(synthetic_aid(1800.0, [&](double, int) { return normal(rng); }));
    alarms += !analysis.consistent || !analysis.findings.empty();
  }
  // alpha = 0.01 per test family and three families: about 1 alarm expected in 40 runs.
  EXPECT_LE(alarms, 4) << "false alarms in " << kAnalysisSeeds << " consistent runs";
}

TEST(InnovationAnalysis, FindsANoiseRiseAndItsTimeSpan) {
  int detected = 0;
  for (int seed = 0; seed < kAnalysisSeeds; ++seed) {
    std::mt19937_64 rng(100 + seed);
    std::normal_distribution<double> normal;
    const auto analysis = analyse(synthetic_aid(1800.0, [&](double t, int i) {
      const bool loud = t >= 600.0 && t < 1200.0 && i < 2;  // horizontal components only
      return (loud ? 2.0 : 1.0) * normal(rng);
    }));
    for (const auto& f : analysis.findings) {
      if (!f.effect || *f.effect != "nonstationary" || !f.time_range_s) continue;
      const auto [t0, t1] = *f.time_range_s;
      EXPECT_NEAR(t0, 600.0, 60.0);
      EXPECT_NEAR(t1, 1200.0, 60.0);
      EXPECT_NEAR(f.scale, 2.0, 0.4);
      EXPECT_EQ(f.components.size(), 2u);
      EXPECT_NE(f.sensor.find("gyro"), std::string::npos);
      ++detected;
      break;
    }
  }
  EXPECT_GE(detected, kAnalysisSeeds - 2);
}

TEST(InnovationAnalysis, NamesUnderstatedWhiteNoise) {
  int named = 0;
  for (int seed = 0; seed < kAnalysisSeeds; ++seed) {
    std::mt19937_64 rng(200 + seed);
    std::normal_distribution<double> normal;
    const auto analysis =
        analyse(synthetic_aid(1800.0, [&](double, int) { return 1.5 * normal(rng); }));
    named += has_effect(analysis, "angle_random_walk") && !has_effect(analysis, "nonstationary");
  }
  EXPECT_GE(named, kAnalysisSeeds - 2);
}

TEST(InnovationAnalysis, NamesACorrelatedErrorAndItsCorrelationTime) {
  const double tau_c = 10.0, rho = std::exp(-1.0 / tau_c);
  int named = 0;
  for (int seed = 0; seed < kAnalysisSeeds; ++seed) {
    std::mt19937_64 rng(300 + seed);
    std::normal_distribution<double> normal;
    std::array<double, 3> state{normal(rng), normal(rng), normal(rng)};
    const auto analysis = analyse(synthetic_aid(3600.0, [&](double, int i) {
      auto& x = state[static_cast<std::size_t>(i)];
      x = rho * x + std::sqrt(1.0 - rho * rho) * normal(rng);  // unit variance, correlated
      return x;
    }));
    for (const auto& f : analysis.findings) {
      if (f.effect && *f.effect == "gauss_markov" && f.tau_c_s) {
        EXPECT_NEAR(*f.tau_c_s, tau_c, 0.3 * tau_c);
        ++named;
        break;
      }
    }
  }
  EXPECT_GE(named, kAnalysisSeeds - 2);
}

TEST(InnovationAnalysis, ReportsAnOverstatedModelWithoutAnEffect) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  const auto analysis =
      analyse(synthetic_aid(1800.0, [&](double, int) { return 0.5 * normal(rng); }));
  EXPECT_TRUE(analysis.consistent);
  ASSERT_EQ(analysis.findings.size(), 1u);
  EXPECT_FALSE(analysis.findings[0].effect.has_value());
  EXPECT_NEAR(analysis.findings[0].scale, 0.5, 0.05);
}

TEST(InnovationAnalysis, NamesAPeriodicError) {
  const double period_s = 8.0;
  std::mt19937_64 rng(9);
  std::normal_distribution<double> normal;
  const auto analysis = analyse(synthetic_aid(1800.0, [&](double t, int) {
    return 0.5 * normal(rng) + 1.5 * std::sin(2.0 * std::numbers::pi * t / period_s + 0.3);
  }));
  bool named = false;
  for (const auto& f : analysis.findings) {
    if (f.effect && *f.effect == "sinusoid" && f.period_s) {
      EXPECT_NEAR(*f.period_s, period_s, 0.5);
      named = true;
    }
  }
  EXPECT_TRUE(named);
}

TEST(InnovationAnalysis, RejectsBadOptions) {
  const AidInnovations aid = synthetic_aid(100.0, [](double, int) { return 0.0; });
  InnovationAnalysisOptions options;
  options.window_s = 0.0;
  EXPECT_THROW(analyse_innovations({aid}, options), ConfigError);
  options = {};
  options.alpha = 0.7;
  EXPECT_THROW(analyse_innovations({aid}, options), ConfigError);
}

TEST(InnovationFile, MalformedFilesNameTheLine) {
  const TempDir dir;
  const std::string header =
      "t,aid,type,accepted,nis,z0,z1,z2,z3,z4,z5,sigma0,sigma1,sigma2,sigma3,sigma4,sigma5\n";
  const auto message = [&](const std::string& content) {
    try {
      read_innovations(dir.write("innovations.csv", content));
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_NE(message("t,x\n").find("innovations.csv:1: not an innovations file"), std::string::npos);
  EXPECT_NE(message(header).find("no aid updates"), std::string::npos);
  EXPECT_NE(message(header + "1,0,zupt,1,0.5,0.1,,,,,\n").find("innovations.csv:2: 11 cells"),
            std::string::npos);
  EXPECT_NE(message(header + "1,0,zupt,1,0.5,x,,,,,,1,,,,,\n").find(":2: component 0"),
            std::string::npos);
  const auto aids = read_innovations(
      dir.write("innovations.csv", header + "1,0,zupt,1,0.5,0.1,0.2,0.3,,,,1,2,3,,,\n"
                                            "1,1,rop,0,nan,0.1,,,,,,1,,,,,\n"));
  ASSERT_EQ(aids.size(), 2u);
  EXPECT_EQ(aids[0].samples[0].z.size(), 3u);
  EXPECT_EQ(aids[1].type, "rop");
  EXPECT_TRUE(std::isnan(aids[1].samples[0].nis));
}

// End to end: the classic white model tuned on the static part, run through the random-vibration
// scenario; the innovations must show the vibration span [600, 1220) s.
TEST(DiagnoseRunCli, FindsTheVibrationSpanOfTheRandomVibrationScenario) {
  const TempDir dir;
  const std::string source = STOCHNAV_SOURCE_DIR;
  const std::string scenario = dir.file("scenario");
  auto result =
      run_cli("simulate scenario '" + source +
                  "/configs/scenarios/paper_random_vibration.json' --out '" + scenario + "'",
              dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json config = {
      {"data", {{"scenario", scenario}}},
      {"noise",
       {{"gyro",
         {{"plugin", "white"}, {"params", nlohmann::json::object()}, {"fit", {{"end_s", 600}}}}},
        {"accel", {{"plugin", "white"}, {"params", {{"N", 0.029}}}}}}},
      {"aids",
       {{{"plugin", "static_position"},
         {"params",
          {{"sigma_position_m", 0.01}, {"sigma_velocity_mps", 0.3}, {"nis_gate", false}}}}}}};
  const std::string run_config = dir.write("run.json", config.dump());
  result = run_cli("run '" + run_config + "' --out '" + dir.file("run") + "'", dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;

  result = run_cli(
      "diagnose --run '" + dir.file("run") + "' --out '" + dir.file("diag") + "' --plots none",
      dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir.file("diag/report.json")));
  EXPECT_FALSE(report["consistent"].get<bool>());
  // The vibration span must be among the nonstationary findings (the unmodelled 20-ug
  // accelerometer bias instability may add a short, weak one in a static phase).
  bool span_found = false;
  for (const auto& finding : report["findings"]) {
    if (finding["effect"] != "nonstationary") continue;
    const double t0 = finding["time_range_s"][0], t1 = finding["time_range_s"][1];
    span_found |= std::abs(t0 - 600.0) <= 60.0 && std::abs(t1 - 1220.0) <= 60.0 &&
                  finding["scale"].get<double>() > 3.0;
  }
  EXPECT_TRUE(span_found) << report.dump(2);
  EXPECT_TRUE(std::filesystem::exists(dir.file("diag/report.md")));
}

TEST(DiagnoseRunCli, BadUseExitsWithTwoAndWritesNothing) {
  const TempDir dir;
  auto result =
      run_cli("diagnose --run '" + dir.file("nowhere") + "' --out '" + dir.file("diag") + "'",
              dir.path().string());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("innovations.csv: not found"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("diag")));
  result = run_cli("diagnose --run x --input y.csv --out '" + dir.file("diag") + "'",
                   dir.path().string());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("do not also give --input"), std::string::npos) << result.err;
  result = run_cli("diagnose --out '" + dir.file("diag") + "'", dir.path().string());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("or --run DIR"), std::string::npos) << result.err;
}

}  // namespace
}  // namespace stochnav
