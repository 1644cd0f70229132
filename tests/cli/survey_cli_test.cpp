// End-to-end: `stochnav survey` reproduces ISCWSA example well #1 (Rev5.11 and Rev4) from a
// listing and a well file written from the shared reference data, writing iscwsa_covariance.csv
// with the DESIGN.md columns; every kind of bad input exits 2 with one line saying what, where
// and how to fix it, and leaves no output folder.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "iscwsa_reference.hpp"
#include "run_cli.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::run_cli;
using testing::TempDir;

/// The well file of ISCWSA example well #1 (the reference header, in degrees).
nlohmann::json example_well_json() {
  return {{"latitude_deg", 60.0},
          {"b_total_nT", 50000.0},
          {"dip_deg", 72.0},
          {"declination_deg", -4.0},
          {"convergence_deg", 0.0},
          {"gravity_m_s2", 9.80665},
          {"earth_rate_deg_h", 15.041},
          {"vertical_section_azimuth_deg", 0.0},
          {"vertical_inc_limit_deg", 1e-4},
          {"azimuth_reference", "true"}};
}

/// The reference's stations as a listing, with an extra text column (allowed, ignored).
std::string example_listing_csv(const testing::IscwsaReference& reference) {
  std::ostringstream out;
  out.precision(17);
  out << "station_type,md_m,inclination_deg,azimuth_deg\n";
  for (std::size_t k = 0; k < reference.md_m.size(); ++k) {
    out << (k == 0 ? "tie-on" : "survey") << ',' << reference.md_m[k] << ','
        << reference.inclination_deg[k] << ',' << reference.azimuth_deg[k] << '\n';
  }
  return out.str();
}

/// iscwsa_covariance.csv keyed by (md, source): the six elements in file order.
struct SurveyCovarianceFile {
  std::string header;
  std::map<std::pair<double, std::string>, std::vector<double>> rows;
  std::size_t row_count = 0;
};

// `stochnav survey` on a listing and a well file, into `out`, from the folder `dir`.
testing::CliResult run_survey(const TempDir& dir, const std::string& listing,
                              const std::string& well, const std::string& model,
                              const std::string& out) {
  return run_cli("survey --listing '" + listing + "' --well '" + well + "' --model " + model +
                     " --out '" + out + "'",
                 dir.path().string());
}

SurveyCovarianceFile read_survey_covariance_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  SurveyCovarianceFile file;
  std::getline(in, file.header);
  for (std::string line; std::getline(in, line);) {
    std::stringstream row(line);
    std::string md, source, cell;
    std::getline(row, md, ',');
    std::getline(row, source, ',');
    std::vector<double> values;
    while (std::getline(row, cell, ',')) values.push_back(std::stod(cell));
    file.rows[{std::stod(md), source}] = values;
    ++file.row_count;
  }
  return file;
}

struct SurveyModelCase {
  const char* model;
  const char* reference_file;
  double atol;
  double rtol;
  std::size_t sources_with_total;
};

class SurveyCliExample : public ::testing::TestWithParam<SurveyModelCase> {};

TEST_P(SurveyCliExample, ReproducesTheIscwsaExampleWell) {
  const SurveyModelCase& c = GetParam();
  STOCHNAV_REQUIRE_SHARED_DATA(path, c.reference_file);
  const auto reference = testing::read_iscwsa_reference(path, c.atol, c.rtol);
  TempDir dir;
  const std::string listing = dir.write("listing.csv", example_listing_csv(reference));
  const std::string well = dir.write("well.json", example_well_json().dump(2));
  const auto out = dir.path() / "out";
  const auto result = run_survey(dir, listing, well, c.model, out.string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("iscwsa_covariance.csv"), std::string::npos) << result.out;

  const auto file = read_survey_covariance_file(out / "iscwsa_covariance.csv");
  EXPECT_EQ(file.header, "md_m,source,nn_m2,ee_m2,vv_m2,ne_m2,nv_m2,ev_m2");
  EXPECT_EQ(file.row_count, reference.md_m.size() * c.sources_with_total);
  int failures = 0;
  for (const auto& expected : reference.rows) {
    const auto found = file.rows.find({expected.md_m, expected.source});
    ASSERT_NE(found, file.rows.end()) << expected.source << " at MD " << expected.md_m;
    ASSERT_EQ(found->second.size(), 6u);
    const double wanted[6] = {expected.nn, expected.ee, expected.vv,
                              expected.ne, expected.nv, expected.ev};
    for (int i = 0; i < 6; ++i) {
      if (!reference.passes(found->second[static_cast<std::size_t>(i)], wanted[i])) {
        ++failures;
        ADD_FAILURE() << expected.source << " at MD " << expected.md_m << " element " << i << ": "
                      << found->second[static_cast<std::size_t>(i)] << " vs " << wanted[i];
      }
    }
  }
  EXPECT_EQ(failures, 0);
}

