#pragma once
// survey.png of experiment/survey.hpp: plan view and vertical section of a survey.

#include <string>
#include <vector>

#include "stochnav/experiment/survey.hpp"
#include "stochnav/io/atomic_file.hpp"

namespace stochnav {

/// What survey.png draws, all in the tie-on frame (north, east, TVD down; m).
struct SurveyPlotData {
  std::vector<WellPathPoint> ins_path;    ///< the INS path (SurveyRecorder::ins_path)
  std::vector<WellPathPoint> truth_path;  ///< the true path; empty without truth
  std::vector<SurveyStation> stations;    ///< the survey stations (their covariances)
  /// One per station: where the station is drawn (minimum_curvature_path).
  std::vector<WellPathPoint> minimum_curvature_stations;
  /// The vertical section's azimuth (deg from true north): the listing's.
  double vertical_section_azimuth_deg = 0.0;
};

/// The plan view's ranges (m). With `equal_scales` the plot keeps east and north at one scale
/// (gnuplot `set size ratio -1`); without, each axis spans its own data: a long straight hole
/// (the smaller span under kEqualScaleRatio of the larger) would otherwise be a few pixels
/// wide. Each range is the data's span plus 5 % on either side, at least kMinimumPlanSpan_m.
struct PlanViewAxes {
  double east_min_m = 0.0;
  double east_max_m = 0.0;
  double north_min_m = 0.0;
  double north_max_m = 0.0;
  bool equal_scales = true;
};
inline constexpr double kEqualScaleRatio = 0.2;
inline constexpr double kMinimumPlanSpan_m = 1.0;

/// The plan view's axes for the points of the INS path, the truth path, the stations and their
/// 2-sigma ellipses at true size. With equal scales the ellipses are then magnified
/// (ellipse_magnification against the plan's extent; they may reach past the ranges); with
/// independent scales they are drawn at true size (magnification 1).
PlanViewAxes plan_view_axes(const SurveyPlotData& data);

/// The gnuplot script of survey.png (no terminal or output line): datablocks $ins, $truth
/// (when there is truth), $stations and $ellipses, then a two-panel multiplot: the plan view
/// with plan_view_axes' ranges and the vertical section along the listing's azimuth, the truth
/// path drawn in both when given.
std::string survey_plot_script(const SurveyPlotData& data);

/// Draws survey_plot_script(data) into `output`'s temporary file (.png or .svg from its final
/// path; committing is the caller's). Throws ConfigError when gnuplot is not installed and
/// InputError when it fails. Nothing is drawn when the INS path is empty.
void plot_survey(const SurveyPlotData& data, PendingFile& output);

/// The factor (1, 2 or 5 times a power of ten, at least 1) that makes the largest ellipse's
/// major axis about `target_fraction` of the plot's extent (largest of the east and north
/// spans), never more. 1 when either length is not positive.
double ellipse_magnification(double largest_major_axis_m, double plot_extent_m,
                             double target_fraction = 0.03);

}  // namespace stochnav
