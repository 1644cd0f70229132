// End-to-end tests of `stochnav diagnose`: the report.json contract, exit code 2 with a located
// one-line message, no partial outputs, and the two real records of ../shared/data/imu-static.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "diagnose_support.hpp"
#include "json_file.hpp"
#include "run_cli.hpp"
#include "sanitized_build.hpp"
#include "stochnav/model/noise_model_json.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using diagnose_testing::simulated_record;
using testing::run_cli;
using testing::TempDir;
namespace fs = std::filesystem;

const char* kBaseModel = R"({"units": "deg/h", "rate_hz": 100, "terms": [
  {"type": "angle_random_walk", "N": 0.5}, {"type": "rate_random_walk", "K": 20}]})";

std::string csv_of(const Record& record) {
  std::ostringstream out;
  out.precision(17);
  out << "t,value\n";
  for (std::size_t i = 0; i < record.values.size(); ++i) {
    out << static_cast<double>(i) / record.rate_hz << ',' << record.values[i] << '\n';
  }
  return out.str();
}

// A record with a Gauss-Markov term the base model lacks.
std::string write_hidden_gauss_markov(const TempDir& dir) {
  NoiseModel truth = noise_model_from_json(nlohmann::json::parse(kBaseModel));
  truth.terms.push_back(noise_term_from_json(
      nlohmann::json::parse(R"({"type": "gauss_markov", "sigma": 40, "tau_c": 4})"), truth.unit,
      "/"));
  return dir.write("record.csv", csv_of(simulated_record(truth, 100000, 100.0, 4)));
}

using testing::read_json;

std::set<std::string> key_set(const nlohmann::json& object) {
  std::set<std::string> keys;
  for (const auto& [key, value] : object.items()) keys.insert(key);
  return keys;
}

// The ADIS16405 record, or in sanitized builds its first 300,000 samples (50 min) in `dir`.
std::string adis_input_for_this_build(const std::string& path, const TempDir& dir) {
  if (testing::study_at_full_size()) return path;
  const std::string input = dir.file("head.csv");
  std::ifstream in(path);
  std::ofstream head(input);
  std::string line;
  for (int row = 0; row <= 300000 && std::getline(in, line); ++row) head << line << '\n';
  return input;
}

// The keys of report.json's wavelet-variance findings (diagnose/report_json.hpp).
void expect_wavelet_keys(const nlohmann::json& report) {
  const nlohmann::json& outliers = report["wavelet_outliers"];
  EXPECT_EQ(key_set(outliers),
            (std::set<std::string>{"contaminated", "explained_by_nonstationary",
                                   "scale_range_s", "largest_excess",
                                   "largest_excess_scale_s", "wv_unit", "levels", "z_threshold",
                                   "differences_beyond", "worst_samples", "summary"}));
  EXPECT_TRUE(outliers["contaminated"].is_boolean());
  ASSERT_TRUE(outliers["levels"].is_array());
  ASSERT_FALSE(outliers["levels"].empty());
  EXPECT_EQ(key_set(outliers["levels"][0]),
            (std::set<std::string>{"scale_s", "edf", "classical", "classical_lo", "classical_hi",
                                   "robust", "robust_lo", "robust_hi", "excess", "tested",
                                   "flagged"}));
  EXPECT_EQ(outliers["scale_range_s"].is_null(), !outliers["contaminated"].get<bool>());
  const nlohmann::json& short_tau = report["short_tau_gauss_markov"];
  EXPECT_EQ(key_set(short_tau),
            (std::set<std::string>{"applicable", "named", "effect", "added_term",
                                   "tau_c_on_range_end", "in_model",
                                   "robust_wv", "scales", "objective_without", "objective_with",
                                   "threshold", "largest_share", "largest_share_scale_s",
                                   "lag1_model", "lag1_record",
                                   "summary"}));
  EXPECT_EQ(short_tau["added_term"].is_null(), !short_tau["named"].get<bool>());
  if (short_tau["named"].get<bool>()) {
    EXPECT_EQ(short_tau["effect"], "gauss_markov");
    EXPECT_EQ(short_tau["added_term"]["type"], "gauss_markov");
    EXPECT_TRUE(short_tau["added_term"].contains("tau_c_sigma"));
  }
}

