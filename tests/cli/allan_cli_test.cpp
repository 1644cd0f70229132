// End-to-end: `stochnav allan --format json` on Stable32's PHASE.DAT reproduces its octave table,
// and the JSON has exactly the fields of the DESIGN.md contract.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <vector>

#include "run_cli.hpp"
#include "stable32_table.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::read_stable32_table_file;
using testing::run_cli;
using testing::TempDir;

/// `stochnav allan --input PHASE --data phase --rate 1 OPTIONS --format json`, parsed; an empty
/// object (and a failure) when the tool does not exit with 0.
nlohmann::json allan_json(const std::string& phase_path, const std::string& options,
                          const TempDir& dir) {
  const auto result = run_cli("allan --input '" + phase_path + "' --data phase --rate 1 " +
                                  options + " --format json",
                              dir.path().string());
  EXPECT_EQ(result.exit_code, 0) << options << ": " << result.err;
  if (result.exit_code != 0) return nlohmann::json::object();
  return nlohmann::json::parse(result.out);
}

/// The JSON's rows against a Stable32 table (which may be the start of them): tau = m (tau0 = 1
/// s), n, the deviation under `name` to 1e-4 and, when bound_tolerance > 0, alpha and the
/// bounds to that relative tolerance.
void expect_matches_table(const nlohmann::json& json, const std::string& name,
                          const std::vector<testing::Stable32Row>& rows,
                          double bound_tolerance) {
  ASSERT_TRUE(json.contains(name) && json.contains("tau")) << json.dump();
  ASSERT_FALSE(rows.empty());
  ASSERT_GE(json[name].size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& row = rows[i];
    SCOPED_TRACE(name + " m = " + std::to_string(row.m));
    EXPECT_EQ(json["tau"][i].get<double>(), static_cast<double>(row.m));
    EXPECT_EQ(json["n"][i].get<std::size_t>(), row.terms);
    EXPECT_NEAR(json[name][i].get<double>(), row.deviation, 1e-4 * row.deviation);
    if (bound_tolerance > 0.0) {
      EXPECT_EQ(json["alpha"][i].get<int>(), row.alpha);
      EXPECT_NEAR(json[name + "_lo"][i].get<double>(), row.lower, bound_tolerance * row.lower);
      EXPECT_NEAR(json[name + "_hi"][i].get<double>(), row.upper, bound_tolerance * row.upper);
    }
  }
}

TEST(AllanCli, JsonOnPhaseDatMatchesStable32OctaveTable) {
  STOCHNAV_REQUIRE_SHARED_DATA(phase_dat, "allan/phasedat/PHASE.DAT");
  STOCHNAV_REQUIRE_SHARED_DATA(table, "allan/phasedat/phase_dat_oadev_octave.txt");
  TempDir dir;
  const auto json = allan_json(phase_dat, "--taus octave --edf stable32", dir);
  std::vector<std::string> keys;
  for (const auto& item : json.items()) keys.push_back(item.key());
  std::sort(keys.begin(), keys.end());
  // The contract's keys, plus the deviation's name and its columns under that name.
  EXPECT_EQ(keys, (std::vector<std::string>{"adev", "adev_hi", "adev_lo", "alpha", "deviation",
                                            "edf", "n", "oadev", "oadev_hi", "oadev_lo", "tau"}));
  EXPECT_EQ(json["oadev"], json["adev"]);
  const auto reference = read_stable32_table_file(table);
  EXPECT_EQ(json["tau"].size(), reference.size());
  expect_matches_table(json, "adev", reference, 1e-2);
}

// Every --deviation keeps the JSON keys of the contract ("adev" holds the chosen deviation).
TEST(AllanCli, TotdevOnPhaseDatMatchesStable32OctaveTable) {
  STOCHNAV_REQUIRE_SHARED_DATA(phase_dat, "allan/phasedat/PHASE.DAT");
  STOCHNAV_REQUIRE_SHARED_DATA(table, "allan/phasedat/phase_dat_totdev_octave.txt");
  TempDir dir;
  const auto json = allan_json(phase_dat, "--taus octave --deviation totdev --edf stable32", dir);
  const auto reference = read_stable32_table_file(table);
  EXPECT_EQ(json["tau"].size(), reference.size());
  expect_matches_table(json, "adev", reference, 1e-3);
}

// The new deviations through the CLI: MTIE (no interval: alpha null) and HTOTDEV with its own
// JSON key beside "adev" (its bounds follow another EDF rule than Stable32's: docs/allan.md).
TEST(AllanCli, MtieAndHtotdevOnPhaseDatMatchStable32) {
  STOCHNAV_REQUIRE_SHARED_DATA(phase_dat, "allan/phasedat/PHASE.DAT");
  STOCHNAV_REQUIRE_SHARED_DATA(mtie_table, "allan/phasedat/phase_dat_mtie.txt");
  STOCHNAV_REQUIRE_SHARED_DATA(htot_table, "allan/phasedat/phase_dat_htotdev_octave.txt");
  TempDir dir;
  const auto mtie = allan_json(phase_dat, "--deviation mtie", dir);
  EXPECT_EQ(mtie["deviation"], "mtie");
  const auto mtie_rows = read_stable32_table_file(mtie_table);
  EXPECT_EQ(mtie["mtie"].size(), mtie_rows.size());
  expect_matches_table(mtie, "mtie", mtie_rows, 0.0);
  for (const auto& alpha : mtie["alpha"]) EXPECT_TRUE(alpha.is_null());
  const auto htot = allan_json(phase_dat, "--deviation htotdev", dir);
  expect_matches_table(htot, "htotdev", read_stable32_table_file(htot_table), 0.0);
}

