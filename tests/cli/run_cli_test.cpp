// End-to-end `stochnav run`: a recording without truth started from "initial_state" (static
// alignment), --data, a deliberate initial error that the filter removes, the self-consistency
// report, and every kind of bad run input: exit code 2, one line, no output folder.

#include "run_cli.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "csv_columns.hpp"
#include "stochnav/experiment/survey_listing.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/io/psins_imu.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::run_cli;
using testing::TempDir;
namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A short drilling scenario (shipped config, shortened): 60 s static, then 1-m stands drilled
// with 20-s connections (ZUPT flags in aids.csv).
nlohmann::json short_drilling() {
  std::ifstream in(std::string(STOCHNAV_SOURCE_DIR) + "/configs/scenarios/drilling_build_hold.json");
  nlohmann::json config = nlohmann::json::parse(in);
  config["drilling"]["duration_s"] = 240;
  config["drilling"]["initial_static_s"] = 60;
  config["drilling"]["stand_length_m"] = 1.0;
  config["drilling"]["connection_s"] = 20;
  config["drilling"]["rop_mph"] = 60;
  config["drilling"]["vibration_episodes"] = nlohmann::json::array();
  return config;
}

// A vibration table holding the tool still at 60 deg inclination for 120 s.
nlohmann::json static_table() {
  std::ifstream in(std::string(STOCHNAV_SOURCE_DIR) +
                   "/configs/scenarios/paper_fixed_frequency.json");
  nlohmann::json config = nlohmann::json::parse(in);
  config["vibration_table"]["attitude"] = {
      {"inclination_deg", 60}, {"toolface_deg", 30}, {"azimuth_deg", 100}};
  config["vibration_table"]["phases"] = {{{"name", "static"}, {"duration_s", 120}, {"motion", "static"}}};
  return config;
}

const nlohmann::json kNoise = {{"gyro", {{"plugin", "white"}, {"params", {{"N", 0.005}}}}},
                               {"accel", {{"plugin", "white"}, {"params", {{"N", 0.03}}}}}};

class RunCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    for (const auto& [name, config] :
         {std::pair{"drilling", short_drilling()}, std::pair{"table", static_table()}}) {
      const std::string path = dir_->write(std::string(name) + ".json", config.dump());
      const auto result = run_cli(
          "simulate scenario '" + path + "' --out '" + dir_->file(name) + "'", dir_->path());
      if (result.exit_code != 0) {
        setup_error_ = "simulate scenario " + std::string(name) + ": " + result.err;
        return;
      }
    }
    // A recording: the drilling run's IMU and aids, no truth.
    fs::create_directories(dir_->path() / "recording");
    for (const char* file : {"imu.csv", "aids.csv"}) {
      fs::copy_file(dir_->path() / "drilling" / file, dir_->path() / "recording" / file);
    }
  }
  // A failure in SetUpTestSuite would only skip the tests: fail each of them instead.
  void SetUp() override { ASSERT_TRUE(setup_error_.empty()) << setup_error_; }

  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }

  // The no-truth config: alignment over the static start, then ZUPTs from the aid data.
  static nlohmann::json recording_config() {
    return {{"noise", kNoise},
            {"aids", {{{"plugin", "zupt"}}}},
            {"initial_state",
             {{"tie_on",
               {{"latitude_deg", 46.58}, {"longitude_deg", 124.87}, {"height_m", -300},
                {"measured_depth_m", 450}}},
              {"alignment", {{"static_s", 50}}}}},
            {"output", {{"decimation", 10}}}};
  }

  static std::string write_config(const std::string& name, const nlohmann::json& config) {
    return dir_->write(name, config.dump());
  }

  static TempDir* dir_;
  static std::string setup_error_;
};
TempDir* RunCli::dir_ = nullptr;
std::string RunCli::setup_error_;