TEST(DiagnoseCli, WritesTheReportJsonContractReportMdAndPlots) {
  TempDir dir;
  const std::string record = write_hidden_gauss_markov(dir);
  const std::string model = dir.write("model.json", kBaseModel);
  const std::string out = dir.file("out");
  const auto result = run_cli(
      "diagnose --input '" + record + "' --model '" + model + "' --out '" + out + "' --seeds 3",
      dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json report = read_json(fs::path(out) / "report.json");
  std::set<std::string> keys;
  for (const auto& [key, value] : report.items()) keys.insert(key);
  // The DESIGN.md contract's keys, plus the wavelet-variance findings (new keys only).
  EXPECT_EQ(keys, (std::set<std::string>{"consistent", "gap_initial", "gap_final", "iterations",
                                         "final_model", "wavelet_outliers",
                                         "short_tau_gauss_markov"}));
  expect_wavelet_keys(report);
  EXPECT_TRUE(report["consistent"].is_boolean());
  EXPECT_TRUE(report["gap_initial"].is_number());
  EXPECT_TRUE(report["gap_final"].is_number());
  ASSERT_TRUE(report["iterations"].is_array());
  ASSERT_FALSE(report["iterations"].empty());
  for (const auto& step : report["iterations"]) {
    std::set<std::string> step_keys;
    for (const auto& [key, value] : step.items()) step_keys.insert(key);
    // "added_term_at_bound" only when the added term's fit ended on a search bound: flagged in
    // the evidence too (issue #26 item 10).
    const std::string evidence = step["evidence"].get<std::string>();
    const bool at_bound = step.contains("added_term_at_bound");
    if (at_bound) step_keys.erase("added_term_at_bound");
    EXPECT_EQ(step_keys, (std::set<std::string>{"effect", "evidence", "tau_range_s", "time_range_s",
                                                "added_term", "gap_before", "gap_after"}));
    EXPECT_EQ(at_bound, evidence.find("ended on the search bound") != std::string::npos)
        << evidence;
    // The runner-up is compared by the gap the kept term is reported with (the exact one),
    // never by a screening gap (issue #26 item 10: "-> 3.09e+04 (next best: ... at 12.5)").
    if (evidence.find("candidate fits") != std::string::npos) {
      EXPECT_TRUE(evidence.find("(next best, assessed the same way: ") != std::string::npos ||
                  evidence.find("(no other candidate was assessed exactly)") != std::string::npos)
          << evidence;
    }
    EXPECT_TRUE(step["tau_range_s"].is_null() || step["tau_range_s"].size() == 2);
    EXPECT_TRUE(step["time_range_s"].is_null() || step["time_range_s"].size() == 2);
    EXPECT_EQ(step["added_term"]["type"], step["effect"]);
    EXPECT_LT(step["gap_after"].get<double>(), step["gap_before"].get<double>());
  }
  EXPECT_EQ(report["iterations"][0]["effect"], "gauss_markov");
  // final_model reads back as a noise model.
  EXPECT_NO_THROW(noise_model_from_json(report["final_model"]));
  EXPECT_TRUE(fs::exists(fs::path(out) / "report.md"));
  EXPECT_TRUE(fs::exists(fs::path(out) / "allan_initial.png"));
  EXPECT_TRUE(fs::exists(fs::path(out) / "allan_step1.png"));
  // No staging folder is left behind.
  for (const auto& entry : fs::directory_iterator(out)) {
    EXPECT_EQ(entry.path().filename().string().find(".diagnose-staging"), std::string::npos);
  }
}

// Issue #26: a term on its search bound is never added silently. A Gauss-Markov term with a
// correlation time of 0.3 samples (nearly white, but with a deficit at the first tau) is fitted
// with tau_c on its lower search bound (the sampling interval): the step that adds it says so
// in report.json ("added_term_at_bound"), in its evidence, in report.md and on standard output.
TEST(DiagnoseCli, ATermAddedOnItsSearchBoundIsFlaggedEverywhere) {
  TempDir dir;
  NoiseModel truth = noise_model_from_json(nlohmann::json::parse(kBaseModel));
  truth.terms.push_back(noise_term_from_json(
      nlohmann::json::parse(R"({"type": "gauss_markov", "sigma": 300, "tau_c": 0.003})"),
      truth.unit, "/"));
  const std::string record =
      dir.write("record.csv", csv_of(simulated_record(truth, 100000, 100.0, 4)));
  const std::string model = dir.write("model.json", kBaseModel);
  const std::string out = dir.file("out");
  const auto result = run_cli("diagnose --input '" + record + "' --model '" + model + "' --out '" +
                                  out + "' --seeds 3 --plots none --max-iterations 1",
                              dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json report = read_json(fs::path(out) / "report.json");
  ASSERT_FALSE(report["iterations"].empty());
  const auto& first = report["iterations"][0];
  EXPECT_EQ(first["effect"], "gauss_markov");
  EXPECT_NEAR(first["added_term"]["tau_c"].get<double>(), 0.01, 1e-6);  // the sampling interval
  ASSERT_TRUE(first.contains("added_term_at_bound")) << first.dump();
  EXPECT_EQ(first["added_term_at_bound"], nlohmann::json::array({"gauss_markov.tau_c"}));
  const std::string flag = "Flagged: gauss_markov.tau_c ended on the search bound";
  EXPECT_NE(first["evidence"].get<std::string>().find(flag), std::string::npos);
  std::ifstream markdown(fs::path(out) / "report.md");
  const std::string md((std::istreambuf_iterator<char>(markdown)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find(flag), std::string::npos);
  EXPECT_NE(result.out.find("step 1: gauss_markov (gap "), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("; on its search bound: gauss_markov.tau_c)"), std::string::npos)
      << result.out;
}

TEST(DiagnoseCli, AConsistentModelGivesNoIterations) {
  TempDir dir;
  const NoiseModel model = noise_model_from_json(nlohmann::json::parse(kBaseModel));
  const std::string record =
      dir.write("record.csv", csv_of(simulated_record(model, 50000, 100.0, 9)));
  const std::string model_path = dir.write("model.json", kBaseModel);
  const std::string out = dir.file("out");
  const auto result = run_cli("diagnose --input '" + record + "' --model '" + model_path +
                                  "' --out '" + out + "' --plots none --seeds 0",
                              dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json report = read_json(fs::path(out) / "report.json");
  EXPECT_TRUE(report["consistent"].get<bool>());
  EXPECT_TRUE(report["iterations"].empty());
}

struct BadCase {
  std::string name;
  std::string model;     // model file content
  std::string record;    // record file content
  std::string expected;  // in the one-line message
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class DiagnoseCliErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(DiagnoseCliErrors, ExitTwoWithOneLocatedLineAndNoOutput) {
  const BadCase& c = GetParam();
  TempDir dir;
  const std::string record = dir.write("record.csv", c.record);
  const std::string model = dir.write("model.json", c.model);
  const std::string out = dir.file("out");
  const auto result =
      run_cli("diagnose --input '" + record + "' --model '" + model + "' --out '" + out + "'",
              dir.path().string());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_NE(result.err.find(c.expected), std::string::npos) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_FALSE(fs::exists(out)) << "no output folder for a failed run";
}

std::string good_record() {
  std::string text = "t,value\n";
  for (int i = 0; i < 2000; ++i) {
    text += std::to_string(i / 100.0) + "," + std::to_string(((i * 7919) % 101) - 50) + "\n";
  }
  return text;
}

INSTANTIATE_TEST_SUITE_P(
    BadInputs, DiagnoseCliErrors,
    ::testing::Values(
        BadCase{
            "NegativeCoefficient",
            R"({"units": "deg/h", "rate_hz": 100, "terms": [{"type": "angle_random_walk", "N": -1}]})",
            good_record(), "/terms/0/N"},
        BadCase{"UnknownTerm",
                R"({"units": "deg/h", "rate_hz": 100, "terms": [{"type": "wobble"}]})",
                good_record(), "/terms/0/type"},
        BadCase{"JsonSyntax", "{\"units\": \"deg/h\",\n \"rate_hz\": 100,,}", good_record(),
                "line 2"},
        BadCase{
            "RecordWithText",
            R"({"units": "deg/h", "rate_hz": 100, "terms": [{"type": "angle_random_walk", "N": 1}]})",
            "t,value\n0,1\n0.01,abc\n0.02,3\n", "record.csv:3"}),
    [](const auto& test_info) { return test_info.param.name; });

TEST(DiagnoseCliRealData, AdisGyroZHasALineNearTwentyHertz) {
  STOCHNAV_REQUIRE_SHARED_DATA(path, "imu-static/adis16405_imu1_static_100hz.csv");
  TempDir dir;
  // An old fit of the ADIS gyro z without the line (stochnav fit, octave taus, Q N B K).
  const std::string model = dir.write("model.json", R"({"units": "deg/s", "rate_hz": 100,
    "terms": [{"type": "quantization", "Q": 6.65e-06}, {"type": "angle_random_walk", "N": 2.3118},
              {"type": "bias_instability", "B": 23.716}, {"type": "rate_random_walk", "K": 202.62}]})");
  const std::string out = dir.file("out");
  const std::string input = adis_input_for_this_build(path, dir);
  const auto result = run_cli("diagnose --input '" + input + "' --column gyro_z_dps --model '" +
                                  model + "' --out '" + out + "' --plots none --seeds 2",
                              dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::printf("%s", result.out.c_str());
  const nlohmann::json report = read_json(fs::path(out) / "report.json");
  ASSERT_FALSE(report["iterations"].empty());
  const auto& first = report["iterations"][0];
  EXPECT_EQ(first["effect"], "sinusoid");
  const double frequency = first["added_term"]["frequency_hz"].get<double>();
  EXPECT_GT(frequency, 17.0);
  EXPECT_LT(frequency, 22.0);
  if (testing::study_at_full_size()) {  // the head alone leaves more than the line
    EXPECT_LT(report["gap_final"].get<double>(), 0.05 * report["gap_initial"].get<double>());
  }
}

TEST(DiagnoseCliRealData, MtigGyroWithOutliers) {
  STOCHNAV_REQUIRE_SHARED_DATA(path, "imu-static/mtig_cont_imu1_gyrox_100hz.csv");
  TempDir dir;
  // An old three-term fit (stochnav fit --terms angle_random_walk,bias_instability,
  // rate_random_walk, octave taus) of the MTi-G record.
  const std::string model = dir.write("model.json", R"({"units": "rad/s", "rate_hz": 100,
    "terms": [{"type": "angle_random_walk", "N": 1.9308}, {"type": "bias_instability", "B": 46.169},
              {"type": "rate_random_walk", "K": 2.27e-05}]})");
  const std::string out = dir.file("out");
  const auto result = run_cli("diagnose --input '" + path + "' --column gyro_x --model '" + model +
                                  "' --out '" + out + "' --plots none --seeds 2",
                              dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::printf("%s", result.out.c_str());
  const nlohmann::json report = read_json(fs::path(out) / "report.json");
  ASSERT_FALSE(report["iterations"].empty());
  EXPECT_EQ(report["iterations"][0]["effect"], "gauss_markov");
  EXPECT_LT(report["gap_final"].get<double>(), 0.5 * report["gap_initial"].get<double>());
  // Issue #30 item 6: the robust/classical split flags the outliers (the published robust-GMWM
  // example), at the short scales, with the samples to look at and what to do.
  expect_wavelet_keys(report);
  const nlohmann::json& outliers = report["wavelet_outliers"];
  EXPECT_TRUE(outliers["contaminated"].get<bool>());
  EXPECT_FALSE(outliers["explained_by_nonstationary"].get<bool>());
  EXPECT_NEAR(outliers["scale_range_s"][0].get<double>(), 0.02, 1e-9);  // the finest scale
  EXPECT_GT(outliers["largest_excess"].get<double>(), 0.3);  // 64 % at 0.02 s (docs/diagnose.md)
  EXPECT_EQ(outliers["worst_samples"].size(), 5U);
  EXPECT_GT(std::abs(outliers["worst_samples"][0]["z"].get<double>()), 20.0);
  EXPECT_NE(outliers["summary"].get<std::string>().find("fit --method gmwm --robust"),
            std::string::npos);
  EXPECT_NE(result.out.find("outliers: classical WV exceeds the robust one"), std::string::npos);
  std::ifstream md_file(fs::path(out) / "report.md");
  const std::string md((std::istreambuf_iterator<char>(md_file)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("## Wavelet variance: outliers and short-tau correlation"), std::string::npos);
  EXPECT_TRUE(report["short_tau_gauss_markov"]["robust_wv"].get<bool>());
}

// Issue #30 item 6: the ADIS16405 gyro X's lag-1 correlation of 0.17 is a Gauss-Markov term of
// correlation time below one sample; the Allan loop leaves its Gauss-Markov term on the tau_c
// bound (0.01 s), the wavelet variance names it with tau_c and sigma. No outliers are flagged.
TEST(DiagnoseCliRealData, AdisGyroXShortTauGaussMarkovIsNamed) {
  STOCHNAV_REQUIRE_SHARED_DATA(path, "imu-static/adis16405_imu1_static_100hz.csv");
  TempDir dir;
  // A white-noise model (N from ADEV(1 s) = 0.04 deg/s).
  const std::string model = dir.write(
      "model.json",
      R"({"units": "deg/s", "rate_hz": 100, "terms": [{"type": "angle_random_walk", "N": 2.4}]})");
  const std::string out = dir.file("out");
  const std::string input = adis_input_for_this_build(path, dir);
  const auto result = run_cli("diagnose --input '" + input + "' --column gyro_x_dps --model '" +
                                  model + "' --out '" + out + "' --plots none --seeds 2",
                              dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::printf("%s", result.out.c_str());
  const nlohmann::json report = read_json(fs::path(out) / "report.json");
  expect_wavelet_keys(report);
  EXPECT_FALSE(report["wavelet_outliers"]["contaminated"].get<bool>());
  const nlohmann::json& short_tau = report["short_tau_gauss_markov"];
  std::printf("%s\n", short_tau["summary"].get<std::string>().c_str());
  ASSERT_TRUE(short_tau["named"].get<bool>()) << short_tau.dump(2);
  const double tau_c = short_tau["added_term"]["tau_c"].get<double>();
  EXPECT_GT(tau_c, 0.002);  // below one sample (0.01 s): what the Allan fits cannot reach
  EXPECT_LT(tau_c, 0.005);
  EXPECT_NEAR(short_tau["lag1_record"].get<double>(), 0.17, 0.01);
  EXPECT_NE(result.out.find("short-tau gauss_markov (wavelet variance)"), std::string::npos);
}

}  // namespace
}  // namespace stochnav