INSTANTIATE_TEST_SUITE_P(
    Models, SurveyCliExample,
    ::testing::Values(SurveyModelCase{"mwd_rev5", testing::kIscwsaRev5File, 1e-6, 5e-5, 36},
                      SurveyModelCase{"mwd_rev4", testing::kIscwsaRev4File, 5e-5, 1e-3, 28}),
    [](const ::testing::TestParamInfo<SurveyModelCase>& case_info) {
      return std::string(case_info.param.model);
    });

// ---------------------------------------------------------------------------------------------
// Bad input.

constexpr char kSurveyGoodListing[] =
    "md_m,inclination_deg,azimuth_deg\n0,0,0\n30,0,0\n60,1,45\n90,2,45\n";

struct SurveyBadInputCase {
  std::string name;
  std::string listing;  ///< listing.csv
  nlohmann::json well;  ///< well.json (dumped), or a string: the file's raw text
  std::string model;
  std::string expected_fragment;  ///< must appear in the one-line message
};

void PrintTo(const SurveyBadInputCase& c, std::ostream* os) { *os << c.name; }

nlohmann::json well_with(const std::string& key, const nlohmann::json& value) {
  nlohmann::json well = example_well_json();
  well[key] = value;
  return well;
}

nlohmann::json well_without(const std::string& key) {
  nlohmann::json well = example_well_json();
  well.erase(key);
  return well;
}

class SurveyBadInput : public ::testing::TestWithParam<SurveyBadInputCase> {};

