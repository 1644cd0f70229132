// write_survey_files of experiment/survey.hpp: survey.csv, trajectory.xml (WITSML),
// survey_errors.csv, well_path.csv and survey.png, each complete in a temporary file, committed
// by the caller.

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <span>
#include <string>
#include <string_view>

#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/survey.hpp"
#include "stochnav/experiment/survey_error_files.hpp"
#include "stochnav/experiment/survey_listing.hpp"
#include "stochnav/experiment/witsml_trajectory.hpp"
#include "stochnav/report/gnuplot.hpp"
#include "survey/survey_plot.hpp"

namespace stochnav {
namespace {

/// DESIGN.md's survey.csv columns; survey_errors.csv uses the same.
constexpr std::string_view kSurveyHeader =
    "t_s,md_m,inclination_deg,azimuth_deg,toolface_deg,tvd_m,north_m,east_m,"
    "inclination_sigma_deg,azimuth_sigma_deg,north_sigma_m,east_sigma_m,tvd_sigma_m,"
    // The station QC (experiment/station_qc.hpp), after DESIGN.md's columns.
    "qc_static_s,qc_inclination_deg,qc_inclination_sigma_deg,qc_azimuth_deg,"
    "qc_azimuth_sigma_deg,qc_gravity_total_m_s2,qc_gravity_model_m_s2,qc_gravity_sigma_m_s2,"
    "qc_earth_rate_total_deg_h,qc_earth_rate_sigma_deg_h,qc_inclination_sigmas,"
    "qc_azimuth_sigmas,qc_flag";
/// The listing's columns (experiment/survey_listing.hpp), after the QC's in survey.csv only.
constexpr std::string_view kListingHeader =
    ",dls_deg_30m,build_deg_30m,turn_deg_30m,closure_m,closure_azimuth_deg,vertical_section_m,"
    "ne_m2,nv_m2,ev_m2,ellipse_semi_major_m,ellipse_semi_minor_m,ellipse_azimuth_deg,"
    "tvd_below_datum_m,tvdss_m,azimuth_defined,gyro_toolface,"
    // The listing that adds up (issue #27): minimum curvature through the listed stations beside
    // the INS positions, and the smoothed MD's sigma.
    "mc_north_m,mc_east_m,mc_tvd_m,md_sigma_m,"
    // What the row is (experiment/survey.hpp): tie_on | survey | projection_to_bit.
    "station_type,"
    // Grid north and the ellipse in the hole's frame (experiment/survey_listing.hpp).
    "grid_azimuth_deg,highside_sigma_m,lateral_sigma_m,alonghole_sigma_m,"
    // Map coordinates from the well reference's (experiment/survey_listing.hpp).
    "map_easting_m,map_northing_m";
/// survey_ft.csv: survey.csv's rows in international feet (write_survey_files).
constexpr std::string_view kFeetListingHeader =
    "station_type,md_ft,inclination_deg,azimuth_deg,grid_azimuth_deg,tvd_ft,"
    "tvd_below_datum_ft,tvdss_ft,north_ft,east_ft,vertical_section_ft,dls_deg_100ft,"
    "build_deg_100ft,turn_deg_100ft,closure_ft,closure_azimuth_deg,mc_north_ft,mc_east_ft,"
    "mc_tvd_ft,north_sigma_ft,east_sigma_ft,tvd_sigma_ft,ellipse_semi_major_ft,"
    "ellipse_semi_minor_ft,ellipse_azimuth_deg,md_sigma_ft";
constexpr double kMetresPerFoot = 0.3048;  ///< the international foot (exact)
/// A rate per 30 m to the same rate per 100 ft.
constexpr double kPer30mToPer100ft = 100.0 * kMetresPerFoot / 30.0;
constexpr std::string_view kWellPathHeader = "source,md_m,north_m,east_m,tvd_m";

/// A CSV number: 9 significant digits (0.01 mm at 1 km, 1 ms at 200 h); any NaN as "nan" (the
/// sign bit of a NaN from sqrt of a rounding-negative variance would otherwise print "-nan").
std::string csv_number(double value) {
  if (std::isnan(value)) return "nan";
  return fmt::format("{:.9g}", value);
}

/// A length (m) with 6 decimals (to the micrometre); NaN as "nan".
std::string csv_micrometres(double metres) {
  if (std::isnan(metres)) return "nan";
  return fmt::format("{:.6f}", metres);
}

/// The value as survey.csv lists it (csv_number's 9 significant digits, read back).
double as_listed(double value) { return std::strtod(csv_number(value).c_str(), nullptr); }

/// The stations with md_m, inclination and azimuth as listed: the derived columns (rates,
/// minimum curvature) are computed from the printed numbers, so that a client recomputing them
/// from survey.csv gets the same values whatever the well's length.
std::vector<SurveyStation> as_listed(std::vector<SurveyStation> stations) {
  for (SurveyStation& s : stations) {
    s.md_m = as_listed(s.md_m);
    s.inclination_deg = as_listed(s.inclination_deg);
    s.azimuth_deg = as_listed(s.azimuth_deg);
  }
  return stations;
}

SurveyStation as_listed(SurveyStation station) {
  return std::move(as_listed(std::vector<SurveyStation>{std::move(station)}).front());
}

SurveyTieOn as_listed(SurveyTieOn tie_on) {
  tie_on.measured_depth_m = as_listed(tie_on.measured_depth_m);
  if (tie_on.direction) {
    tie_on.direction->inclination_deg = as_listed(tie_on.direction->inclination_deg);
    tie_on.direction->azimuth_deg = as_listed(tie_on.direction->azimuth_deg);
  }
  return tie_on;
}

void append_cells(std::string& csv, std::span<const double> cells, bool leading_comma) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0 || leading_comma) csv += ',';
    csv += csv_number(cells[i]);
  }
}

