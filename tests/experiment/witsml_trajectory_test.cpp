// trajectory.xml (experiment/witsml_trajectory.hpp): the survey stations as a WITSML 1.4.1.1
// trajectory, read back with an XML parser: the elements in the schema's order, the units, the
// values of survey.csv's columns, the tie-in point first, undefined values left out.

#include "stochnav/experiment/witsml_trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <pugixml.hpp>
#include <string>
#include <vector>

namespace stochnav {
namespace {

// The order of WITSML 1.4.1.1's cs_trajectoryStation sequence, restricted to the elements a run
// writes (target, dTimStn, typeSurveyTool, mtf, the magnetic and raw-data elements, location
// and sourceStation are not written).
const std::vector<std::string> kStationOrder = {
    "typeTrajStation", "md",      "tvd",       "incl",           "azi",
    "gtf",             "dispNs",  "dispEw",    "vertSect",       "dls",
    "rateTurn",        "rateBuild", "mdDelta", "tvdDelta",       "modelToolError",
    "statusTrajStation", "matrixCov"};
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
    EXPECT_STREQ(station.child("typeTrajStation").text().get(), "MD INCL and AZI");
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

}  // namespace
}  // namespace stochnav
