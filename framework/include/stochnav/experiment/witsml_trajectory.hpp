#pragma once
// trajectory.xml of a navigation run: the survey stations as a WITSML 1.4.1.1 `trajectory`
// (namespace http://www.witsml.org/schemas/1series), the exchange format of the drilling
// industry's data stores, beside survey.csv.
//
// One `trajectorys` document holding one `trajectory` (uidWell, uidWellbore, uid attributes;
// nameWell, nameWellbore, name; mdMn, mdMx; aziVertSect and its origin, the tie-on; definitive
// false, memory true, finalTraj true; aziRef "true north") whose first trajectoryStation is the
// tie-on ("tie in point": its MD, TVD, zero displacement, its inclination and azimuth when
// known), then one station per survey station ("gyro inertial": WITSML 1.4.1.1's
// TrajStationType has no measured "MD INCL and AZI" -- that value came with 2.0 -- its values
// are planned sections and, marked deprecated but valid, the survey tool kinds; an INS survey
// is an inertial gyro's), then the projection to the
// bit when the listing has one (a station of type kProjectionToBit: "hold to delta-MD", the
// schema's TrajStationType for a section that "holds angle, azimuth to a specified delta
// measured depth" -- WITSML 1.4.1.1 has no "projection" value; uid "projection-to-bit", no
// statusTrajStation, its matrixCov the last station's as in survey.csv), elements in the
// schema's order:
//   md, tvd (m)               MD; TVD below the depth datum when the run has one (survey
//                             "datum_elevation_m"), else below the tie-on
//   incl, azi, gtf (dega)     inclination, azimuth from true north, high-side toolface
//   dispNs, dispEw, vertSect  north, east from the tie-on, vertical section (m)
//   dls, rateTurn, rateBuild  dega/m (survey.csv's deg/30 m over 30); left out where undefined
//   mdDelta, tvdDelta (m)     from the previous station
//   modelToolError            "stochnav INS filter covariance (1 sigma)"
//   statusTrajStation         "position" when the station's static QC passes, "open" (not
//                             validated) when it flags the station (experiment/station_qc.hpp)
//   matrixCov                 varianceNN, NE, NVert, EE, EVert, VertVert (m2; vertical down)
// Numbers are written with 9 significant digits; a value that is NaN is left out (its element
// is optional in the schema).

#include <string>
#include <vector>

#include "stochnav/experiment/survey.hpp"
#include "stochnav/experiment/survey_listing.hpp"

namespace stochnav {

/// The names and identifiers the trajectory carries (WITSML uids: any non-empty string).
struct WitsmlTrajectoryNames {
  std::string well = "well";
  std::string wellbore = "wellbore";
  std::string trajectory = "stochnav INS survey";
  std::string uid_well = "well";
  std::string uid_wellbore = "wellbore";
  std::string uid = "stochnav-trajectory";
};

/// The document of survey.csv's rows after the tie-on (the survey stations, then the
/// projection to the bit if any): `listing` is survey_listing(stations, tie_on, options) (one
/// row per station), `options` the listing's references (the VS azimuth and the depth datum).
///
/// Checked against the WITSML 1.4.1.1 XSD (obj_trajectory.xsd, Energistics) by
/// tests/experiment/witsml_trajectory_test.cpp when STOCHNAV_WITSML_XSD names it (the schema
/// is not redistributed here: docs/navigation.md says where to get it).
std::string witsml_trajectory_xml(const std::vector<SurveyStation>& stations,
                                  const std::vector<StationListing>& listing,
                                  const SurveyTieOn& tie_on, const SurveyListingOptions& options,
                                  const WitsmlTrajectoryNames& names = {});

}  // namespace stochnav