/// The stations' rows; with `listing` (one per station) its columns after the QC's.
std::string stations_csv(const std::vector<SurveyStation>& stations,
                         const std::vector<StationListing>* listing = nullptr) {
  std::string csv = std::string(kSurveyHeader);
  if (listing != nullptr) csv += kListingHeader;
  csv += '\n';
  for (std::size_t row = 0; row < stations.size(); ++row) {
    const SurveyStation& s = stations[row];
    const double columns[] = {s.t_s,
                              s.md_m,
                              s.inclination_deg,
                              s.azimuth_deg,
                              s.toolface_deg,
                              s.tvd_m,
                              s.north_m,
                              s.east_m,
                              s.inclination_sigma_deg,
                              s.azimuth_sigma_deg,
                              s.north_sigma_m,
                              s.east_sigma_m,
                              s.tvd_sigma_m,
                              s.qc.static_duration_s,
                              s.qc.static_inclination_deg,
                              s.qc.static_inclination_sigma_deg,
                              s.qc.gyrocompass_azimuth_deg,
                              s.qc.gyrocompass_azimuth_sigma_deg,
                              s.qc.gravity_total_m_s2,
                              s.qc.gravity_model_m_s2,
                              s.qc.gravity_sigma_m_s2,
                              s.qc.earth_rate_total_deg_h,
                              s.qc.earth_rate_sigma_deg_h,
                              s.qc.inclination_difference_sigmas,
                              s.qc.azimuth_difference_sigmas,
                              s.qc.checked ? (s.qc.flagged ? 1.0 : 0.0) : std::nan("")};
    append_cells(csv, columns, false);
    if (listing != nullptr) {
      const StationListing& l = (*listing)[row];
      const double listing_columns[] = {l.dls_deg_30m,
                                        l.build_deg_30m,
                                        l.turn_deg_30m,
                                        l.closure_m,
                                        l.closure_azimuth_deg,
                                        l.vertical_section_m,
                                        l.ne_m2,
                                        l.nv_m2,
                                        l.ev_m2,
                                        l.ellipse_semi_major_m,
                                        l.ellipse_semi_minor_m,
                                        l.ellipse_azimuth_deg,
                                        l.tvd_below_datum_m,
                                        l.tvdss_m,
                                        l.azimuth_defined,
                                        l.gyro_toolface};
      append_cells(csv, listing_columns, true);
      // Micrometres, whatever the well's size: a client's recomputation compares to 1e-6 m.
      for (double metres : {l.mc_north_m, l.mc_east_m, l.mc_tvd_m}) {
        csv += ',' + csv_micrometres(metres);
      }
      append_cells(csv, std::span<const double>(&s.md_sigma_m, 1), true);
      csv += ',';
      csv += station_type_name(s.type);
      const double hole_frame_columns[] = {l.grid_azimuth_deg, l.highside_sigma_m,
                                           l.lateral_sigma_m, l.alonghole_sigma_m};
      append_cells(csv, hole_frame_columns, true);
      // Map coordinates are millions of metres: fixed decimals, not 9 significant digits.
      for (double metres : {l.map_easting_m, l.map_northing_m}) {
        csv += ',' + csv_micrometres(metres);
      }
    }
    csv += '\n';
  }
  return csv;
}

