// trajectory.xml (experiment/witsml_trajectory.hpp): the survey stations as a WITSML 1.4.1.1
// trajectory, read back with an XML parser: the elements in the schema's order, the units, the
// values of survey.csv's columns, the tie-in point first, undefined values left out.

#include "stochnav/experiment/witsml_trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <pugixml.hpp>
#include <string>
#include <vector>

#include "temp_dir.hpp"

namespace stochnav {
namespace {

// The order of WITSML 1.4.1.1's cs_trajectoryStation sequence, restricted to the elements a run
// writes (target, dTimStn, typeSurveyTool, mtf, the magnetic and raw-data elements, location
// and sourceStation are not written; location only with a map reference).
const std::vector<std::string> kStationOrder = {
    "typeTrajStation", "md",      "tvd",       "incl",           "azi",
    "gtf",             "dispNs",  "dispEw",    "vertSect",       "dls",
    "rateTurn",        "rateBuild", "mdDelta", "tvdDelta",       "modelToolError",
    "statusTrajStation", "matrixCov", "location"};
// The order of obj_trajectory's elements the run writes.
const std::vector<std::string> kTrajectoryOrder = {
    "nameWell",   "nameWellbore",       "name",       "mdMn",       "mdMx",
    "aziVertSect", "dispNsVertSectOrig", "dispEwVertSectOrig", "definitive", "memory",
    "finalTraj",  "aziRef",             "trajectoryStation", "commonData"};

// True when the children's names appear in `order`'s order (each may repeat or be absent).
bool in_order(pugi::xml_node parent, const std::vector<std::string>& order) {
  std::size_t position = 0;
  for (pugi::xml_node child : parent.children()) {
    while (position < order.size() && order[position] != child.name()) ++position;
    if (position == order.size()) return false;
  }
  return true;
}

double number(pugi::xml_node node, const char* name) {
  return node.child(name).text().as_double(std::nan(""));
}

struct Listing {
  std::vector<SurveyStation> stations;
  std::vector<StationListing> rows;
  SurveyTieOn tie_on{0.8, 2.2, -300.0, 1000.0};
  SurveyListingOptions options;
};

Listing two_stations() {
  Listing listing;
  listing.options.vertical_section_azimuth_deg = 45.0;
  listing.options.datum_elevation_m = 30.0;
  listing.options.tie_on_tvd_m = 1200.0;
  for (int i = 1; i <= 2; ++i) {
    SurveyStation station;
    station.md_m = 1000.0 + 30.0 * i;
    station.inclination_deg = 10.0 + 3.0 * i;
    station.azimuth_deg = 40.0 + i;
    station.toolface_deg = 90.0;
    station.tvd_m = 29.0 * i;
    station.north_m = 4.0 * i;
    station.east_m = 3.0 * i;
    station.position_covariance_nev_m2 << 0.04, 0.01, 0.002, 0.01, 0.09, 0.003, 0.002, 0.003,
        0.16;
    listing.stations.push_back(station);
  }
  listing.stations[1].qc.flagged = true;
  listing.rows = survey_listing(listing.stations, listing.tie_on, listing.options);
  return listing;
}

TEST(WitsmlTrajectory, StationsInTheSchemasOrderWithSurveyCsvsValues) {
  const Listing listing = two_stations();
  const std::string xml =
      witsml_trajectory_xml(listing.stations, listing.rows, listing.tie_on, listing.options);
  pugi::xml_document document;
  ASSERT_TRUE(document.load_string(xml.c_str())) << xml;
  const pugi::xml_node root = document.child("trajectorys");
  EXPECT_STREQ(root.attribute("xmlns").value(), "http://www.witsml.org/schemas/1series");
  EXPECT_STREQ(root.attribute("version").value(), "1.4.1.1");
  const pugi::xml_node trajectory = root.child("trajectory");
  EXPECT_TRUE(in_order(trajectory, kTrajectoryOrder)) << xml;
  EXPECT_STREQ(trajectory.child("aziRef").text().get(), "true north");
  EXPECT_DOUBLE_EQ(number(trajectory, "aziVertSect"), 45.0);
  EXPECT_DOUBLE_EQ(number(trajectory, "mdMn"), 1000.0);
  EXPECT_DOUBLE_EQ(number(trajectory, "mdMx"), 1060.0);

  std::vector<pugi::xml_node> stations;
  for (pugi::xml_node node : trajectory.children("trajectoryStation")) stations.push_back(node);
  ASSERT_EQ(stations.size(), 3u) << "the tie-in point and two stations";
  EXPECT_STREQ(stations[0].child("typeTrajStation").text().get(), "tie in point");
  EXPECT_DOUBLE_EQ(number(stations[0], "md"), 1000.0);
  EXPECT_DOUBLE_EQ(number(stations[0], "tvd"), 1200.0) << "TVD below the depth datum";
  EXPECT_TRUE(stations[0].child("incl").empty()) << "the tie-on's attitude is not known here";
  for (std::size_t i = 1; i < stations.size(); ++i) {
    SCOPED_TRACE(i);
    const pugi::xml_node station = stations[i];
    const SurveyStation& s = listing.stations[i - 1];
    EXPECT_TRUE(in_order(station, kStationOrder)) << xml;
    EXPECT_STREQ(station.child("typeTrajStation").text().get(), "gyro inertial");
    EXPECT_STREQ(station.child("md").attribute("uom").value(), "m");
    EXPECT_STREQ(station.child("incl").attribute("uom").value(), "dega");
    EXPECT_DOUBLE_EQ(number(station, "md"), s.md_m);
    EXPECT_DOUBLE_EQ(number(station, "tvd"), 1200.0 + s.tvd_m);
    EXPECT_DOUBLE_EQ(number(station, "incl"), s.inclination_deg);
    EXPECT_DOUBLE_EQ(number(station, "dispNs"), s.north_m);
    // Nine significant digits, as survey.csv.
    EXPECT_NEAR(number(station, "vertSect"), listing.rows[i - 1].vertical_section_m, 1e-7);
    EXPECT_DOUBLE_EQ(number(station, "mdDelta"), 30.0);
    const pugi::xml_node cov = station.child("matrixCov");
    EXPECT_DOUBLE_EQ(number(cov, "varianceNE"), 0.01);
    EXPECT_DOUBLE_EQ(number(cov, "varianceVertVert"), 0.16);
  }
  // The first station's rates need the tie-on's direction, unknown here: left out, not NaN.
  EXPECT_TRUE(stations[1].child("dls").empty()) << xml;
  EXPECT_STREQ(stations[2].child("dls").attribute("uom").value(), "dega/m");
  EXPECT_NEAR(number(stations[2], "dls"), listing.rows[1].dls_deg_30m / 30.0, 1e-9);
  EXPECT_STREQ(stations[1].child("statusTrajStation").text().get(), "position");
  EXPECT_STREQ(stations[2].child("statusTrajStation").text().get(), "open")
      << "a station its static QC flags is not validated";
  EXPECT_EQ(xml.find("nan"), std::string::npos) << xml;
}

/// two_stations() with the tie-on's direction known and a projection to the bit 12.5 m ahead.
Listing with_projection_to_bit() {
  Listing listing = two_stations();
  listing.tie_on.direction = SurveyDirection{10.0, 40.0};
  listing.options.sensor_to_bit_m = 12.5;
  listing.stations.push_back(projected_to_bit(listing.stations.back(), 12.5));
  listing.rows = survey_listing(listing.stations, listing.tie_on, listing.options);
  return listing;
}

// With a map reference (the well's grid coordinates and convergence), every station carries
// survey.csv's map_easting_m and map_northing_m as a location in that grid, the tie-in point the
// reference itself; without one, no location.
TEST(WitsmlTrajectory, MapCoordinatesAsEachStationsLocation) {
  Listing listing = with_projection_to_bit();
  listing.options.grid_convergence_deg = 1.5;
  listing.options.map_reference = MapReference{430000.0, 6700000.0, 0.9996};
  listing.rows = survey_listing(listing.stations, listing.tie_on, listing.options);
  const std::string xml =
      witsml_trajectory_xml(listing.stations, listing.rows, listing.tie_on, listing.options);
  pugi::xml_document document;
  ASSERT_TRUE(document.load_string(xml.c_str()));
  std::vector<pugi::xml_node> stations;
  for (pugi::xml_node station :
       document.child("trajectorys").child("trajectory").children("trajectoryStation")) {
    EXPECT_TRUE(in_order(station, kStationOrder)) << station.attribute("uid").value();
    stations.push_back(station);
  }
  ASSERT_EQ(stations.size(), 4u);
  const pugi::xml_node tie_in = stations[0].child("location");
  EXPECT_DOUBLE_EQ(number(tie_in, "easting"), 430000.0);
  EXPECT_DOUBLE_EQ(number(tie_in, "northing"), 6700000.0);
  for (std::size_t i = 1; i < stations.size(); ++i) {
    const pugi::xml_node location = stations[i].child("location");
    ASSERT_FALSE(location.empty()) << i;
    EXPECT_STREQ(location.child("easting").attribute("uom").value(), "m");
    // 12 significant digits: 1e-5 m at millions of metres.
    EXPECT_NEAR(number(location, "easting"), listing.rows[i - 1].map_easting_m, 1e-4) << i;
    EXPECT_NEAR(number(location, "northing"), listing.rows[i - 1].map_northing_m, 1e-4) << i;
    EXPECT_NE(number(location, "easting"), 430000.0) << "the station's, not the reference's";
  }
  const Listing plain = with_projection_to_bit();
  EXPECT_EQ(witsml_trajectory_xml(plain.stations, plain.rows, plain.tie_on, plain.options)
                .find("<location"),
            std::string::npos);
}

// The projection to the bit, the listing's last row, is the trajectory's last station:
// "hold to delta-MD" (WITSML 1.4.1.1's TrajStationType has no "projected" value; this one
// "holds angle, azimuth to a specified delta measured depth"), no status (not a measurement).
TEST(WitsmlTrajectory, ProjectionToTheBitHoldsAngleAndAzimuth) {
  const Listing listing = with_projection_to_bit();
  const std::string xml =
      witsml_trajectory_xml(listing.stations, listing.rows, listing.tie_on, listing.options);
  pugi::xml_document document;
  ASSERT_TRUE(document.load_string(xml.c_str())) << xml;
  const pugi::xml_node trajectory = document.child("trajectorys").child("trajectory");
  std::vector<pugi::xml_node> stations;
  for (pugi::xml_node node : trajectory.children("trajectoryStation")) stations.push_back(node);
  ASSERT_EQ(stations.size(), 4u) << "the tie-in point, two stations, the bit";
  const pugi::xml_node bit = stations.back();
  EXPECT_STREQ(bit.attribute("uid").value(), "projection-to-bit");
  EXPECT_STREQ(bit.child("typeTrajStation").text().get(), "hold to delta-MD");
  EXPECT_TRUE(in_order(bit, kStationOrder)) << xml;
  EXPECT_DOUBLE_EQ(number(bit, "md"), 1072.5);
  EXPECT_DOUBLE_EQ(number(bit, "mdDelta"), 12.5);
  EXPECT_DOUBLE_EQ(number(bit, "incl"), listing.stations[1].inclination_deg);
  EXPECT_NEAR(number(bit, "dls"), 0.0, 1e-12) << "straight ahead";
  EXPECT_TRUE(bit.child("statusTrajStation").empty());
  EXPECT_DOUBLE_EQ(number(trajectory, "mdMx"), 1072.5);
  EXPECT_STREQ(stations[1].child("typeTrajStation").text().get(), "gyro inertial");
}

// Against the WITSML 1.4.1.1 XSD (Energistics' obj_trajectory.xsd, in its folder tree: it
// imports ../../abstract_v1.0). The schema is under the Energistics licence and not in this
// repository: STOCHNAV_WITSML_XSD names the file (docs/navigation.md says where to get it);
// without it, or without xmllint (Debian libxml2-utils), the test is skipped.
TEST(WitsmlTrajectory, ValidatesAgainstTheWitsml1411Schema) {
  const char* schema = std::getenv("STOCHNAV_WITSML_XSD");
  if (schema == nullptr || !std::filesystem::is_regular_file(schema)) {
    GTEST_SKIP() << "STOCHNAV_WITSML_XSD does not name the WITSML 1.4.1.1 obj_trajectory.xsd "
                    "(not redistributed here; docs/navigation.md, trajectory.xml)";
  }
  if (std::system("command -v xmllint > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "no xmllint (Debian package libxml2-utils)";
  }
  const testing::TempDir dir;
  Listing listing = with_projection_to_bit();
  listing.stations[0].qc.flagged = true;  // one "open" station
  listing.options.grid_convergence_deg = 1.5;  // with map coordinates (locations)
  listing.options.map_reference = MapReference{430000.0, 6700000.0, 0.9996};
  listing.rows = survey_listing(listing.stations, listing.tie_on, listing.options);
  const std::string document = dir.write(
      "trajectory.xml",
      witsml_trajectory_xml(listing.stations, listing.rows, listing.tie_on, listing.options));
  // And a listing without datum, tie-on direction or projection (the optional elements left
  // out).
  const Listing plain = two_stations();
  SurveyListingOptions no_datum = plain.options;
  no_datum.datum_elevation_m.reset();
  no_datum.tie_on_tvd_m.reset();
  const std::string plain_document = dir.write(
      "plain.xml", witsml_trajectory_xml(plain.stations, plain.rows, plain.tie_on, no_datum));
  for (const std::string& path : {document, plain_document}) {
    const std::string log = dir.file("xmllint.log");
    const std::string command = "xmllint --noout --schema '" + std::string(schema) + "' '" +
                                path + "' > '" + log + "' 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    const std::string output((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
    EXPECT_EQ(status, 0) << output;
    EXPECT_NE(output.find("validates"), std::string::npos) << output;
  }
}

}  // namespace
}  // namespace stochnav
