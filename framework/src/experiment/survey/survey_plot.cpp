#include "survey/survey_plot.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>

#include "stochnav/core/angles.hpp"
#include "stochnav/report/gnuplot.hpp"

namespace stochnav {
namespace {

/// The ellipses and error bars are drawn at 2 sigma.
constexpr double kSigmaScale = 2.0;
constexpr int kEllipseSegments = 72;

/// Semi-axes of the 2-sigma ellipse of a horizontal covariance [[NN, NE], [NE, EE]] (m^2), as
/// (north, east) vectors: the eigenvectors scaled by 2 sqrt(eigenvalue).
struct EllipseAxes {
  Eigen::Vector2d major_ne = Eigen::Vector2d::Zero();
  Eigen::Vector2d minor_ne = Eigen::Vector2d::Zero();
};

EllipseAxes two_sigma_axes(const Eigen::Matrix2d& covariance_ne_m2) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(covariance_ne_m2);
  // Eigenvalues come in increasing order; rounding may leave a tiny negative one.
  const auto semi_axis = [&](int k) {
    return kSigmaScale * std::sqrt(std::max(solver.eigenvalues()(k), 0.0)) *
           solver.eigenvectors().col(k);
  };
  return {semi_axis(1), semi_axis(0)};
}

/// The east and north bounds of every point of the plan view.
struct PlanBounds {
  double east_min = std::numeric_limits<double>::infinity();
  double east_max = -std::numeric_limits<double>::infinity();
  double north_min = std::numeric_limits<double>::infinity();
  double north_max = -std::numeric_limits<double>::infinity();
  void add(const std::vector<WellPathPoint>& points) {
    for (const WellPathPoint& p : points) {
      east_min = std::min(east_min, p.east_m);
      east_max = std::max(east_max, p.east_m);
      north_min = std::min(north_min, p.north_m);
      north_max = std::max(north_max, p.north_m);
    }
  }
};

PlanBounds plan_bounds(const SurveyPlotData& data) {
  PlanBounds bounds;
  bounds.add(data.ins_path);
  bounds.add(data.truth_path);
  bounds.add(data.minimum_curvature_stations);
  // The stations' 2-sigma ellipses at true size (the magnification is 1 with independent
  // scales): the extent of an ellipse with semi-axes a, b along a unit x is hypot(a.x, b.x).
  for (std::size_t i = 0; i < data.minimum_curvature_stations.size() && i < data.stations.size();
       ++i) {
    const EllipseAxes axes = two_sigma_axes(data.stations[i].horizontal_covariance_m2);
    const WellPathPoint& p = data.minimum_curvature_stations[i];
    const double north_extent = std::hypot(axes.major_ne.x(), axes.minor_ne.x());
    const double east_extent = std::hypot(axes.major_ne.y(), axes.minor_ne.y());
    if (std::isnan(north_extent) || std::isnan(east_extent)) continue;
    bounds.add({{p.md_m, p.north_m - north_extent, p.east_m - east_extent, p.tvd_m},
                {p.md_m, p.north_m + north_extent, p.east_m + east_extent, p.tvd_m}});
  }
  return bounds;
}

/// A range [low, high] padded by 5 % on either side and widened about its middle to `span`.
std::pair<double, double> padded_range(double low, double high, double span) {
  const double middle = 0.5 * (low + high);
  const double half = 0.5 * std::max(high - low, span) * 1.1;
  return {middle - half, middle + half};
}

/// Horizontal displacement along an azimuth (m): the x axis of the vertical section.
double section_displacement_m(const WellPathPoint& p, double azimuth_rad) {
  return p.north_m * std::cos(azimuth_rad) + p.east_m * std::sin(azimuth_rad);
}

/// Datablock `$name`: east north tvd section, one row per point.
std::string path_datablock(std::string_view name, const std::vector<WellPathPoint>& path,
                           double section_azimuth_rad) {
  std::string block = fmt::format("${} << EOD\n", name);
  auto out = std::back_inserter(block);
  for (const WellPathPoint& p : path) {
    fmt::format_to(out, "{:.9g} {:.9g} {:.9g} {:.9g}\n", p.east_m, p.north_m, p.tvd_m,
                   section_displacement_m(p, section_azimuth_rad));
  }
  return block + "EOD\n";
}

/// Datablock $stations: east north tvd section magnified-2-sigma-tvd.
std::string stations_datablock(const std::vector<SurveyStation>& stations,
                               const std::vector<WellPathPoint>& points, double section_azimuth_rad,
                               double magnification) {
  std::string block = "$stations << EOD\n";
  auto out = std::back_inserter(block);
  for (std::size_t i = 0; i < points.size(); ++i) {
    fmt::format_to(out, "{:.9g} {:.9g} {:.9g} {:.9g} {:.9g}\n", points[i].east_m, points[i].north_m,
                   points[i].tvd_m, section_displacement_m(points[i], section_azimuth_rad),
                   kSigmaScale * stations[i].tvd_sigma_m * magnification);
  }
  return block + "EOD\n";
}

/// Datablock $ellipses: closed polylines (east north), one per station, separated by blank
/// lines so gnuplot does not join them.
std::string ellipses_datablock(const std::vector<SurveyStation>& stations,
                               const std::vector<WellPathPoint>& points, double magnification) {
  std::string block = "$ellipses << EOD\n";
  auto out = std::back_inserter(block);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const EllipseAxes axes = two_sigma_axes(stations[i].horizontal_covariance_m2);
    for (int k = 0; k <= kEllipseSegments; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / kEllipseSegments;
      const Eigen::Vector2d offset_ne =
          magnification * (std::cos(angle) * axes.major_ne + std::sin(angle) * axes.minor_ne);
      fmt::format_to(out, "{:.9g} {:.9g}\n", points[i].east_m + offset_ne.y(),
                     points[i].north_m + offset_ne.x());
    }
    block += '\n';
  }
  return block + "EOD\n";
}

