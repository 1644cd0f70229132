#pragma once
// The geometry of a drilling scenario's well path (scenario_config.hpp WellPathConfig) as a
// function of measured depth md (m): the offset of the path point from the wellhead (md 0) in
// a local-level frame at the wellhead (E, N, U; m, U up, so TVD = -U), and the direction of the
// path, inclination I(md) and azimuth A(md) of ins/mwd_attitude.hpp, with their md-derivatives.
// The unit tangent is t = (sin I sin A, sin I cos A, -cos I) and the offset its integral.
//
// Plane form: vertical, a circular build (turning when turn_rate_rad_per_m != 0), a hold; the
// path without turn is evaluated with the circular-arc closed forms. Sections form and plane
// form with turn: within a section I and A are linear in md, and the offset from the section
// start has the closed form of the integrals of cos(c + k u) and sin(c + k u) (written with
// sinc, exact as k -> 0); the offsets of the section starts are accumulated once. The error is
// rounding only (< 1e-9 m over 10 km). md below 0 or beyond the last section: straight
// extrapolation along the first / last tangent.

#include <Eigen/Core>
#include <vector>

#include "stochnav/scenario/scenario_config.hpp"

namespace stochnav {

struct WellPathPoint {
  Eigen::Vector3d offset_enu_m = Eigen::Vector3d::Zero();  ///< from the wellhead, ENU (m)
  double inclination_rad = 0.0;                            ///< I(md), [0, pi]
  double azimuth_rad = 0.0;                                ///< A(md), not wrapped
  double build_rate_rad_per_m = 0.0;                       ///< dI/dmd at md (rad/m)
  double turn_rate_rad_per_m = 0.0;                        ///< dA/dmd at md (rad/m)
};

class WellPath {
 public:
  /// `well` validated (scenario_config_json.hpp); the plane form needs build_rate > 0.
  explicit WellPath(const WellPathConfig& well);

  /// The path at measured depth md_m (m). At a section boundary: the section that starts there.
  WellPathPoint at(double md_m) const;

  /// True for the plane form without turn (the original circular-arc evaluation).
  bool plane() const { return plane_; }
  /// Measured depths where the sections start (sections form, or the plane form with turn).
  const std::vector<double>& section_start_md_m() const { return start_md_; }

 private:
  WellPathConfig well_;
  bool plane_ = true;
  double build_end_md_m_ = 0.0;
  std::vector<double> start_md_;
  std::vector<double> start_inclination_;
  std::vector<double> start_azimuth_;
  std::vector<Eigen::Vector3d> start_offset_;
  std::vector<WellSectionConfig> sections_;  // a final hold of length 0 marks the end
};

/// The sections equivalent to a plane-form path (its kickoff and build; start azimuth is the
/// well azimuth); a sections-form path unchanged.
std::vector<WellSectionConfig> well_sections(const WellPathConfig& well);

}  // namespace stochnav