/// survey_ft.csv: the rows of survey.csv (`stations`, `listing` parallel) in feet.
std::string feet_listing_csv(const std::vector<SurveyStation>& stations,
                             const std::vector<StationListing>& listing) {
  std::string csv = std::string(kFeetListingHeader) + '\n';
  const auto ft = [](double metres) { return metres / kMetresPerFoot; };
  for (std::size_t row = 0; row < stations.size(); ++row) {
    const SurveyStation& s = stations[row];
    const StationListing& l = listing[row];
    csv += station_type_name(s.type);
    const double columns[] = {ft(s.md_m),
                              s.inclination_deg,
                              s.azimuth_deg,
                              l.grid_azimuth_deg,
                              ft(s.tvd_m),
                              ft(l.tvd_below_datum_m),
                              ft(l.tvdss_m),
                              ft(s.north_m),
                              ft(s.east_m),
                              ft(l.vertical_section_m),
                              l.dls_deg_30m * kPer30mToPer100ft,
                              l.build_deg_30m * kPer30mToPer100ft,
                              l.turn_deg_30m * kPer30mToPer100ft,
                              ft(l.closure_m),
                              l.closure_azimuth_deg};
    append_cells(csv, columns, true);
    for (double metres : {l.mc_north_m, l.mc_east_m, l.mc_tvd_m}) {
      csv += ',' + csv_micrometres(ft(metres));
    }
    const double uncertainty_columns[] = {ft(s.north_sigma_m),
                                          ft(s.east_sigma_m),
                                          ft(s.tvd_sigma_m),
                                          ft(l.ellipse_semi_major_m),
                                          ft(l.ellipse_semi_minor_m),
                                          l.ellipse_azimuth_deg,
                                          ft(s.md_sigma_m)};
    append_cells(csv, uncertainty_columns, true);
    csv += '\n';
  }
  return csv;
}

void append_well_path_rows(std::string& csv, std::string_view source,
                           const std::vector<WellPathPoint>& points) {
  for (const WellPathPoint& p : points) {
    csv += fmt::format("{},{},{},{},{}\n", source, csv_number(p.md_m), csv_number(p.north_m),
                       csv_number(p.east_m), csv_number(p.tvd_m));
  }
}

std::string well_path_csv(const std::vector<WellPathPoint>& minimum_curvature_stations,
                          const std::vector<WellPathPoint>& ins_path,
                          const std::vector<WellPathPoint>& truth_path, double tie_on_md_m) {
  std::string csv = std::string(kWellPathHeader) + '\n';
  append_well_path_rows(csv, "minimum_curvature", {{tie_on_md_m, 0.0, 0.0, 0.0}});
  append_well_path_rows(csv, "minimum_curvature", minimum_curvature_stations);
  append_well_path_rows(csv, "ins", ins_path);
  append_well_path_rows(csv, "truth", truth_path);
  return csv;
}

std::unique_ptr<PendingFile> pending_text_file(const std::filesystem::path& path,
                                               std::string_view content) {
  auto pending = std::make_unique<PendingFile>(path);
  write_pending_file(*pending, content);
  return pending;
}