std::string magnification_label(double magnification) {
  return fmt::format("x{:g}", magnification);
}

}  // namespace

double ellipse_magnification(double largest_major_axis_m, double plot_extent_m,
                             double target_fraction) {
  if (!(largest_major_axis_m > 0.0) || !(plot_extent_m > 0.0)) return 1.0;
  const double wanted = target_fraction * plot_extent_m / largest_major_axis_m;
  if (wanted <= 1.0) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(wanted)));
  for (double mantissa : {5.0, 2.0}) {
    if (mantissa * decade <= wanted) return mantissa * decade;
  }
  return decade;
}

PlanViewAxes plan_view_axes(const SurveyPlotData& data) {
  const PlanBounds bounds = plan_bounds(data);
  PlanViewAxes axes;
  if (!(bounds.east_max >= bounds.east_min)) return axes;  // no point
  const double east_span = bounds.east_max - bounds.east_min;
  const double north_span = bounds.north_max - bounds.north_min;
  const double larger = std::max({east_span, north_span, kMinimumPlanSpan_m});
  axes.equal_scales = std::min(east_span, north_span) >= kEqualScaleRatio * larger;
  // Equal scales: both axes span the larger extent (the picture is then as wide as high).
  const double east_minimum = axes.equal_scales ? larger : kMinimumPlanSpan_m;
  const double north_minimum = axes.equal_scales ? larger : kMinimumPlanSpan_m;
  std::tie(axes.east_min_m, axes.east_max_m) =
      padded_range(bounds.east_min, bounds.east_max, east_minimum);
  std::tie(axes.north_min_m, axes.north_max_m) =
      padded_range(bounds.north_min, bounds.north_max, north_minimum);
  return axes;
}