TEST_P(SurveyBadInput, ExitCodeTwoOneLineNoOutputFolder) {
  const SurveyBadInputCase& c = GetParam();
  TempDir dir;
  const std::string listing = dir.write("listing.csv", c.listing);
  const std::string well =
      dir.write("well.json", c.well.is_string() ? c.well.get<std::string>() : c.well.dump(2));
  const auto out = dir.path() / "out";
  const auto result = run_survey(dir, listing, well, c.model, out.string());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  ASSERT_FALSE(result.err.empty());
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
  EXPECT_EQ(result.err.rfind("stochnav: error: ", 0), 0u) << result.err;
  EXPECT_NE(result.err.find(c.expected_fragment), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(out)) << "a failed run left " << out;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SurveyBadInput,
    ::testing::Values(
        SurveyBadInputCase{"unknown_key", kSurveyGoodListing, well_with("colour", "red"),
                           "mwd_rev5", "well.json: /colour: unknown key"},
        SurveyBadInputCase{"typo_key", kSurveyGoodListing,
                           [] {
                             nlohmann::json w = well_without("dip_deg");
                             w["dip_dge"] = 72.0;
                             return w;
                           }(),
                           "mwd_rev5", "/dip_dge: unknown key 'dip_dge'; did you mean 'dip_deg'?"},
        SurveyBadInputCase{"wrong_type", kSurveyGoodListing, well_with("dip_deg", "72"), "mwd_rev5",
                           "well.json: /dip_deg: found \"72\"; expected a number"},
        SurveyBadInputCase{"missing_key", kSurveyGoodListing, well_without("gravity_m_s2"),
                           "mwd_rev5", "well.json: /gravity_m_s2: missing; expected a number > 0"},
        SurveyBadInputCase{"dip_out_of_range", kSurveyGoodListing, well_with("dip_deg", 90.0),
                           "mwd_rev5", "/dip_deg: found 90.0; expected a number in (-90, 90) (deg)"},
        SurveyBadInputCase{"unknown_reference", kSurveyGoodListing,
                           well_with("azimuth_reference", "magnetic"), "mwd_rev5",
                           "/azimuth_reference: found \"magnetic\"; expected \"true\" or \"grid\""},
        SurveyBadInputCase{"nan_in_well", kSurveyGoodListing,
                           nlohmann::json("{\"latitude_deg\": NaN}"), "mwd_rev5", "well.json"},
        SurveyBadInputCase{"not_json", kSurveyGoodListing, nlohmann::json("{latitude_deg: 60"),
                           "mwd_rev5", "well.json"},
        SurveyBadInputCase{
            "md_not_increasing", "md_m,inclination_deg,azimuth_deg\n0,0,0\n30,0,0\n30,1,45\n",
            example_well_json(), "mwd_rev5", "listing.csv:4: md_m 30 does not increase"},
        SurveyBadInputCase{"one_station", "md_m,inclination_deg,azimuth_deg\n0,0,0\n",
                           example_well_json(), "mwd_rev5",
                           "1 station(s); the error model needs "
                           "at least two"},
        SurveyBadInputCase{"no_stations", "md_m,inclination_deg,azimuth_deg\n", example_well_json(),
                           "mwd_rev5", "0 station(s)"},
        SurveyBadInputCase{"inclination_above_180",
                           "md_m,inclination_deg,azimuth_deg\n0,0,0\n30,181,0\n",
                           example_well_json(), "mwd_rev5",
                           "listing.csv:3: inclination_deg 181 is outside [0, 180]"},
        SurveyBadInputCase{"negative_inclination",
                           "md_m,inclination_deg,azimuth_deg\n0,0,0\n30,-1,0\n",
                           example_well_json(), "mwd_rev5", "listing.csv:3: inclination_deg -1"},
        SurveyBadInputCase{"azimuth_360", "md_m,inclination_deg,azimuth_deg\n0,0,0\n30,5,360\n",
                           example_well_json(), "mwd_rev5",
                           "listing.csv:3: azimuth_deg 360 is outside [0, 360)"},
        SurveyBadInputCase{"nan_in_listing", "md_m,inclination_deg,azimuth_deg\n0,0,0\n30,nan,10\n",
                           example_well_json(), "mwd_rev5",
                           "listing.csv:3: column inclination_deg is NaN"},
        SurveyBadInputCase{"text_in_listing",
                           "md_m,inclination_deg,azimuth_deg\n0,0,0\n30,five,10\n",
                           example_well_json(), "mwd_rev5",
                           "listing.csv:3: column inclination_deg is not a number"},
        SurveyBadInputCase{"missing_column", "md_m,inclination_deg\n0,0\n30,1\n",
                           example_well_json(), "mwd_rev5", "no column 'azimuth_deg'"},
        SurveyBadInputCase{"short_row", "md_m,inclination_deg,azimuth_deg\n0,0,0\n30,1\n",
                           example_well_json(), "mwd_rev5", "listing.csv:3: 2 cells for 3"},
        SurveyBadInputCase{"unknown_model", kSurveyGoodListing, example_well_json(), "mwd_rev9",
                           "--model 'mwd_rev9': unknown survey error model; did you mean"},
        SurveyBadInputCase{"other_model", kSurveyGoodListing, example_well_json(), "gyro",
                           "--model 'gyro': unknown survey error model; use mwd_rev5"},
        SurveyBadInputCase{
            "tie_on_below_surface", "md_m,inclination_deg,azimuth_deg\n500,0,0\n530,1,10\n",
            example_well_json(), "mwd_rev5", "well.json: /tie_on_tvd_m: missing, and"}),
    [](const ::testing::TestParamInfo<SurveyBadInputCase>& case_info) {
      return case_info.param.name;
    });

