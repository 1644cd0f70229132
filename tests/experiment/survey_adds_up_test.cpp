// Issue #27, "a listing that adds up", end to end on a simulated drilling run with truth: the
// short drilling scenario (configs/scenarios/drilling_short.json: 2 h, through the kickoff into
// the build, with 9.5-m joints and 2-min connections for ten stations) navigated by the shipped
// configs/runs/drilling_build_hold.json. survey.csv carries both solutions of every station:
// the INS filter's (north_m, east_m, tvd_m) and minimum curvature through the listed MD,
// inclination and azimuth (mc_*). Checked:
//   - a client recomputing minimum curvature from survey.csv alone (its tie-on row, then the
//     stations) reproduces mc_* to 1e-6 m; the tie-on row is trajectory.xml's tie-in point;
//   - per station and axis, |INS - MC| <= 3 sigma, sigma = sqrt(sigma_INS^2 + (md_sigma_m
//     t)^2) with t the axis' component of the hole direction: the filter's stated position
//     sigma and the smoothed MD's stated sigma along the hole (minimum curvature's own angle
//     errors are far smaller here);
//   - the check can fail: the same listing with its station MDs read as the raw tally 2 m deep
//     (a deliberate offset against the tie-on) leaves 3 sigma.
// Minimum curvature's error against truth is printed beside the INS's.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <pugixml.hpp>
#include <string>
#include <vector>

#include "client_minimum_curvature.hpp"
#include "csv_columns.hpp"
#include "json_file.hpp"
#include "run_cli.hpp"
#include "temp_dir.hpp"