TEST_F(RunCli, RecordingWithoutTruthStartsFromTheAlignment) {
  const std::string config = write_config("recording.json", recording_config());
  const fs::path out = dir_->path() / "out_recording";
  const auto result = run_cli("run '" + config + "' --out '" + out.string() + "' --data '" +
                                  (dir_->path() / "recording").string() + "'",
                              dir_->path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(result.err.empty()) << "short runs print no progress lines: " << result.err;
  for (const char* file : {"nav.csv", "biases.csv", "states.csv", "innovations.csv",
                           "survey.csv", "trajectory.xml", "metrics.json"}) {
    EXPECT_TRUE(fs::exists(out / file)) << file;
  }
  EXPECT_FALSE(fs::exists(out / "errors.csv"));
  EXPECT_FALSE(fs::exists(out / "errors.png"));
  const std::string survey = read(out / "survey.csv");
  EXPECT_EQ(survey.substr(0, survey.find(",qc_")),  // DESIGN.md's columns, then the QC's
            "t_s,md_m,inclination_deg,azimuth_deg,toolface_deg,tvd_m,north_m,east_m,"
            "inclination_sigma_deg,azimuth_sigma_deg,north_sigma_m,east_sigma_m,tvd_sigma_m");
  const auto metrics = nlohmann::json::parse(read(out / "metrics.json"));
  EXPECT_TRUE(metrics["metrics"].is_null());
  EXPECT_TRUE(metrics["consistency"].is_null());
  // Without truth the run judges itself by its innovations.
  EXPECT_EQ(metrics["self_check"]["source"], "innovations");
  EXPECT_FALSE(metrics["self_check"]["optimistic"].get<bool>()) << metrics["self_check"];
  EXPECT_NE(result.out.find("consistency (innovations, no truth): ok"), std::string::npos)
      << result.out;
  ASSERT_EQ(metrics["aids"].size(), 1u);
  EXPECT_EQ(metrics["aids"][0]["type"], "zupt");
  EXPECT_EQ(metrics["aids"][0]["dof"], 3);
  EXPECT_GE(metrics["aids"][0]["attempts"].get<int>(), 40);
  // Navigation starts at the end of the alignment span.
  EXPECT_NEAR(metrics["initial"]["t_s"].get<double>(), 50.0, 1e-6);
  const std::string nav = read(out / "nav.csv");
  EXPECT_EQ(nav.substr(nav.find('\n') + 1, 7), "50.100,");
  // The aligned tool heading (vertical tool: azimuth + gyro toolface) against the truth's 60 deg.
  const double heading = std::fmod(metrics["initial"]["azimuth_deg"].get<double>() +
                                       metrics["initial"]["toolface_deg"].get<double>(),
                                   360.0);
  EXPECT_NEAR(heading, 60.0, 3.0 * metrics["initial"]["attitude_sigma_deg"][2].get<double>() + 0.5);
  EXPECT_NE(result.out.find("no truth"), std::string::npos) << result.out;
}

// states.csv: every sensor-error state beyond position, velocity and attitude, named with its
// unit, with a _sigma twin, on nav.csv's epochs: here the biases, both scale-factor blocks and a
// gyro Gauss-Markov block (its three states and the sensor error they make).
TEST_F(RunCli, StatesFileHoldsEverySensorErrorStateWithItsSigma) {
  nlohmann::json config = recording_config();
  config["noise"]["gyro"] = {{"plugin", "gauss_markov"},
                             {"params", {{"sigma", 0.5}, {"tau_c", 300}, {"N", 0.005}}}};
  config["filter"] = {{"scale_factor_sigma_ppm", {{"gyro", 100}, {"accel", 100}}}};
  const fs::path out = dir_->path() / "out_states";
  const auto result = run_cli("run '" + write_config("states.json", config) + "' --out '" +
                                  out.string() + "' --data '" +
                                  (dir_->path() / "recording").string() + "'",
                              dir_->path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string text = read(out / "states.csv");
  const std::string header = text.substr(0, text.find('\n'));
  std::vector<std::string> estimates;
  for (const char* stem : {"accel_bias_%_m_s2", "gyro_bias_%_deg_h", "gyro_scale_factor_%_ppm",
                           "accel_scale_factor_%_ppm", "gyro.gauss_markov_error_%_deg_h"}) {
    for (const char* axis : {"x", "y", "z"}) {
      std::string name = stem;
      name.replace(name.find('%'), 1, axis);
      estimates.push_back(name);
    }
  }
  for (const char* state : {"gyro.gauss_markov_0_si", "gyro.gauss_markov_1_si",
                            "gyro.gauss_markov_2_si"}) {
    estimates.emplace_back(state);
  }
  const testing::CsvColumns columns = testing::read_csv_columns((out / "states.csv").string());
  EXPECT_EQ(columns.size(), 1 + 2 * estimates.size()) << header;
  const testing::CsvColumns nav = testing::read_csv_columns((out / "nav.csv").string());
  ASSERT_TRUE(columns.contains("t")) << header;
  EXPECT_EQ(columns.at("t"), nav.at("t")) << "decimated like nav.csv";
  for (const std::string& name : estimates) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(columns.contains(name) && columns.contains(name + "_sigma")) << header;
    const std::vector<double>& sigma = columns.at(name + "_sigma");
    EXPECT_TRUE(std::all_of(sigma.begin(), sigma.end(), [](double s) { return s > 0.0; }));
  }
  // The Gauss-Markov sensor error is its states in deg/h (M = I): 0.5 deg/h a priori.
  const double rad_per_s_in_deg_h = 180.0 / M_PI * 3600.0;
  const double error_x = columns.at("gyro.gauss_markov_error_x_deg_h").back();
  EXPECT_NEAR(error_x, columns.at("gyro.gauss_markov_0_si").back() * rad_per_s_in_deg_h,
              1e-5 * std::max(1.0, std::abs(error_x)));
  EXPECT_LE(columns.at("gyro.gauss_markov_error_x_deg_h_sigma").front(), 0.5 + 1e-9);
}

TEST_F(RunCli, RecordingWithoutTruthFlagsAnOverconfidentModelByItsInnovations) {
  // The same recording with a noise model a thousand times too confident: no truth to score
  // against, but the ZUPT innovations leave their predicted 3 sigma and the run says so.
  nlohmann::json config = recording_config();
  config["noise"] = {{"gyro", {{"plugin", "white"}, {"params", {{"N", 5e-6}}}}},
                     {"accel", {{"plugin", "white"}, {"params", {{"N", 3e-5}}}}}};
  const fs::path out = dir_->path() / "out_overconfident";
  const auto result = run_cli("run '" + write_config("overconfident.json", config) + "' --out '" +
                                  out.string() + "' --data '" +
                                  (dir_->path() / "recording").string() + "'",
                              dir_->path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto metrics = nlohmann::json::parse(read(out / "metrics.json"));
  EXPECT_EQ(metrics["self_check"]["source"], "innovations");
  EXPECT_TRUE(metrics["self_check"]["optimistic"].get<bool>()) << metrics["self_check"];
  EXPECT_NE(result.out.find("consistency (innovations, no truth): OPTIMISTIC (zupt innovations"),
            std::string::npos)
      << result.out;
}

TEST_F(RunCli, InitialErrorIsRemovedAndTheRunChecksItself) {
  nlohmann::json config = {
      {"data", {{"scenario", dir_->file("table")}}},
      {"noise", kNoise},
      {"aids",
       {{{"plugin", "static_position"},
         {"params", {{"sigma_position_m", 0.01}, {"sigma_velocity_mps", 0.001}}}}}},
      {"filter", {{"initial_sigma", {{"attitude_deg", {0.3, 0.3, 1.0}}, {"gyro_bias_deg_h", 1}}}}},
      {"initial_error", {{"attitude_deg", {0.3, -0.3, 0.0}}}},
      {"output", {{"decimation", 10}}}};
  const fs::path out = dir_->path() / "out_error";
  const auto result =
      run_cli("run '" + write_config("error.json", config) + "' --out '" + out.string() + "'",
              dir_->path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  // errors.csv: t, 9 errors, 9 sigmas, nees. Inclination error is column 4, its sigma 13.
  std::ifstream errors(out / "errors.csv");
  std::string line;
  std::getline(errors, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(errors, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  ASSERT_GT(rows.size(), 100u);
  constexpr int kInclination = 4, kInclinationSigma = 13;
  EXPECT_GT(std::abs(rows.front()[kInclination]), 0.1) << "the run starts away from truth";
  const auto& last = rows.back();
  EXPECT_LT(std::abs(last[kInclination]), 3.0 * last[kInclinationSigma]);
  EXPECT_LT(std::abs(last[kInclination]), 0.05 * std::abs(rows.front()[kInclination]));
  const auto metrics = nlohmann::json::parse(read(out / "metrics.json"));
  ASSERT_TRUE(metrics["consistency"].is_object());
  EXPECT_GT(metrics["consistency"]["inside_3sigma"]["inclination_err_deg"].get<double>(), 0.9);
  EXPECT_GT(metrics["consistency"]["nees_mean"].get<double>(), 0.0);
  EXPECT_NE(result.out.find("consistency: "), std::string::npos) << result.out;

  // draw_seed: the same seed draws the same start, another seed another.
  config["initial_error"] = {{"draw_seed", 3}};
  const auto nav_of = [&](const std::string& name) {
    const auto run = run_cli("run '" + write_config(name + ".json", config) + "' --out '" +
                                 dir_->file(name) + "' --no-plot",
                             dir_->path());
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return read(dir_->path() / name / "nav.csv");
  };
  const std::string a = nav_of("seed_a");
  EXPECT_EQ(a, nav_of("seed_b"));
  config["initial_error"]["draw_seed"] = 4;
  EXPECT_NE(a, nav_of("seed_c"));
}

// The real ring-laser-gyro record (no truth) through the shipped configs: the alignment's
// heading of the forward axis against the header's 90.6 deg ("maybe inaccurate"), and the
// ZUPT-aided position staying put while the free INS drifts away.
TEST(RunPsins, AlignmentThenZuptOnTheRealRecord) {
  STOCHNAV_REQUIRE_SHARED_DATA(path, "psins/lasergyro.imu");
  const TempDir dir;
  {
    const PsinsImuRecord record = read_psins_imu(path);
    std::ofstream csv(dir.file("imu.csv"));
    csv << "t,dtheta_x,dtheta_y,dtheta_z,dv_x,dv_y,dv_z\n";
    char line[256];
    for (std::size_t k = 0; k < record.increments.size(); ++k) {
      const auto& r = record.increments[k];
      std::snprintf(line, sizeof line, "%.2f,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                    static_cast<double>(k + 1) * record.interval_s, r[0], r[1], r[2], r[3], r[4],
                    r[5]);
      csv << line;
    }
  }
  const auto run = [&](const std::string& name) {
    const auto result = run_cli("run '" + std::string(STOCHNAV_SOURCE_DIR) + "/configs/runs/" +
                                    name + ".json' --data '" + dir.path().string() + "' --out '" +
                                    dir.file(name) + "' --no-plot",
                                dir.path());
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return nlohmann::json::parse(read(dir.path() / name / "metrics.json"));
  };
  // Horizontal distance (m) of nav.csv's last row from the start.
  const auto drift_m = [&](const std::string& name, const nlohmann::json& metrics) {
    const std::string nav = read(dir.path() / name / "nav.csv");
    const std::string last = nav.substr(nav.rfind('\n', nav.size() - 2) + 1);
    std::stringstream cells(last);
    std::vector<double> row;
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0, kR = 6378137.0;
    const double lat0 = metrics["initial"]["latitude_deg"].get<double>();
    const double north = (row[1] - lat0) * kRadPerDeg * kR;
    const double east = (row[2] - metrics["initial"]["longitude_deg"].get<double>()) *
                        kRadPerDeg * kR * std::cos(lat0 * kRadPerDeg);
    return std::hypot(north, east);
  };
  const nlohmann::json zupt = run("psins_zupt");
  const nlohmann::json free = run("psins_free");
  const auto& start = zupt["initial"];
  constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;
  const Eigen::Quaterniond q = quaternion_from_mwd(
      {.inclination_rad = start["inclination_deg"].get<double>() * kRadPerDeg,
       .toolface_rad = start["toolface_deg"].get<double>() * kRadPerDeg,
       .azimuth_rad = start["azimuth_deg"].get<double>() * kRadPerDeg});
  const Eigen::Vector3d forward_n = q * Eigen::Vector3d::UnitY();  // body y = forward
  const double heading = std::atan2(forward_n.x(), forward_n.y()) / kRadPerDeg;
  const double heading_sigma = start["attitude_sigma_deg"][2].get<double>();
  std::printf("PSINS: heading after the 300-s alignment %.2f deg (1-sigma %.2f); position drift "
              "after 1547 s: %.2f m with ZUPT, %.0f m free\n",
              heading, heading_sigma, drift_m("psins_zupt", zupt), drift_m("psins_free", free));
  EXPECT_NEAR(heading, 90.6, 1.0);
  EXPECT_LT(heading_sigma, 0.5);
  EXPECT_LT(drift_m("psins_zupt", zupt), 1.0);
  EXPECT_GT(drift_m("psins_free", free), 50.0);
  EXPECT_EQ(zupt["aids"][0]["rejected_share"], 0.0);
}

struct BadRunCase {
  std::string name;
  std::string config_patch;  // JSON merge-patched into the recording config
  std::string data;          // --data folder under the test folder ("" for none)
  std::string expected;      // must appear in the one-line message
};
void PrintTo(const BadRunCase& c, std::ostream* os) { *os << c.name; }

// A run into a folder that held an earlier run with truth: none of that run's files (its
// errors.csv and errors.png, which a recording does not write) stays beside this run's.
TEST_F(RunCli, ARunReplacesAnEarlierRunsFilesWhole) {
  const fs::path out = dir_->path() / "out_reused";
  fs::create_directories(out);
  for (const char* file : {"errors.csv", "errors.png", "metrics.json", "covariance.csv"}) {
    dir_->write(std::string("out_reused/") + file, "from an earlier run");
  }
  const std::string kept = dir_->write("out_reused/notes.txt", "the user's own file");
  const std::string config = write_config("recording_reused.json", recording_config());
  const auto result = run_cli("run '" + config + "' --out '" + out.string() + "' --data '" +
                                  (dir_->path() / "recording").string() + "' --no-plot",
                              dir_->path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  for (const char* file : {"errors.csv", "errors.png"}) {
    EXPECT_FALSE(fs::exists(out / file)) << file << " of the earlier run stayed";
  }
  for (const char* file : {"metrics.json", "covariance.csv"}) {
    EXPECT_NE(read(out / file), "from an earlier run") << file;
  }
  EXPECT_TRUE(fs::exists(kept)) << "a file no run writes was removed";
}

// Splits a CSV row into its cells.
std::vector<std::string> csv_cells(const std::string& row) {
  std::vector<std::string> cells;
  std::stringstream in(row);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

TEST_F(RunCli, SurveyListingColumnsFollowTheSurveySection) {
  nlohmann::json config = recording_config();
  config["survey"] = {{"vertical_section_azimuth_deg", 90},
                      {"ellipse_confidence", 0.95},
                      {"datum_elevation_m", 30},
                      {"grid_convergence_deg", 1.25},
                      {"well_reference",
                       {{"easting_m", 431000.0}, {"northing_m", 6520000.0},
                        {"scale_factor", 0.9996}}},
                      {"length_unit", "ft"}};
  const fs::path out = dir_->path() / "out_listing";
  const auto result =
      run_cli("run '" + write_config("listing.json", config) + "' --out '" + out.string() +
                  "' --data '" + (dir_->path() / "recording").string() + "' --no-plot",
              dir_->path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::stringstream survey(read(out / "survey.csv"));
  std::string header_line;
  std::getline(survey, header_line);
  // DESIGN.md's columns, the QC's, then the listing's.
  EXPECT_TRUE(header_line.starts_with("t_s,md_m,inclination_deg,azimuth_deg,toolface_deg,tvd_m,"))
      << header_line;
  EXPECT_TRUE(header_line.ends_with(
      ",qc_azimuth_sigmas,qc_flag,dls_deg_30m,build_deg_30m,turn_deg_30m,closure_m,"
      "closure_azimuth_deg,vertical_section_m,ne_m2,nv_m2,ev_m2,ellipse_semi_major_m,"
      "ellipse_semi_minor_m,ellipse_azimuth_deg,tvd_below_datum_m,tvdss_m,azimuth_defined,"
      "gyro_toolface,mc_north_m,mc_east_m,mc_tvd_m,md_sigma_m,station_type,grid_azimuth_deg,"
      "highside_sigma_m,lateral_sigma_m,alonghole_sigma_m,map_easting_m,map_northing_m"))
      << header_line;
  const std::vector<std::string> header = csv_cells(header_line);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(survey, line);) rows.push_back(csv_cells(line));
  ASSERT_GE(rows.size(), 2u);
  const auto cell = [&](std::size_t row, const std::string& name) {
    const auto at = std::find(header.begin(), header.end(), name);
    if (at == header.end() || rows[row].size() != header.size()) {
      ADD_FAILURE() << "no cell " << name << " in row " << row;
      return std::nan("");
    }
    return std::stod(rows[row][static_cast<std::size_t>(at - header.begin())]);
  };
  // The tie-on row first (no rates); after an aligned start the tie-on's attitude is the
  // aligned one, so the first station has rates from it.
  const auto type_of = [&](std::size_t row) {
    const auto at = std::find(header.begin(), header.end(), "station_type");
    return at == header.end() ? std::string()
                              : rows[row][static_cast<std::size_t>(at - header.begin())];
  };
  EXPECT_EQ(type_of(0), "tie_on");
  EXPECT_TRUE(std::isnan(cell(0, "dls_deg_30m")));
  EXPECT_EQ(cell(0, "md_m"), 450.0);
  EXPECT_EQ(cell(0, "north_m"), 0.0);
  EXPECT_GT(cell(0, "north_sigma_m"), 0.0) << "the initial covariance's";
  EXPECT_EQ(type_of(1), "survey");
  // Over a course of at least kMinimumCourseLengthM from the tie-on the first station has rates;
  // a station at the tie-on's depth (the alignment's) has none (survey_listing.hpp).
  const double first_course_m = cell(1, "md_m") - cell(0, "md_m");
  EXPECT_EQ(std::isfinite(cell(1, "dls_deg_30m")), first_course_m >= kMinimumCourseLengthM)
      << first_course_m;
  const std::size_t r = rows.size() - 1;
  // Grid north 1.25 deg east of true; the ellipse in the hole's frame keeps the variances' sum.
  EXPECT_NEAR(cell(r, "grid_azimuth_deg"), std::fmod(cell(r, "azimuth_deg") - 1.25 + 360.0, 360.0),
              1e-6);
  EXPECT_NEAR(std::pow(cell(r, "highside_sigma_m"), 2) + std::pow(cell(r, "lateral_sigma_m"), 2) +
                  std::pow(cell(r, "alonghole_sigma_m"), 2),
              std::pow(cell(r, "north_sigma_m"), 2) + std::pow(cell(r, "east_sigma_m"), 2) +
                  std::pow(cell(r, "tvd_sigma_m"), 2),
              1e-6);
  EXPECT_TRUE(std::isfinite(cell(r, "dls_deg_30m")));
  EXPECT_GE(cell(r, "dls_deg_30m"), 0.0);
  EXPECT_NEAR(cell(r, "closure_m"), std::hypot(cell(r, "north_m"), cell(r, "east_m")), 1e-6);
  EXPECT_NEAR(cell(r, "vertical_section_m"), cell(r, "east_m"), 1e-6);  // azimuth 90: east
  // Datum 30 m above MSL, tie-on height -300 m: 330 m below the datum.
  EXPECT_NEAR(cell(r, "tvd_below_datum_m"), 330.0 + cell(r, "tvd_m"), 1e-5);
  EXPECT_NEAR(cell(r, "tvdss_m"), 300.0 + cell(r, "tvd_m"), 1e-5);
  EXPECT_GE(cell(r, "ellipse_semi_major_m"), cell(r, "ellipse_semi_minor_m"));
  EXPECT_GT(cell(r, "ellipse_semi_minor_m"), 0.0);
  // The 95 % ellipse is 2.4477 sigma: its axes bracket the north and east sigmas scaled so.
  EXPECT_GE(cell(r, "ellipse_semi_major_m") * (1 + 1e-6),
            2.4477 * std::max(cell(r, "north_sigma_m"), cell(r, "east_sigma_m")));
  EXPECT_LE(cell(r, "ellipse_semi_minor_m") * (1 - 1e-6),
            2.4478 * std::min(cell(r, "north_sigma_m"), cell(r, "east_sigma_m")));
  EXPECT_TRUE(std::isfinite(cell(r, "ne_m2")));
  EXPECT_TRUE(std::isfinite(cell(r, "nv_m2")));
  EXPECT_TRUE(std::isfinite(cell(r, "ev_m2")));
  // Map coordinates: the well reference's plus the offsets turned by 1.25 deg, times 0.9996.
  const double g = 1.25 * std::numbers::pi / 180.0;
  EXPECT_EQ(cell(0, "map_easting_m"), 431000.0);
  EXPECT_NEAR(cell(r, "map_easting_m"),
              431000.0 + 0.9996 * (cell(r, "east_m") * std::cos(g) -
                                   cell(r, "north_m") * std::sin(g)),
              1e-3);
  EXPECT_NEAR(cell(r, "map_northing_m"),
              6520000.0 + 0.9996 * (cell(r, "north_m") * std::cos(g) +
                                    cell(r, "east_m") * std::sin(g)),
              1e-3);
  // "length_unit": "ft": survey_ft.csv beside survey.csv, row for row.
  std::stringstream feet(read(out / "survey_ft.csv"));
  std::string feet_header;
  std::getline(feet, feet_header);
  EXPECT_TRUE(feet_header.starts_with("station_type,md_ft,")) << feet_header;
  std::vector<std::string> first_feet_row;
  std::string line;
  std::getline(feet, line);
  first_feet_row = csv_cells(line);
  ASSERT_GE(first_feet_row.size(), 2u);
  EXPECT_EQ(first_feet_row[0], "tie_on");
  EXPECT_NEAR(std::stod(first_feet_row[1]), 450.0 / 0.3048, 1e-4);
}

// The tally reads the bit's depth (450.45 m at the start: 450 m with the scenario's 1e-3 scale
// error, averaged over the static start); a tie-on MD 50 m shallower is refused, naming both
// values, unless the survey sensor sits 50 m behind the bit: then the stations' MDs are the
// tally minus 50 m.
TEST_F(RunCli, TieOnMdIsCheckedAgainstTheTallyTakenToTheSensor) {
  nlohmann::json config = recording_config();
  config["aids"] = {{{"plugin", "zupt"}}, {{"plugin", "pipe_length"}}};
  config["initial_state"]["tie_on"]["measured_depth_m"] = 400;
  const std::string data = (dir_->path() / "recording").string();
  const fs::path refused = dir_->path() / "out_tie_on_refused";
  const auto result = run_cli("run '" + write_config("tie_on_far.json", config) + "' --out '" +
                                  refused.string() + "' --data '" + data + "' --no-plot",
                              dir_->path());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
  EXPECT_NE(result.err.find("/initial_state/tie_on/measured_depth_m: 400 m, but the depth "
                            "data's tally at the start (measured_depth_m, 450.4"),
            std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("/survey/sensor_to_bit_m"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(refused));

  config["survey"] = {{"sensor_to_bit_m", 50}};
  const fs::path out = dir_->path() / "out_sensor_behind_bit";
  const auto accepted =
      run_cli("run '" + write_config("sensor_behind_bit.json", config) + "' --out '" +
                  out.string() + "' --data '" + data + "' --no-plot",
              dir_->path());
  ASSERT_EQ(accepted.exit_code, 0) << accepted.err;
  const auto survey = stochnav::testing::read_csv_columns((out / "survey.csv").string());
  const auto aids = stochnav::testing::read_csv_columns(data + "/aids.csv");
  ASSERT_GE(survey.at("md_m").size(), 3u);
  const auto types =
      stochnav::testing::read_csv_text_column((out / "survey.csv").string(), "station_type");
  ASSERT_EQ(types.size(), survey.at("md_m").size());
  EXPECT_EQ(types.front(), "tie_on");
  EXPECT_EQ(types.back(), "projection_to_bit");
  EXPECT_EQ(survey.at("md_m").front(), 400.0) << "the configured tie-on";
  // The first station, at the end of the static start: the mean tally there, minus 50 m.
  EXPECT_NEAR(survey.at("md_m")[1], aids.at("measured_depth_m").front() - 50.0, 0.2);
  for (std::size_t i = 1; i + 1 < types.size(); ++i) {
    EXPECT_EQ(types[i], "survey");
    EXPECT_GT(survey.at("md_sigma_m")[i], 0.0);
    EXPECT_LT(survey.at("md_sigma_m")[i], 0.06)
        << "the pipe_length aid's 5 cm per reading, and its scale error";
  }
  // The projection to the bit: 50 m beyond the last station.
  const std::size_t last = types.size() - 2;
  EXPECT_NEAR(survey.at("md_m").back(), survey.at("md_m")[last] + 50.0, 1e-5);
}

/// The numbers of an iscwsa_covariance.csv (its six elements per row, rows in order).
std::vector<double> covariance_values(const fs::path& path) {
  std::vector<double> values;
  std::stringstream file(read(path));
  std::string line;
  std::getline(file, line);
  while (std::getline(file, line)) {
    const std::vector<std::string> cells = csv_cells(line);
    for (std::size_t i = 2; i < cells.size(); ++i) values.push_back(std::stod(cells[i]));
  }
  return values;
}

// "survey/error_model": the run writes iscwsa_covariance.csv for its own survey stations (one
// row per station and source, the first survey station the model's tie-on) and the plot beside
// the filter's sigmas. MWD Rev5's TOTAL is positive definite past the tie-on; the gyro model
// GYRO-NS-CT takes its magnitudes from the run's white gyro model, GYRO-MWD has OWSG's.
TEST_F(RunCli, SurveyErrorModelBesideTheFiltersCovariance) {
  const std::string well = dir_->write(
      "run_well.json", R"({"latitude_deg": 46.58, "b_total_nT": 55000, "dip_deg": 65,
        "declination_deg": -9, "convergence_deg": 0, "gravity_m_s2": 9.806,
        "earth_rate_deg_h": 15.041, "vertical_section_azimuth_deg": 0,
        "vertical_inc_limit_deg": 0.0001, "azimuth_reference": "true"})");
  for (const auto& [model, sources] : {std::pair{"mwd_rev5", 36u}, std::pair{"gyro_ns_ct", 20u},
                                       std::pair{"gyro_mwd", 19u}}) {
    nlohmann::json config = recording_config();
    config["survey"] = {{"error_model", model}, {"well", well}};
    const fs::path out = dir_->path() / (std::string("out_error_model_") + model);
    const auto result =
        run_cli("run '" + write_config(std::string("error_model_") + model + ".json", config) +
                    "' --out '" + out.string() + "' --data '" +
                    (dir_->path() / "recording").string() + "'" +
                    (std::string(model) == "mwd_rev5" ? " --no-plot" : ""),
                dir_->path());
    ASSERT_EQ(result.exit_code, 0) << result.err;
    if (std::string(model) == "gyro_ns_ct" && fs::exists(out / "survey.png")) {
      EXPECT_TRUE(fs::exists(out / "survey_uncertainty.png")) << "gnuplot drew survey.png";
    }
    const auto types =
        stochnav::testing::read_csv_text_column((out / "survey.csv").string(), "station_type");
    const auto survey_md =
        stochnav::testing::read_csv_columns((out / "survey.csv").string()).at("md_m");
    std::vector<double> station_md;
    for (std::size_t i = 0; i < types.size(); ++i) {
      if (types[i] == "survey") station_md.push_back(survey_md[i]);
    }
    ASSERT_GE(station_md.size(), 2u);
    std::stringstream file(read(out / "iscwsa_covariance.csv"));
    std::string line;
    std::getline(file, line);
    EXPECT_EQ(line, "md_m,source,nn_m2,ee_m2,vv_m2,ne_m2,nv_m2,ev_m2");
    std::vector<std::vector<std::string>> rows;
    while (std::getline(file, line)) rows.push_back(csv_cells(line));
    ASSERT_EQ(rows.size(), station_md.size() * sources) << model;
    for (std::size_t k = 0; k < station_md.size(); ++k) {
      const std::vector<std::string>& total = rows[(k + 1) * sources - 1];
      ASSERT_EQ(total.size(), 8u);
      EXPECT_EQ(total[1], "TOTAL");
      EXPECT_NEAR(std::stod(total[0]), station_md[k], 1e-6);
      const double nn = std::stod(total[2]), ee = std::stod(total[3]), vv = std::stod(total[4]);
      const double ne = std::stod(total[5]), nv = std::stod(total[6]), ev = std::stod(total[7]);
      if (k == 0) {
        EXPECT_EQ(nn + ee + vv, 0.0) << "the first station is the model's tie-on";
        continue;
      }
      Eigen::Matrix3d p;
      p << nn, ne, nv, ne, ee, ev, nv, ev, vv;
      // Both models' totals (the gyro tool model's with its depth and misalignment terms)
      // are positive definite past the tie-on, with a vertical part.
      EXPECT_EQ(Eigen::LLT<Eigen::Matrix3d>(p).info(), Eigen::Success)
          << model << " TOTAL at MD " << station_md[k] << " not positive definite:\n"
          << p;
      EXPECT_GT(vv, 0.0) << model;
    }
  }
  // The gyro magnitudes came from the run's white gyro model: the same file as from a fitted
  // model with its N (not the OWSG magnitudes': GXY-RN is N / sqrt(60 s) here, not 0.4 deg/h).
  const std::string fit = dir_->write(
      "run_gyro_fit.json",
      R"({"units": "deg/h", "rate_hz": 100, "terms": [{"type": "angle_random_walk", "N": 0.005}]})");
  nlohmann::json config = recording_config();
  config["survey"] = {{"error_model", "gyro_ns_ct"}, {"well", well}, {"noise_model", fit}};
  const fs::path out = dir_->path() / "out_error_model_fit";
  const auto result =
      run_cli("run '" + write_config("error_model_fit.json", config) + "' --out '" + out.string() +
                  "' --data '" + (dir_->path() / "recording").string() + "' --no-plot",
              dir_->path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::vector<double> from_fit = covariance_values(out / "iscwsa_covariance.csv");
  const std::vector<double> from_run_model = covariance_values(
      dir_->path() / "out_error_model_gyro_ns_ct" / "iscwsa_covariance.csv");
  ASSERT_EQ(from_fit.size(), from_run_model.size());
  for (std::size_t i = 0; i < from_fit.size(); ++i) {
    EXPECT_NEAR(from_run_model[i], from_fit[i], 1e-9 * std::abs(from_fit[i]));
  }
  EXPECT_GT(*std::max_element(from_fit.begin(), from_fit.end()), 0.0);
}

class BadRun : public RunCli, public ::testing::WithParamInterface<BadRunCase> {};

TEST_P(BadRun, ExitCodeTwoOneLineNoOutput) {
  const BadRunCase& c = GetParam();
  nlohmann::json config = recording_config();
  config["data"] = {{"imu", dir_->file("recording/imu.csv")}};
  config.merge_patch(nlohmann::json::parse(c.config_patch));
  const std::string path = write_config("bad_" + c.name + ".json", config);
  const fs::path out = dir_->path() / ("out_bad_" + c.name);
  std::string arguments = "run '" + path + "' --out '" + out.string() + "'";
  if (!c.data.empty()) {
    fs::create_directories(dir_->path() / c.data);
    arguments += " --data '" + dir_->file(c.data) + "'";
  }
  const auto result = run_cli(arguments, dir_->path());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  ASSERT_FALSE(result.err.empty());
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
  EXPECT_NE(result.err.find(c.expected), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(out)) << "a failed run left " << out;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadRun,
    ::testing::Values(
        BadRunCase{"no_truth_no_initial_state", R"({"initial_state": null})", "",
                   "/initial_state: missing"},
        BadRunCase{"alignment_not_static", R"({"initial_state": {"alignment": {"static_s": 120}}})",
                   "", "/initial_state/alignment/static_s: the first 120 s are not static"},
        BadRunCase{"data_without_imu", "{}", "empty_recording", "no imu.csv"},
        BadRunCase{"negative_interval", R"({"filter": {"covariance_interval_s": -1}})", "",
                   "/filter/covariance_interval_s"},
        BadRunCase{"fractional_lockout", R"({"filter": {"max_consecutive_rejections": 2.5}})", "",
                   "/filter/max_consecutive_rejections: found 2.5; expected an integer >= 0"},
        BadRunCase{"unknown_filter_key", R"({"filter": {"gate_lockout": 3}})", "",
                   "/filter/gate_lockout: unknown key"},
        BadRunCase{"survey_azimuth_360", R"({"survey": {"vertical_section_azimuth_deg": 360}})", "",
                   "/survey/vertical_section_azimuth_deg: 360"},
        BadRunCase{"survey_azimuth_negative",
                   R"({"survey": {"vertical_section_azimuth_deg": -0.5}})", "",
                   "/survey/vertical_section_azimuth_deg: -0.5"},
        BadRunCase{"survey_confidence_one", R"({"survey": {"ellipse_confidence": 1}})", "",
                   "/survey/ellipse_confidence: 1"},
        BadRunCase{"survey_confidence_zero", R"({"survey": {"ellipse_confidence": 0}})", "",
                   "/survey/ellipse_confidence: 0"},
        BadRunCase{"survey_datum_text", R"({"survey": {"datum_elevation_m": "RKB"}})", "",
                   "/survey/datum_elevation_m"},
        BadRunCase{"survey_datum_far", R"({"survey": {"datum_elevation_m": 20000}})", "",
                   "/survey/datum_elevation_m: 20000"},
        BadRunCase{"survey_tie_on_tvd_without_datum", R"({"survey": {"tie_on_tvd_m": 100}})", "",
                   "/survey/tie_on_tvd_m: given without datum_elevation_m"},
        BadRunCase{"survey_sensor_to_bit_negative", R"({"survey": {"sensor_to_bit_m": -1}})", "",
                   "/survey/sensor_to_bit_m: -1"},
        BadRunCase{"survey_sensor_to_bit_far", R"({"survey": {"sensor_to_bit_m": 250}})", "",
                   "/survey/sensor_to_bit_m: 250"},
        BadRunCase{"survey_tie_on_tolerance_zero", R"({"survey": {"tie_on_md_tolerance_m": 0}})",
                   "", "/survey/tie_on_md_tolerance_m: 0"},
        BadRunCase{"survey_tie_on_tolerance_text",
                   R"({"survey": {"tie_on_md_tolerance_m": "5 m"}})", "",
                   "/survey/tie_on_md_tolerance_m"},
        BadRunCase{"survey_grid_convergence_far", R"({"survey": {"grid_convergence_deg": 12}})", "",
                   "/survey/grid_convergence_deg: 12"},
        BadRunCase{"survey_well_reference_without_convergence",
                   R"({"survey": {"well_reference": {"easting_m": 1, "northing_m": 2}}})", "",
                   "/survey/well_reference: given without grid_convergence_deg"},
        BadRunCase{"survey_well_reference_missing_northing",
                   R"({"survey": {"grid_convergence_deg": 0,
                                  "well_reference": {"easting_m": 1}}})",
                   "", "/survey/well_reference/northing_m: missing"},
        BadRunCase{"survey_well_reference_scale_far",
                   R"({"survey": {"grid_convergence_deg": 0, "well_reference":
                       {"easting_m": 1, "northing_m": 2, "scale_factor": 1.5}}})",
                   "", "/survey/well_reference/scale_factor: 1.5"},
        BadRunCase{"survey_well_reference_not_object",
                   R"({"survey": {"grid_convergence_deg": 0, "well_reference": [1, 2]}})", "",
                   "/survey/well_reference: not an object"},
        BadRunCase{"survey_length_unit_feet", R"({"survey": {"length_unit": "feet"}})", "",
                   "/survey/length_unit: found \"feet\"; expected one of \"m\", \"ft\""},
        BadRunCase{"survey_unknown_key", R"({"survey": {"vs_azimuth_deg": 10}})", "",
                   "/survey/vs_azimuth_deg: unknown key"},
        BadRunCase{"survey_not_object", R"({"survey": 3})", "", "/survey: not an object"},
        BadRunCase{"survey_error_model_typo", R"({"survey": {"error_model": "mwd_rev6"}})", "",
                   "/survey/error_model 'mwd_rev6': unknown survey error model; did you mean"},
        BadRunCase{"survey_mwd_without_well", R"({"survey": {"error_model": "mwd_rev5"}})", "",
                   "/survey/well: missing; \"error_model\": \"mwd_rev5\" needs the well file"},
        BadRunCase{"survey_noise_model_with_mwd",
                   R"({"survey": {"error_model": "none", "noise_model": "fit.json"}})", "",
                   "/survey/noise_model: given with \"error_model\": \"none\""},
        BadRunCase{"survey_well_missing_file",
                   R"({"survey": {"error_model": "gyro_ns_ct", "well": "absent_well.json"}})", "",
                   "/survey/well: file not found"},
        BadRunCase{"survey_gyrocompass_time_zero",
                   R"({"survey": {"error_model": "gyro_ns_ct", "gyrocompass_time_s": 0}})", "",
                   "/survey/gyrocompass_time_s"},
        BadRunCase{"survey_noise_model_with_gyro_ns",
                   R"({"survey": {"error_model": "gyro_ns", "noise_model": "fit.json"}})", "",
                   "/survey/noise_model: given with \"error_model\": \"gyro_ns\"; it applies "
                   "to \"gyro_ns_ct\" only"},
        BadRunCase{"open_loop", R"({"filter": {"feedback": "open_loop"}})", "",
                   "/filter/feedback: found \"open_loop\"; the navigator has one mode"}),
    [](const ::testing::TestParamInfo<BadRunCase>& case_info) { return case_info.param.name; });

}  // namespace
}  // namespace stochnav
