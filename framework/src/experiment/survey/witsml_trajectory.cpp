#include "stochnav/experiment/witsml_trajectory.hpp"

#include <fmt/format.h>

#include <cmath>
#include <pugixml.hpp>
#include <sstream>

#include "stochnav/version.hpp"

namespace stochnav {
namespace {

constexpr double kMetresPer30m = 30.0;

// A measure element <name uom="...">value</name> (12 significant digits: 0.01 mm at a map
// coordinate of millions of metres); left out when the value is NaN.
void add_measure(pugi::xml_node parent, const char* name, double value, const char* uom) {
  if (std::isnan(value)) return;
  pugi::xml_node node = parent.append_child(name);
  node.append_attribute("uom") = uom;
  node.text().set(fmt::format("{:.12g}", value).c_str());
}

void add_text(pugi::xml_node parent, const char* name, const std::string& text) {
  parent.append_child(name).text().set(text.c_str());
}

struct StationValues {
  std::string type;
  double md_m, tvd_m, incl_deg, azi_deg, gtf_deg, north_m, east_m, vertical_section_m;
  double dls_deg_30m, turn_deg_30m, build_deg_30m, md_delta_m, tvd_delta_m;
  double map_easting_m, map_northing_m;    // NaN without a map reference
  const SurveyStation* station = nullptr;  // null for the tie-in point
};

// The station's tool error model, status and NEV covariance (a measured station or the
// projection to the bit).
void add_station_quality(pugi::xml_node node, const SurveyStation& station) {
  if (station.type == SurveyStationType::kProjectionToBit) {
    // Not a measurement: no status; its covariance is the last station's.
    add_text(node, "modelToolError",
             "stochnav INS filter covariance of the last survey station (1 sigma); the "
             "projection's own error is not included");
  } else {
    add_text(node, "modelToolError", "stochnav INS filter covariance (1 sigma)");
    add_text(node, "statusTrajStation", station.qc.flagged ? "open" : "position");
  }
  const Eigen::Matrix3d& p = station.position_covariance_nev_m2;
  pugi::xml_node cov = node.append_child("matrixCov");
  add_measure(cov, "varianceNN", p(0, 0), "m2");
  add_measure(cov, "varianceNE", p(0, 1), "m2");
  add_measure(cov, "varianceNVert", p(0, 2), "m2");
  add_measure(cov, "varianceEE", p(1, 1), "m2");
  add_measure(cov, "varianceEVert", p(1, 2), "m2");
  add_measure(cov, "varianceVertVert", p(2, 2), "m2");
}

// The station's map coordinates (survey.csv's map_easting_m, map_northing_m) as a location in
// the well reference's projected grid; nothing without a map reference.
void add_map_location(pugi::xml_node node, double easting_m, double northing_m) {
  if (std::isnan(easting_m) || std::isnan(northing_m)) return;
  pugi::xml_node location = node.append_child("location");
  location.append_attribute("uid") = "map";
  add_text(location, "wellCRS", "map grid of the run config's well_reference");
  add_measure(location, "easting", easting_m, "m");
  add_measure(location, "northing", northing_m, "m");
  add_text(location, "description",
           "from dispNs and dispEw by the grid convergence and scale factor (survey.csv)");
}

void add_station(pugi::xml_node trajectory, const std::string& uid, const StationValues& v) {
  pugi::xml_node node = trajectory.append_child("trajectoryStation");
  node.append_attribute("uid") = uid.c_str();
  add_text(node, "typeTrajStation", v.type);
  add_measure(node, "md", v.md_m, "m");
  add_measure(node, "tvd", v.tvd_m, "m");
  add_measure(node, "incl", v.incl_deg, "dega");
  add_measure(node, "azi", v.azi_deg, "dega");
  add_measure(node, "gtf", v.gtf_deg, "dega");
  add_measure(node, "dispNs", v.north_m, "m");
  add_measure(node, "dispEw", v.east_m, "m");
  add_measure(node, "vertSect", v.vertical_section_m, "m");
  add_measure(node, "dls", v.dls_deg_30m / kMetresPer30m, "dega/m");
  add_measure(node, "rateTurn", v.turn_deg_30m / kMetresPer30m, "dega/m");
  add_measure(node, "rateBuild", v.build_deg_30m / kMetresPer30m, "dega/m");
  add_measure(node, "mdDelta", v.md_delta_m, "m");
  add_measure(node, "tvdDelta", v.tvd_delta_m, "m");
  if (v.station != nullptr) add_station_quality(node, *v.station);
  add_map_location(node, v.map_easting_m, v.map_northing_m);
}

}  // namespace

std::string witsml_trajectory_xml(const std::vector<SurveyStation>& stations,
                                  const std::vector<StationListing>& listing,
                                  const SurveyTieOn& tie_on, const SurveyListingOptions& options,
                                  const WitsmlTrajectoryNames& names) {
  const double tvd_origin_m = tie_on_tvd_below_datum_m(tie_on, options).value_or(0.0);
  const double nan = std::nan("");
  const MapCoordinates tie_on_map =
      options.map_reference ? map_coordinates(*options.map_reference,
                                              options.grid_convergence_deg.value_or(0.0), 0.0, 0.0)
                            : MapCoordinates{nan, nan};
  pugi::xml_document document;
  pugi::xml_node declaration = document.append_child(pugi::node_declaration);
  declaration.append_attribute("version") = "1.0";
  declaration.append_attribute("encoding") = "UTF-8";
  pugi::xml_node root = document.append_child("trajectorys");
  root.append_attribute("xmlns") = "http://www.witsml.org/schemas/1series";
  root.append_attribute("version") = "1.4.1.1";
  pugi::xml_node trajectory = root.append_child("trajectory");
  trajectory.append_attribute("uidWell") = names.uid_well.c_str();
  trajectory.append_attribute("uidWellbore") = names.uid_wellbore.c_str();
  trajectory.append_attribute("uid") = names.uid.c_str();
  add_text(trajectory, "nameWell", names.well);
  add_text(trajectory, "nameWellbore", names.wellbore);
  add_text(trajectory, "name", names.trajectory);
  add_measure(trajectory, "mdMn", tie_on.measured_depth_m, "m");
  add_measure(trajectory, "mdMx", stations.empty() ? tie_on.measured_depth_m : stations.back().md_m,
              "m");
  add_measure(trajectory, "aziVertSect", vertical_section_azimuth_deg(stations, tie_on, options),
              "dega");
  add_measure(trajectory, "dispNsVertSectOrig", 0.0, "m");
  add_measure(trajectory, "dispEwVertSectOrig", 0.0, "m");
  add_text(trajectory, "definitive", "false");
  add_text(trajectory, "memory", "true");
  add_text(trajectory, "finalTraj", "true");
  add_text(trajectory, "aziRef", "true north");

  add_station(trajectory, "tie-on",
              {.type = "tie in point",
               .md_m = tie_on.measured_depth_m,
               .tvd_m = tvd_origin_m,
               .incl_deg = tie_on.direction ? tie_on.direction->inclination_deg : nan,
               .azi_deg = tie_on.direction ? tie_on.direction->azimuth_deg : nan,
               .gtf_deg = nan,
               .north_m = 0.0,
               .east_m = 0.0,
               .vertical_section_m = 0.0,
               .dls_deg_30m = nan,
               .turn_deg_30m = nan,
               .build_deg_30m = nan,
               .md_delta_m = nan,
               .tvd_delta_m = nan,
               .map_easting_m = tie_on_map.easting_m,
               .map_northing_m = tie_on_map.northing_m});
  double previous_md = tie_on.measured_depth_m;
  double previous_tvd = 0.0;
  for (std::size_t i = 0; i < stations.size(); ++i) {
    const SurveyStation& s = stations[i];
    const StationListing& row = listing.at(i);
    const bool projection = s.type == SurveyStationType::kProjectionToBit;
    add_station(trajectory, projection ? std::string("projection-to-bit")
                                       : fmt::format("station-{}", i + 1),
                {.type = projection ? "hold to delta-MD" : "gyro inertial",
                 .md_m = s.md_m,
                 .tvd_m = tvd_origin_m + s.tvd_m,
                 .incl_deg = s.inclination_deg,
                 .azi_deg = s.azimuth_deg,
                 .gtf_deg = s.toolface_deg,
                 .north_m = s.north_m,
                 .east_m = s.east_m,
                 .vertical_section_m = row.vertical_section_m,
                 .dls_deg_30m = row.dls_deg_30m,
                 .turn_deg_30m = row.turn_deg_30m,
                 .build_deg_30m = row.build_deg_30m,
                 .md_delta_m = s.md_m - previous_md,
                 .tvd_delta_m = s.tvd_m - previous_tvd,
                 .map_easting_m = row.map_easting_m,
                 .map_northing_m = row.map_northing_m,
                 .station = &s});
    previous_md = s.md_m;
    previous_tvd = s.tvd_m;
  }
  pugi::xml_node common = trajectory.append_child("commonData");
  add_text(common, "comments",
           fmt::format("Written by stochnav {} from the survey stations of a navigation run "
                       "(survey.csv); positions and covariances from the INS filter.",
                       kVersion));
  std::ostringstream out;
  document.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
  return out.str();
}

}  // namespace stochnav