std::string survey_plot_script(const SurveyPlotData& data) {
  const std::vector<SurveyStation>& stations = data.stations;
  const std::vector<WellPathPoint>& points = data.minimum_curvature_stations;
  const PlanViewAxes axes = plan_view_axes(data);
  double largest_major_axis_m = 0.0;
  for (const SurveyStation& s : stations) {
    largest_major_axis_m = std::max(
        largest_major_axis_m, 2.0 * two_sigma_axes(s.horizontal_covariance_m2).major_ne.norm());
  }
  // With equal scales the ellipses are magnified to be seen on a km-long plan; with
  // independent scales the narrow axis already spans them at true size (plan_view_axes).
  const double magnification =
      axes.equal_scales
          ? ellipse_magnification(largest_major_axis_m, (axes.east_max_m - axes.east_min_m) / 1.1)
          : 1.0;
  const double section_azimuth_rad = data.vertical_section_azimuth_deg * kRadPerDeg;
  const bool has_stations = !points.empty();
  const bool has_truth = !data.truth_path.empty();
  const std::string magnified = magnification_label(magnification);

  std::string script = path_datablock("ins", data.ins_path, section_azimuth_rad);
  if (has_truth) script += path_datablock("truth", data.truth_path, section_azimuth_rad);
  if (has_stations) {
    script += stations_datablock(stations, points, section_azimuth_rad, magnification);
    script += ellipses_datablock(stations, points, magnification);
  }
  script += "set multiplot layout 1,2 title 'survey: INS path and minimum-curvature stations'\n";
  script += "set grid\nset key below noenhanced\nset bmargin 8\n";

  // Plan view: one scale for east and north when the well spreads in both; else each axis
  // its own range (said in the title), so a long straight hole is not squashed to a line.
  script += fmt::format(
      "set title 'plan view (2-sigma ellipses {}{})' noenhanced\n{}\n"
      "set xrange [{:.9g}:{:.9g}]\nset yrange [{:.9g}:{:.9g}]\n"
      "set xlabel 'east (m)'\nset ylabel 'north (m)'\n"
      "plot $ins using 1:2 with lines lw 1.5 lc rgb '#1f77b4' title 'INS path'",
      magnified, axes.equal_scales ? "" : "; axes scaled independently",
      axes.equal_scales ? "set size ratio -1" : "set size noratio", axes.east_min_m,
      axes.east_max_m, axes.north_min_m, axes.north_max_m);
  if (has_truth) {
    script += ", $truth using 1:2 with lines lw 1 dt 2 lc rgb 'black' title 'truth'";
  }
  if (has_stations) {
    script += fmt::format(
        ", $stations using 1:2 with points pt 7 ps 0.5 lc rgb '#d62728' "
        "title 'stations (minimum curvature)', $ellipses using 1:2 with lines lc rgb '#2ca02c' "
        "title '2-sigma ellipses {}'",
        magnified);
  }
  script += '\n';

  // Vertical section along the listing's azimuth, TVD growing downwards.
  script += fmt::format(
      "set title 'vertical section along azimuth {:.1f} deg' noenhanced\nset size noratio\n"
      "set xrange [*:*]\nset yrange [*:*] reverse\n"
      "set xlabel 'vertical section (m)'\nset ylabel 'TVD (m)'\n"
      "plot $ins using 4:3 with lines lw 1.5 lc rgb '#1f77b4' title 'INS path'",
      data.vertical_section_azimuth_deg);
  if (has_truth) {
    script += ", $truth using 4:3 with lines lw 1 dt 2 lc rgb 'black' title 'truth'";
  }
  if (has_stations) {
    script += fmt::format(
        ", $stations using 4:3:5 with yerrorbars pt 7 ps 0.5 lc rgb '#d62728' "
        "title 'stations, +/-2-sigma TVD {}'",
        magnified);
  }
  script += "\nunset multiplot\n";
  return script;
}

void plot_survey(const SurveyPlotData& data, PendingFile& output) {
  if (data.ins_path.empty()) return;
  render_gnuplot(survey_plot_script(data), output);
}

}  // namespace stochnav
