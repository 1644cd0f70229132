#include "survey/survey_plot.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <string>

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

/// Largest of the east and north spans of everything in the plan view (m).
double plan_extent_m(const std::vector<WellPathPoint>& ins_path,
                     const std::vector<WellPathPoint>& stations) {
  double north_min = std::numeric_limits<double>::infinity();
  double north_max = -north_min;
  double east_min = north_min;
  double east_max = -north_min;
  for (const auto* points : {&ins_path, &stations}) {
    for (const WellPathPoint& p : *points) {
      north_min = std::min(north_min, p.north_m);
      north_max = std::max(north_max, p.north_m);
      east_min = std::min(east_min, p.east_m);
      east_max = std::max(east_max, p.east_m);
    }
  }
  return std::max(north_max - north_min, east_max - east_min);
}

/// Horizontal displacement along an azimuth (m): the x axis of the vertical section.
double section_displacement_m(const WellPathPoint& p, double azimuth_rad) {
  return p.north_m * std::cos(azimuth_rad) + p.east_m * std::sin(azimuth_rad);
}

/// Datablock $ins: east north tvd section.
std::string ins_datablock(const std::vector<WellPathPoint>& ins_path, double section_azimuth_rad) {
  std::string block = "$ins << EOD\n";
  auto out = std::back_inserter(block);
  for (const WellPathPoint& p : ins_path) {
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

/// An azimuth in [0, 360) deg from atan2's (-pi, pi] rad.
double azimuth_deg(double azimuth_rad) {
  const double degrees = azimuth_rad * kDegPerRad;
  return degrees < 0.0 ? degrees + 360.0 : degrees;
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

void plot_survey(const SurveyRecorder& recorder,
                 const std::vector<WellPathPoint>& minimum_curvature_stations,
                 PendingFile& output) {
  const std::vector<WellPathPoint>& ins_path = recorder.ins_path();
  const std::vector<SurveyStation>& stations = recorder.stations();
  if (ins_path.empty()) return;

  double largest_major_axis_m = 0.0;
  for (const SurveyStation& s : stations) {
    largest_major_axis_m = std::max(
        largest_major_axis_m, 2.0 * two_sigma_axes(s.horizontal_covariance_m2).major_ne.norm());
  }
  const double magnification = ellipse_magnification(
      largest_major_axis_m, plan_extent_m(ins_path, minimum_curvature_stations));
  // The vertical section is drawn along the closure: from the tie-on to the last station (to
  // the INS path's end when there is no station).
  const WellPathPoint& closure_point =
      minimum_curvature_stations.empty() ? ins_path.back() : minimum_curvature_stations.back();
  const double section_azimuth_rad = std::atan2(closure_point.east_m, closure_point.north_m);
  const bool has_stations = !minimum_curvature_stations.empty();
  const std::string magnified = magnification_label(magnification);

  std::string script = ins_datablock(ins_path, section_azimuth_rad);
  if (has_stations) {
    script += stations_datablock(stations, minimum_curvature_stations, section_azimuth_rad,
                                 magnification);
    script += ellipses_datablock(stations, minimum_curvature_stations, magnification);
  }
  script += "set multiplot layout 1,2 title 'survey: INS path and minimum-curvature stations'\n";
  script += "set grid\nset key below noenhanced\nset bmargin 7\n";

  // Plan view, equal scales so the path and the ellipses keep their shape.
  script += fmt::format(
      "set title 'plan view (2-sigma ellipses {})' noenhanced\nset size ratio -1\n"
      "set xlabel 'east (m)'\nset ylabel 'north (m)'\n"
      "plot $ins using 1:2 with lines lw 1.5 lc rgb '#1f77b4' title 'INS path'",
      magnified);
  if (has_stations) {
    script += fmt::format(
        ", $stations using 1:2 with points pt 7 ps 0.5 lc rgb '#d62728' "
        "title 'stations (minimum curvature)', $ellipses using 1:2 with lines lc rgb '#2ca02c' "
        "title '2-sigma ellipses {}'",
        magnified);
  }
  script += '\n';

  // Vertical section, TVD growing downwards.
  script += fmt::format(
      "set title 'vertical section along azimuth {:.1f} deg' noenhanced\nset size noratio\n"
      "set yrange [*:*] reverse\n"
      "set xlabel 'horizontal displacement (m)'\nset ylabel 'TVD (m)'\n"
      "plot $ins using 4:3 with lines lw 1.5 lc rgb '#1f77b4' title 'INS path'",
      azimuth_deg(section_azimuth_rad));
  if (has_stations) {
    script += fmt::format(
        ", $stations using 4:3:5 with yerrorbars pt 7 ps 0.5 lc rgb '#d62728' "
        "title 'stations, +/-2-sigma TVD {}'",
        magnified);
  }
  script += "\nunset multiplot\n";
  render_gnuplot(script, output);
}

}  // namespace stochnav
