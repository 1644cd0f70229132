#pragma once
// survey.png of experiment/survey.hpp: plan view and vertical section of a survey.

#include <filesystem>
#include <vector>

#include "stochnav/experiment/survey.hpp"
#include "stochnav/io/atomic_file.hpp"

namespace stochnav {

/// Draws the INS path, the minimum-curvature stations (one point per station, as
/// minimum_curvature_path returns them) and their 2-sigma position uncertainty, magnified so it
/// can be seen on a km-long path, into `output`'s temporary file (.png or .svg from its final
/// path; committing is the caller's). Throws ConfigError when gnuplot is not installed and
/// InputError when it fails. Nothing is drawn when the recorder saw no epoch.
void plot_survey(const SurveyRecorder& recorder,
                 const std::vector<WellPathPoint>& minimum_curvature_stations,
                 PendingFile& output);

/// The factor (1, 2 or 5 times a power of ten, at least 1) that makes the largest ellipse's
/// major axis about `target_fraction` of the plot's extent (largest of the east and north
/// spans), never more. 1 when either length is not positive.
double ellipse_magnification(double largest_major_axis_m, double plot_extent_m,
                             double target_fraction = 0.03);

}  // namespace stochnav