namespace {

using stochnav::testing::CsvColumns;
using stochnav::testing::ListedPosition;
using stochnav::testing::ListedStation;
using stochnav::testing::read_csv_columns;
using stochnav::testing::read_json;

// Simulates the drilling scenario into `scratch` and runs the shipped run config on it.
// Returns the run folder.
std::string drilling_run(const stochnav::testing::TempDir& scratch) {
  const std::string source = STOCHNAV_SOURCE_DIR;
  nlohmann::json scenario = read_json(source + "/configs/scenarios/drilling_short.json");
  scenario["drilling"]["stand_length_m"] = 9.5;
  scenario["drilling"]["connection_s"] = 120;
  std::ofstream(scratch.file("scenario.json")) << scenario.dump();
  const std::string data = scratch.file("scenario");
  const auto simulated = stochnav::testing::run_cli(
      "simulate scenario '" + scratch.file("scenario.json") + "' --out '" + data + "'",
      scratch.path().string());
  EXPECT_EQ(simulated.exit_code, 0) << simulated.err;
  const std::string run = scratch.file("run");
  const auto result = stochnav::testing::run_cli(
      "run '" + source + "/configs/runs/drilling_build_hold.json' --out '" + run + "' --data '" +
          data + "' --no-plot",
      scratch.path().string());
  EXPECT_EQ(result.exit_code, 0) << result.err;
  return run;
}

// The tie-on as trajectory.xml's tie-in point lists it (MD, inclination, azimuth).
ListedStation listed_tie_on(const std::string& run) {
  pugi::xml_document document;
  EXPECT_TRUE(document.load_file((run + "/trajectory.xml").c_str()));
  const pugi::xml_node tie_in =
      document.child("trajectorys").child("trajectory").child("trajectoryStation");
  EXPECT_EQ(std::string(tie_in.child_value("typeTrajStation")), "tie in point");
  return {std::stod(tie_in.child_value("md")), std::stod(tie_in.child_value("incl")),
          std::stod(tie_in.child_value("azi"))};
}

// survey.csv's rows: the tie-on first (station_type tie_on), then the stations (survey).
ListedStation tie_on_row(const CsvColumns& survey) {
  return {survey.at("md_m")[0], survey.at("inclination_deg")[0], survey.at("azimuth_deg")[0]};
}

// The survey stations' columns only (the rows after the tie-on's).
CsvColumns station_rows(const CsvColumns& survey) {
  CsvColumns stations;
  for (const auto& [name, column] : survey) stations[name].assign(column.begin() + 1, column.end());
  return stations;
}

std::vector<ListedStation> listed_stations(const CsvColumns& survey, double md_offset_m = 0.0) {
  std::vector<ListedStation> stations;
  for (std::size_t i = 0; i < survey.at("md_m").size(); ++i) {
    stations.push_back({survey.at("md_m")[i] + md_offset_m, survey.at("inclination_deg")[i],
                        survey.at("azimuth_deg")[i]});
  }
  return stations;
}

// The largest |INS - MC| over stations and axes in units of the stated sigma (see the top).
double worst_ins_vs_mc_sigmas(const CsvColumns& survey, const std::vector<ListedPosition>& mc) {
  double worst = 0.0;
  for (std::size_t i = 0; i < mc.size(); ++i) {
    const double inclination = survey.at("inclination_deg")[i] * std::numbers::pi / 180.0;
    const double azimuth = survey.at("azimuth_deg")[i] * std::numbers::pi / 180.0;
    const double along_hole[3] = {std::sin(inclination) * std::cos(azimuth),
                                  std::sin(inclination) * std::sin(azimuth), std::cos(inclination)};
    const double ins[3] = {survey.at("north_m")[i], survey.at("east_m")[i], survey.at("tvd_m")[i]};
    const double ins_sigma[3] = {survey.at("north_sigma_m")[i], survey.at("east_sigma_m")[i],
                                 survey.at("tvd_sigma_m")[i]};
    const double minimum_curvature[3] = {mc[i].north_m, mc[i].east_m, mc[i].tvd_m};
    const double md_sigma = survey.at("md_sigma_m")[i];
    for (int axis = 0; axis < 3; ++axis) {
      const double sigma = std::hypot(ins_sigma[axis], md_sigma * along_hole[axis]);
      worst = std::max(worst, std::abs(ins[axis] - minimum_curvature[axis]) / sigma);
    }
  }
  return worst;
}

std::vector<ListedPosition> listed_mc(const CsvColumns& survey) {
  std::vector<ListedPosition> mc;
  for (std::size_t i = 0; i < survey.at("mc_north_m").size(); ++i) {
    mc.push_back({survey.at("mc_north_m")[i], survey.at("mc_east_m")[i], survey.at("mc_tvd_m")[i]});
  }
  return mc;
}

// A client's recomputation from survey.csv's rows reproduces mc_* (m).
double worst_client_difference_m(const ListedStation& tie_on, const CsvColumns& survey) {
  const auto client = stochnav::testing::client_minimum_curvature(tie_on, listed_stations(survey));
  const auto listed = listed_mc(survey);
  double worst_m = 0.0;
  for (std::size_t i = 0; i < client.size(); ++i) {
    worst_m = std::max({worst_m, std::abs(client[i].north_m - listed[i].north_m),
                        std::abs(client[i].east_m - listed[i].east_m),
                        std::abs(client[i].tvd_m - listed[i].tvd_m)});
  }
  std::printf("client recomputation of mc_*: worst difference %.3g m over %zu stations\n", worst_m,
              client.size());
  return worst_m;
}

// One test, one simulated run (ctest runs every test in a process of its own).
TEST(SurveyAddsUp, ClientReproducesTheListingAndInsAgreesWithMinimumCurvature) {
  const stochnav::testing::TempDir scratch;
  const std::string run = drilling_run(scratch);
  const CsvColumns listing = read_csv_columns(run + "/survey.csv");
  const auto types = stochnav::testing::read_csv_text_column(run + "/survey.csv", "station_type");
  ASSERT_GE(types.size(), 4u);
  EXPECT_EQ(types[0], "tie_on");
  for (std::size_t i = 1; i < types.size(); ++i) EXPECT_EQ(types[i], "survey") << i;
  const ListedStation tie_on = tie_on_row(listing);
  const ListedStation tie_in = listed_tie_on(run);
  EXPECT_EQ(tie_on.md_m, tie_in.md_m);
  EXPECT_EQ(tie_on.inclination_deg, tie_in.inclination_deg);
  EXPECT_EQ(tie_on.azimuth_deg, tie_in.azimuth_deg);
  const CsvColumns survey = station_rows(listing);
  const CsvColumns errors = read_csv_columns(run + "/survey_errors.csv");
  const std::size_t stations = survey.at("md_m").size();
  ASSERT_GE(stations, 3u);
  ASSERT_EQ(errors.at("md_m").size(), stations);
  for (std::size_t i = 0; i < stations; ++i) {
    EXPECT_TRUE(std::isfinite(survey.at("md_sigma_m")[i])) << "station " << i;
    EXPECT_GT(survey.at("md_sigma_m")[i], 0.0) << "station " << i;
  }
  EXPECT_LT(worst_client_difference_m(tie_on, survey), 1e-6);

  const std::vector<ListedPosition> mc = listed_mc(survey);
  const double worst = worst_ins_vs_mc_sigmas(survey, mc);
  // Minimum curvature's and the INS's errors against truth (truth = INS - its error).
  double worst_mc_error_m = 0.0, worst_ins_error_m = 0.0;
  for (std::size_t i = 0; i < stations; ++i) {
    const double ins[3] = {survey.at("north_m")[i], survey.at("east_m")[i], survey.at("tvd_m")[i]};
    const double ins_error[3] = {errors.at("north_m")[i], errors.at("east_m")[i],
                                 errors.at("tvd_m")[i]};
    const double minimum_curvature[3] = {mc[i].north_m, mc[i].east_m, mc[i].tvd_m};
    double mc_error_m2 = 0.0, ins_error_m2 = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
      const double truth = ins[axis] - ins_error[axis];
      mc_error_m2 += std::pow(minimum_curvature[axis] - truth, 2);
      ins_error_m2 += ins_error[axis] * ins_error[axis];
    }
    worst_mc_error_m = std::max(worst_mc_error_m, std::sqrt(mc_error_m2));
    worst_ins_error_m = std::max(worst_ins_error_m, std::sqrt(ins_error_m2));
  }
  std::printf(
      "%zu stations to MD %.1f m: worst |INS - MC| %.2f sigma; worst 3-D error against truth: "
      "minimum curvature %.3f m, INS %.3f m\n",
      stations, survey.at("md_m").back(), worst, worst_mc_error_m, worst_ins_error_m);
  EXPECT_LE(worst, 3.0);

  // The check has teeth: station MDs read 2 m deep against the tie-on (the raw tally with an
  // offset) put minimum curvature metres along the hole from the INS.
  const auto offset_mc =
      stochnav::testing::client_minimum_curvature(tie_on, listed_stations(survey, 2.0));
  const double worst_offset = worst_ins_vs_mc_sigmas(survey, offset_mc);
  std::printf("with station MDs 2 m deep: worst |INS - MC| %.1f sigma\n", worst_offset);
  EXPECT_GT(worst_offset, 3.0);
}

}  // namespace
