// End-to-end: `stochnav survey` reproduces ISCWSA example well #1 (Rev5.11 and Rev4) from a
// listing and a well file written from the shared reference data, writing iscwsa_covariance.csv
// with the DESIGN.md columns; every kind of bad input exits 2 with one line saying what, where
// and how to fix it, and leaves no output folder.

#include <gtest/gtest.h>

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
