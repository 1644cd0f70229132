#include "stochnav/scenario/well_path.hpp"

#include <algorithm>
#include <cmath>

namespace stochnav {
namespace {

// sin(x) / x, with its series near 0 (error < x^8 / 9! there).
double sinc(double x) {
  if (std::abs(x) < 1e-3) {
    const double x2 = x * x;
    return 1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0));
  }
  return std::sin(x) / x;
}

// Integrals over u in [0, s] of cos(c + k u) and sin(c + k u):
// (sin(c + k s) - sin c) / k = s cos(c + k s / 2) sinc(k s / 2), and the like for sin.
double integral_cos(double c, double k, double s) {
  return s * std::cos(c + 0.5 * k * s) * sinc(0.5 * k * s);
}
double integral_sin(double c, double k, double s) {
  return s * std::sin(c + 0.5 * k * s) * sinc(0.5 * k * s);
}

// Offset from the start of a section with I = i0 + b s, A = a0 + t s, after s metres:
// sin I sin A = (cos(I - A) - cos(I + A)) / 2, sin I cos A = (sin(I + A) + sin(I - A)) / 2.
Eigen::Vector3d section_offset(double i0, double a0, double b, double t, double s) {
  const double east = 0.5 * (integral_cos(i0 - a0, b - t, s) - integral_cos(i0 + a0, b + t, s));
  const double north = 0.5 * (integral_sin(i0 + a0, b + t, s) + integral_sin(i0 - a0, b - t, s));
  return {east, north, -integral_cos(i0, b, s)};
}

Eigen::Vector3d tangent(double inclination, double azimuth) {
  const double sin_i = std::sin(inclination);
  return {sin_i * std::sin(azimuth), sin_i * std::cos(azimuth), -std::cos(inclination)};
}

}  // namespace

std::vector<WellSectionConfig> well_sections(const WellPathConfig& well) {
  if (!well.sections.empty()) return well.sections;
  std::vector<WellSectionConfig> sections;
  if (well.kickoff_md_m > 0.0) sections.push_back({well.kickoff_md_m, 0.0, 0.0});
  sections.push_back({well.target_inclination_rad / well.build_rate_rad_per_m,
                      well.build_rate_rad_per_m, well.turn_rate_rad_per_m});
  return sections;
}

WellPath::WellPath(const WellPathConfig& well) : well_(well) {
  plane_ = well.sections.empty() && well.turn_rate_rad_per_m == 0.0;
  build_end_md_m_ = well.kickoff_md_m + well.target_inclination_rad / well.build_rate_rad_per_m;
  if (plane_) return;
  sections_ = well_sections(well);
  double md = 0.0;
  double inclination = well.sections.empty() ? 0.0 : well.start_inclination_rad;
  double azimuth = well.sections.empty() ? well.azimuth_rad : well.start_azimuth_rad;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  for (const auto& section : sections_) {
    start_md_.push_back(md);
    start_inclination_.push_back(inclination);
    start_azimuth_.push_back(azimuth);
    start_offset_.push_back(offset);
    offset += section_offset(inclination, azimuth, section.build_rate_rad_per_m,
                             section.turn_rate_rad_per_m, section.length_m);
    md += section.length_m;
    inclination += section.build_rate_rad_per_m * section.length_m;
    azimuth += section.turn_rate_rad_per_m * section.length_m;
  }
  // The final hold.
  sections_.push_back({0.0, 0.0, 0.0});
  start_md_.push_back(md);
  start_inclination_.push_back(inclination);
  start_azimuth_.push_back(azimuth);
  start_offset_.push_back(offset);
}

WellPathPoint WellPath::at(double md) const {
  WellPathPoint point;
  if (plane_) {
    // The original evaluation (kept operation for operation: shipped scenarios are unchanged).
    const WellPathConfig& well = well_;
    const double sin_a = std::sin(well.azimuth_rad);
    const double cos_a = std::cos(well.azimuth_rad);
    point.azimuth_rad = well.azimuth_rad;
    if (md <= well.kickoff_md_m) {
      point.offset_enu_m = Eigen::Vector3d(0.0, 0.0, -md);
      return point;
    }
    const double radius = 1.0 / well.build_rate_rad_per_m;
    const double build_md = std::min(md, build_end_md_m_) - well.kickoff_md_m;
    const double theta = build_md * well.build_rate_rad_per_m;
    const double horizontal = radius * (1.0 - std::cos(theta));
    const double vertical = well.kickoff_md_m + radius * std::sin(theta);
    Eigen::Vector3d p(horizontal * sin_a, horizontal * cos_a, -vertical);
    point.inclination_rad = theta;
    if (md < build_end_md_m_) {
      point.build_rate_rad_per_m = well.build_rate_rad_per_m;
    } else {
      const double hold = md - build_end_md_m_;
      p += hold *
           Eigen::Vector3d(std::sin(theta) * sin_a, std::sin(theta) * cos_a, -std::cos(theta));
    }
    point.offset_enu_m = p;
    return point;
  }
  if (md < 0.0) {
    point.inclination_rad = start_inclination_.front();
    point.azimuth_rad = start_azimuth_.front();
    point.offset_enu_m = md * tangent(point.inclination_rad, point.azimuth_rad);
    return point;
  }
  const auto it = std::upper_bound(start_md_.begin(), start_md_.end(), md);
  const std::size_t k = static_cast<std::size_t>(it - start_md_.begin()) - 1;
  const WellSectionConfig& section = sections_[k];
  const double s = md - start_md_[k];
  const double b = section.build_rate_rad_per_m;
  const double t = section.turn_rate_rad_per_m;
  point.inclination_rad = start_inclination_[k] + b * s;
  point.azimuth_rad = start_azimuth_[k] + t * s;
  point.build_rate_rad_per_m = b;
  point.turn_rate_rad_per_m = t;
  point.offset_enu_m =
      start_offset_[k] + section_offset(start_inclination_[k], start_azimuth_[k], b, t, s);
  return point;
}

}  // namespace stochnav