/// survey.png rendered into a PendingFile, or null when gnuplot is not installed (the plot is
/// optional; the numbers are complete without it).
std::unique_ptr<PendingFile> pending_survey_plot(const SurveyPlotData& data,
                                                 const std::filesystem::path& path) {
  if (data.ins_path.empty()) return nullptr;
  try {
    check_plot_request(path);
  } catch (const ConfigError&) {
    return nullptr;
  }
  auto pending = std::make_unique<PendingFile>(path);
  plot_survey(data, *pending);
  return pending;
}

}  // namespace

std::vector<std::unique_ptr<PendingFile>> write_survey_files(
    const SurveyRecorder& recorder, const SurveyTieOn& recorded_tie_on,
    const std::filesystem::path& out_dir, bool plot, const SurveyListingOptions& options,
    const SurveyErrorModelRequest* error_model) {
  const std::vector<SurveyStation> stations = as_listed(recorder.stations());
  const SurveyTieOn tie_on = as_listed(recorded_tie_on);
  const std::vector<WellPathPoint> minimum_curvature_stations =
      minimum_curvature_path(stations, tie_on.measured_depth_m, tie_on.direction);
  // One vertical-section azimuth for every row and trajectory.xml: the survey stations' (a
  // projection to the bit does not move it).
  SurveyListingOptions listing = options;
  listing.vertical_section_azimuth_deg = vertical_section_azimuth_deg(stations, tie_on, options);
  std::vector<std::unique_ptr<PendingFile>> files;
  // survey.csv's rows: the tie-on, the stations, the projection to the bit.
  std::vector<SurveyStation> rows = {as_listed(recorder.tie_on_station())};
  rows.insert(rows.end(), stations.begin(), stations.end());
  if (listing.sensor_to_bit_m > 0.0 && !stations.empty()) {
    rows.push_back(as_listed(projected_to_bit(stations.back(), listing.sensor_to_bit_m)));
  }
  const std::vector<SurveyStation> listed_after_tie_on(rows.begin() + 1, rows.end());
  const std::vector<StationListing> station_rows =
      survey_listing(listed_after_tie_on, tie_on, listing);
  std::vector<StationListing> listing_rows = {
      tie_on_listing(rows.front(), listed_after_tie_on, tie_on, listing)};
  listing_rows.insert(listing_rows.end(), station_rows.begin(), station_rows.end());
  files.push_back(pending_text_file(out_dir / "survey.csv", stations_csv(rows, &listing_rows)));
  if (listing.length_unit == SurveyLengthUnit::kFoot) {
    files.push_back(
        pending_text_file(out_dir / "survey_ft.csv", feet_listing_csv(rows, listing_rows)));
  }
  // The tie-in point, the stations and the projection to the bit.
  files.push_back(
      pending_text_file(out_dir / "trajectory.xml",
                        witsml_trajectory_xml(listed_after_tie_on, station_rows, tie_on, listing)));
  if (!recorder.station_errors().empty()) {
    files.push_back(
        pending_text_file(out_dir / "survey_errors.csv", stations_csv(recorder.station_errors())));
  }
  const std::vector<WellPathPoint> truth_path = recorder.truth_path();
  files.push_back(pending_text_file(out_dir / "well_path.csv",
                                    well_path_csv(minimum_curvature_stations, recorder.ins_path(),
                                                  truth_path, tie_on.measured_depth_m)));
  if (plot) {
    const SurveyPlotData plot_data{recorder.ins_path(), truth_path, recorder.stations(),
                                   minimum_curvature_stations,
                                   *listing.vertical_section_azimuth_deg};
    if (auto picture = pending_survey_plot(plot_data, out_dir / "survey.png")) {
      files.push_back(std::move(picture));
    }
  }
  if (error_model != nullptr) {
    for (auto& file : write_survey_error_files(*error_model, stations, out_dir, plot)) {
      files.push_back(std::move(file));
    }
  }
  return files;
}

}  // namespace stochnav