// --edf: the default (plausible) never gives a larger EDF than Stable32's rule, so its intervals
// contain Stable32's, with the same noise types; an unknown rule is bad input (exit 2, one line).
TEST(AllanCli, DefaultEdfRuleNeverNarrowsStable32sInterval) {
  STOCHNAV_REQUIRE_SHARED_DATA(phase_dat, "allan/phasedat/PHASE.DAT");
  TempDir dir;
  const auto plausible = allan_json(phase_dat, "--taus all", dir);
  const auto stable32 = allan_json(phase_dat, "--taus all --edf stable32", dir);
  ASSERT_EQ(plausible["edf"].size(), stable32["edf"].size());
  for (std::size_t i = 0; i < plausible["edf"].size(); ++i) {
    EXPECT_LE(plausible["edf"][i].get<double>(), stable32["edf"][i].get<double>()) << i;
    EXPECT_LE(plausible["adev_lo"][i].get<double>(), stable32["adev_lo"][i].get<double>()) << i;
    EXPECT_GE(plausible["adev_hi"][i].get<double>(), stable32["adev_hi"][i].get<double>()) << i;
    EXPECT_EQ(plausible["alpha"][i], stable32["alpha"][i]) << i;
  }
  const auto result = run_cli("allan --input '" + phase_dat + "' --data phase --rate 1 --edf loose",
                              dir.path().string());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("edf 'loose' is unknown"), std::string::npos) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
}

// A Theo1 factor the record cannot hold is bad input (exit 2, one line), like any other.
TEST(AllanCli, DeviationOnTooShortRecordExitsTwo) {
  TempDir dir;
  const auto path = dir.path() / "short.txt";
  {
    std::ofstream out(path);
    for (int i = 0; i < 8; ++i) out << i * 0.5 << "\n";
  }
  const auto result = run_cli("allan --input '" + path.string() +
                                  "' --data phase --rate 1 --deviation theo1",
                              dir.path().string());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
}

TEST(AllanCli, RateAndPhaseInputsAgree) {
  STOCHNAV_REQUIRE_SHARED_DATA(freq, "allan/nbs14/nbs14_1000_freq.txt");
  STOCHNAV_REQUIRE_SHARED_DATA(phase_dat, "allan/phasedat/PHASE.DAT");
  TempDir dir;
  const auto from_rate =
      run_cli("allan --input '" + freq + "' --rate 1 --format json", dir.path().string());
  const auto from_phase = run_cli(
      "allan --input '" + phase_dat + "' --data phase --rate 1 --format json", dir.path().string());
  ASSERT_EQ(from_rate.exit_code, 0) << from_rate.err;
  ASSERT_EQ(from_phase.exit_code, 0) << from_phase.err;
  const auto a = nlohmann::json::parse(from_rate.out);
  const auto b = nlohmann::json::parse(from_phase.out);
  ASSERT_EQ(a["adev"].size(), b["adev"].size());
  for (std::size_t i = 0; i < a["adev"].size(); ++i) {
    EXPECT_NEAR(a["adev"][i].get<double>(), b["adev"][i].get<double>(),
                1e-6 * b["adev"][i].get<double>());
  }
}

TEST(AllanCli, WritesPlotWhenAsked) {
  STOCHNAV_REQUIRE_SHARED_DATA(phase_dat, "allan/phasedat/PHASE.DAT");
  TempDir dir;
  const auto plot = dir.file("adev.png");
  const auto result = run_cli("allan --input '" + phase_dat + "' --data phase --rate 1 --plot '" +
                                  plot + "' --output '" + dir.file("adev.txt") + "'",
                              dir.path().string());
  if (result.exit_code == 2 && result.err.find("gnuplot") != std::string::npos) {
    GTEST_SKIP() << "gnuplot not installed: " << result.err;
  }
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_GT(std::filesystem::file_size(plot), 1000U);
  EXPECT_TRUE(std::filesystem::exists(dir.file("adev.txt")));
}

// A quote in a file name (a folder named "John's data") reaches the plot's title: gnuplot's
// quoting, not the shell's, keeps the script valid (it failed with "gnuplot failed").
TEST(AllanCli, PlotsARecordWhoseNameHasAQuote) {
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "it's");
  std::string csv = "t,g\n";
  for (int i = 0; i < 4000; ++i) {
    csv += std::to_string(0.01 * i) + "," + std::to_string(i % 7) + "\n";
  }
  const std::string input = dir.write("it's/record.csv", csv);
  for (const std::string command : {"allan", "davar --window 1000 --step 500"}) {
    const std::string plot = (dir.path() / "it's" / (command.substr(0, 5) + ".png")).string();
    const auto result = run_cli(command + " --input \"" + input + "\" --column g --plot \"" +
                                    plot + "\" --output \"" + plot + ".txt\"",
                                dir.path().string());
    if (result.exit_code == 2 && result.err.find("needs gnuplot") != std::string::npos) {
      GTEST_SKIP() << "gnuplot not installed: " << result.err;
    }
    ASSERT_EQ(result.exit_code, 0) << command << ": " << result.err;
    EXPECT_GT(std::filesystem::file_size(plot), 1000U) << command;
  }
}

}  // namespace
}  // namespace stochnav