TEST(SurveyCli, TieOnBelowTheSurfaceWithItsTvdRuns) {
  TempDir dir;
  const std::string listing =
      dir.write("listing.csv", "md_m,inclination_deg,azimuth_deg\n500,0,0\n530,1,10\n560,2,10\n");
  const std::string well = dir.write("well.json", well_with("tie_on_tvd_m", 499.5).dump());
  const auto out = dir.path() / "out";
  const auto result = run_survey(dir, listing, well, "mwd_rev4", out.string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto file = read_survey_covariance_file(out / "iscwsa_covariance.csv");
  EXPECT_EQ(file.row_count, 3u * 28u);
  EXPECT_EQ(file.rows.at({500.0, "TOTAL"}), std::vector<double>(6, 0.0)) << "the tie-on is exact";
  EXPECT_GT(file.rows.at({560.0, "TOTAL"})[0], 0.0);
}

// A run's survey.csv: its tie_on row (at the depth of its first station, 1 mm deeper here) and
// its projection_to_bit are not stations; the first survey station is the tie-on.
TEST(SurveyCli, RunListingTieOnAndProjectionRowsAreSkipped) {
  TempDir dir;
  const std::string listing = dir.write(
      "survey.csv",
      "md_m,inclination_deg,azimuth_deg,station_type\n500.001,0,0,tie_on\n500,0,0,survey\n"
      "530,1,10,survey\n560,2,10,survey\n572.5,2,10,projection_to_bit\n");
  const std::string well = dir.write("well.json", well_with("tie_on_tvd_m", 499.5).dump());
  const auto out = dir.path() / "out";
  const auto result = run_survey(dir, listing, well, "mwd_rev4", out.string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto file = read_survey_covariance_file(out / "iscwsa_covariance.csv");
  EXPECT_EQ(file.row_count, 3u * 28u);
  EXPECT_EQ(file.rows.at({500.0, "TOTAL"}), std::vector<double>(6, 0.0)) << "the tie-on is exact";
  EXPECT_EQ(file.rows.count({572.5, "TOTAL"}), 0u);
}

// ---------------------------------------------------------------------------------------------
// --model gyro_ns_ct: the OWSG gyro tool model GYRO-NS-CT.

/// Vertical to 300 m, a build of 3 deg / 30 m at azimuth 45 deg to 45 deg, a hold to 1200 m:
/// gyrocompass stations to 15 deg, continuous from there.
std::string gyro_listing_csv() {
  std::ostringstream out;
  out << "md_m,inclination_deg,azimuth_deg\n";
  for (int md = 0; md <= 1200; md += 30) {
    const double inclination = std::clamp((md - 300) / 10.0, 0.0, 45.0);
    out << md << ',' << inclination << ',' << (inclination > 0 ? 45 : 0) << '\n';
  }
  return out.str();
}

constexpr std::size_t kGyroListingStations = 41;
const std::vector<std::string> kGyroSources = {
    "DRFR",   "DSFS",   "DSTG",     "XYM1",    "XYM2",    "XYM3E",   "XYM4E",
    "XCLA",   "XCLH",   "AXYZ-MIS", "AXYZ-SF", "AXYZ-ZB", "GXY-B1S", "GXY-B2S",
    "GXY-G4", "GXY-RN", "GXY-GD",   "GXY-GRW", "SAGE",    "TOTAL"};

TEST(SurveyCliGyro, OwsgMagnitudesFromAListing) {
  TempDir dir;
  const std::string listing = dir.write("listing.csv", gyro_listing_csv());
  const std::string well = dir.write("well.json", example_well_json().dump());
  const auto out = dir.path() / "out";
  const auto result = run_survey(dir, listing, well, "gyro_ns_ct", out.string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("GXY-RN 0.4 deg/h, GXY-GD 0.5 deg/h, GXY-GRW 0.25 deg/sqrt(h)"),
            std::string::npos)
      << result.out;
  const auto file = read_survey_covariance_file(out / "iscwsa_covariance.csv");
  EXPECT_EQ(file.header, "md_m,source,nn_m2,ee_m2,vv_m2,ne_m2,nv_m2,ev_m2");
  ASSERT_EQ(file.row_count, kGyroListingStations * kGyroSources.size());
  for (int md = 0; md <= 1200; md += 30) {
    std::vector<double> sum(6, 0.0);
    for (std::size_t s = 0; s + 1 < kGyroSources.size(); ++s) {
      const auto& row = file.rows.at({md, kGyroSources[s]});
      for (std::size_t i = 0; i < 6; ++i) sum[i] += row[i];
    }
    const auto& total = file.rows.at({md, "TOTAL"});
    for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(total[i], sum[i], 1e-12 * (1 + total[0]));
    // The depth terms give every station past the tie-on a vertical part.
    if (md > 0) {
      EXPECT_GT(total[2], 0.0) << "VV at MD " << md;
    }
    // The gyro terms are azimuth errors: horizontal only.
    EXPECT_EQ(file.rows.at({md, "GXY-B1S"})[2], 0.0) << "VV at MD " << md;
  }
  EXPECT_GT(file.rows.at({1200.0, "TOTAL"})[0], 0.0);
  EXPECT_GT(file.rows.at({1200.0, "GXY-GD"})[1], 0.0) << "the continuous survey drifts";
  EXPECT_EQ(file.rows.at({300.0, "GXY-GD"})[1], 0.0) << "a gyrocompass station does not";
}

// A noise model whose mapping gives exactly the OWSG magnitudes (N = 0.25 deg/sqrt(h) is
// GXY-GRW; N / sqrt(T) = 0.4 deg/h at T = 1406.25 s; 0.664 B = 0.5 deg/h) reproduces the OWSG
// file; as written by `stochnav fit`, with the coefficients' sigmas.
TEST(SurveyCliGyro, NoiseModelMappedToTheMagnitudes) {
  TempDir dir;
  const std::string listing = dir.write("listing.csv", gyro_listing_csv());
  const std::string well = dir.write("well.json", example_well_json().dump());
  const double b = 0.5 / std::sqrt(2.0 * std::log(2.0) / M_PI);
  const nlohmann::json fit = {
      {"units", "deg/h"},
      {"rate_hz", 100},
      {"terms",
       {{{"type", "angle_random_walk"}, {"N", 0.25}, {"N_sigma", 0.001}},
        {{"type", "bias_instability"}, {"B", b}, {"B_sigma", nullptr}},
        {{"type", "sinusoid"}, {"amplitude", 0.1}, {"frequency_hz", 2}}}}};
  const std::string noise_model = dir.write("fit.json", fit.dump());
  const auto owsg = run_survey(dir, listing, well, "gyro_ns_ct", (dir.path() / "owsg").string());
  ASSERT_EQ(owsg.exit_code, 0) << owsg.err;
  const auto mapped = run_survey(
      dir, listing, well,
      "gyro_ns_ct --noise-model '" + noise_model + "' --gyrocompass-time-s 1406.25",
      (dir.path() / "mapped").string());
  ASSERT_EQ(mapped.exit_code, 0) << mapped.err;
  EXPECT_NE(mapped.out.find("ignored sinusoid"), std::string::npos) << mapped.out;
  const auto expected = read_survey_covariance_file(dir.path() / "owsg" / "iscwsa_covariance.csv");
  const auto found = read_survey_covariance_file(dir.path() / "mapped" / "iscwsa_covariance.csv");
  ASSERT_EQ(found.row_count, expected.row_count);
  for (const auto& [key, values] : expected.rows) {
    for (std::size_t i = 0; i < 6; ++i) {
      EXPECT_NEAR(found.rows.at(key)[i], values[i], 1e-9 * (1e-9 + std::abs(values[i])))
          << key.second << " at MD " << key.first;
    }
  }
  // A slower run drifts longer between stations: GXY-GD grows as 1 / speed.
  const auto slow = run_survey(dir, listing, well,
                               "gyro_ns_ct --noise-model '" + noise_model +
                                   "' --gyrocompass-time-s 1406.25 --running-speed-m-h 1371.6",
                               (dir.path() / "slow").string());
  ASSERT_EQ(slow.exit_code, 0) << slow.err;
  const auto slow_file = read_survey_covariance_file(dir.path() / "slow" / "iscwsa_covariance.csv");
  EXPECT_NEAR(slow_file.rows.at({1200.0, "GXY-GD"})[0],
              4.0 * expected.rows.at({1200.0, "GXY-GD"})[0],
              1e-9 * expected.rows.at({1200.0, "GXY-GD"})[0]);
}

// --model gyro_ns and gyro_mwd: the OWSG stationary gyro tool models GYRO-NS and GYRO-MWD.

const std::vector<std::string> kStationaryGyroSources = {
    "DRFR",     "DSFS",    "DSTG",    "SAGE",    "XYM1",    "XYM2",   "XYM3E",
    "XYM4E",    "XCLA",    "XCLH",    "AXYZ-MIS", "AXYZ-SF", "AXYZ-ZB", "GXY-B1R",
    "GXY-B2R",  "GXY-G1",  "GXY-G4",  "GXY-RN",  "TOTAL"};

TEST(SurveyCliStationaryGyro, GyroNsAndGyroMwdFromAListing) {
  TempDir dir;
  const std::string listing = dir.write("listing.csv", gyro_listing_csv());
  const std::string well = dir.write("well.json", example_well_json().dump());
  std::map<std::string, SurveyCovarianceFile> files;
  for (const auto& [model, title] : {std::pair{"gyro_ns", "OWSG GYRO-NS (rev 5): 41 stations x 18 "
                                                          "sources"},
                                     std::pair{"gyro_mwd", "OWSG GYRO-MWD (rev 5): 41 stations "
                                                           "x 18 sources"}}) {
    const auto out = dir.path() / model;
    const auto result = run_survey(dir, listing, well, model, out.string());
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find(title), std::string::npos) << result.out;
    const auto file = read_survey_covariance_file(out / "iscwsa_covariance.csv");
    ASSERT_EQ(file.row_count, kGyroListingStations * kStationaryGyroSources.size()) << model;
    for (int md = 0; md <= 1200; md += 30) {
      std::vector<double> sum(6, 0.0);
      for (std::size_t s = 0; s + 1 < kStationaryGyroSources.size(); ++s) {
        const auto& row = file.rows.at({md, kStationaryGyroSources[s]});
        for (std::size_t i = 0; i < 6; ++i) sum[i] += row[i];
      }
      const auto& total = file.rows.at({md, "TOTAL"});
      for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(total[i], sum[i], 1e-12 * (1 + total[0]));
      if (md > 0) {
        EXPECT_GT(total[2], 0.0) << model << " VV at MD " << md;
      }
      EXPECT_EQ(file.rows.at({md, "GXY-RN"})[2], 0.0) << "an azimuth error: horizontal only";
    }
    files.emplace(model, file);
  }
  // GYRO-MWD's rate noise is 0.6 deg/h against GYRO-NS's 0.4; their biases are the same.
  const double ns_noise = files.at("gyro_ns").rows.at({1200.0, "GXY-RN"})[0];
  EXPECT_GT(ns_noise, 0.0);
  EXPECT_NEAR(files.at("gyro_mwd").rows.at({1200.0, "GXY-RN"})[0], 2.25 * ns_noise,
              1e-12 * ns_noise);
  EXPECT_EQ(files.at("gyro_mwd").rows.at({1200.0, "GXY-B1R"}),
            files.at("gyro_ns").rows.at({1200.0, "GXY-B1R"}));
}

TEST(SurveyCliStationaryGyro, AStationAtNinetyDegreesExitsTwo) {
  TempDir dir;
  const std::string listing = dir.write(
      "listing.csv", "md_m,inclination_deg,azimuth_deg\n0,0,0\n30,45,10\n60,90,10\n");
  const std::string well = dir.write("well.json", example_well_json().dump());
  const auto out = dir.path() / "out";
  const auto result = run_survey(dir, listing, well, "gyro_ns", out.string());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
  EXPECT_NE(result.err.find("listing.csv: "), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("at 90 deg inclination"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

struct SurveyGyroBadInputCase {
  std::string name;
  std::string model_and_options;  ///< after --model; FIT stands for the noise model file's path
  nlohmann::json noise_model;     ///< fit.json's content
  nlohmann::json well;
  std::string expected_fragment;
};

void PrintTo(const SurveyGyroBadInputCase& c, std::ostream* os) { *os << c.name; }

const nlohmann::json kGoodGyroFit = {
    {"units", "deg/h"}, {"rate_hz", 100}, {"terms", {{{"type", "angle_random_walk"}, {"N", 0.1}}}}};

class SurveyGyroBadInput : public ::testing::TestWithParam<SurveyGyroBadInputCase> {};

TEST_P(SurveyGyroBadInput, ExitCodeTwoOneLineNoOutputFolder) {
  const SurveyGyroBadInputCase& c = GetParam();
  TempDir dir;
  const std::string listing = dir.write("listing.csv", gyro_listing_csv());
  const std::string well = dir.write("well.json", c.well.dump());
  const std::string fit = dir.write("fit.json", c.noise_model.dump());
  std::string model = c.model_and_options;
  if (const auto at = model.find("FIT"); at != std::string::npos) {
    model.replace(at, 3, "'" + fit + "'");
  }
  const auto out = dir.path() / "out";
  const auto result = run_survey(dir, listing, well, model, out.string());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  ASSERT_FALSE(result.err.empty());
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
  EXPECT_NE(result.err.find(c.expected_fragment), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(out)) << "a failed run left " << out;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SurveyGyroBadInput,
    ::testing::Values(
        SurveyGyroBadInputCase{"noise_model_with_mwd", "mwd_rev5 --noise-model FIT", kGoodGyroFit,
                               example_well_json(),
                               "--noise-model applies to --model gyro_ns_ct only"},
        SurveyGyroBadInputCase{"speed_with_mwd", "mwd_rev4 --running-speed-m-h 1000",
                               kGoodGyroFit, example_well_json(),
                               "--running-speed-m-h applies to --model gyro_ns_ct only"},
        SurveyGyroBadInputCase{"time_without_noise_model", "gyro_ns_ct --gyrocompass-time-s 60",
                               kGoodGyroFit, example_well_json(),
                               "--gyrocompass-time-s maps a noise model"},
        SurveyGyroBadInputCase{"time_zero", "gyro_ns_ct --noise-model FIT --gyrocompass-time-s 0",
                               kGoodGyroFit, example_well_json(), "--gyrocompass-time-s"},
        SurveyGyroBadInputCase{"speed_negative", "gyro_ns_ct --running-speed-m-h -5", kGoodGyroFit,
                               example_well_json(), "--running-speed-m-h"},
        SurveyGyroBadInputCase{"accelerometer_model", "gyro_ns_ct --noise-model FIT",
                               {{"units", "m/s^2"},
                                {"rate_hz", 100},
                                {"terms", {{{"type", "angle_random_walk"}, {"N", 0.1}}}}},
                               example_well_json(),
                               "fit.json: /units: found \"m/s^2\"; expected a gyro rate unit"},
        SurveyGyroBadInputCase{"negative_coefficient", "gyro_ns_ct --noise-model FIT",
                               {{"units", "deg/h"},
                                {"rate_hz", 100},
                                {"terms", {{{"type", "angle_random_walk"}, {"N", -0.1}}}}},
                               example_well_json(), "fit.json: /terms/0/N"},
        SurveyGyroBadInputCase{"noise_model_not_an_object", "gyro_ns_ct --noise-model FIT",
                               "{not json", example_well_json(), "fit.json"},
        SurveyGyroBadInputCase{"no_earth_rate", "gyro_ns_ct", kGoodGyroFit,
                               well_with("earth_rate_deg_h", 0.0),
                               "well.json: /earth_rate_deg_h: 0; the gyro model gyrocompasses"},
        SurveyGyroBadInputCase{"at_the_pole", "gyro_ns_ct", kGoodGyroFit,
                               well_with("latitude_deg", 90.0),
                               "well.json: /latitude_deg: 90; a gyrocompass cannot"},
        SurveyGyroBadInputCase{"typo_model", "gyro_ns_tc", kGoodGyroFit, example_well_json(),
                               "--model 'gyro_ns_tc': unknown survey error model; did you mean "
                               "'gyro_ns_ct'?"},
        SurveyGyroBadInputCase{"typo_stationary_model", "gyro_mdw", kGoodGyroFit,
                               example_well_json(),
                               "--model 'gyro_mdw': unknown survey error model; did you mean "
                               "'gyro_mwd'?"},
        SurveyGyroBadInputCase{"unknown_model_lists_the_models", "sperry_xyz", kGoodGyroFit,
                               example_well_json(),
                               "use mwd_rev5 (ISCWSA MWD Rev5.11), mwd_rev4 (ISCWSA MWD Rev4), "
                               "gyro_ns_ct, gyro_ns or gyro_mwd"},
        SurveyGyroBadInputCase{"noise_model_with_gyro_ns", "gyro_ns --noise-model FIT",
                               kGoodGyroFit, example_well_json(),
                               "--noise-model applies to --model gyro_ns_ct only"},
        SurveyGyroBadInputCase{"speed_with_gyro_mwd", "gyro_mwd --running-speed-m-h 1000",
                               kGoodGyroFit, example_well_json(),
                               "--running-speed-m-h applies to --model gyro_ns_ct only"},
        SurveyGyroBadInputCase{"gyro_ns_no_earth_rate", "gyro_ns", kGoodGyroFit,
                               well_with("earth_rate_deg_h", 0.0),
                               "well.json: /earth_rate_deg_h: 0; the gyro model gyrocompasses"},
        SurveyGyroBadInputCase{"gyro_mwd_at_the_pole", "gyro_mwd", kGoodGyroFit,
                               well_with("latitude_deg", -90.0),
                               "well.json: /latitude_deg: -90; a gyrocompass cannot"}),
    [](const ::testing::TestParamInfo<SurveyGyroBadInputCase>& case_info) {
      return case_info.param.name;
    });

TEST(SurveyCli, MissingListingFileNamesIt) {
  TempDir dir;
  const std::string well = dir.write("well.json", example_well_json().dump());
  const auto result = run_survey(dir, dir.file("absent.csv"), well, "mwd_rev5", dir.file("out"));
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("absent.csv: cannot open"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out"));
}

}  // namespace
}  // namespace stochnav
