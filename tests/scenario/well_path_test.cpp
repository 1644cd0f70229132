// Well geometry (scenario/well_path.hpp) against closed forms and a fine numerical integration.

#include "stochnav/scenario/well_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace stochnav {
namespace {

constexpr double kRadPerDegree = std::numbers::pi / 180.0;
constexpr double kPerThirtyMetres = kRadPerDegree / 30.0;  // rad/m per deg/30 m

Eigen::Vector3d tangent(double inclination, double azimuth) {
  return {std::sin(inclination) * std::sin(azimuth), std::sin(inclination) * std::cos(azimuth),
          -std::cos(inclination)};
}

WellPathConfig sections_well(double inclination_deg, double azimuth_deg,
                             std::vector<WellSectionConfig> sections) {
  WellPathConfig well;
  well.start_inclination_rad = inclination_deg * kRadPerDegree;
  well.start_azimuth_rad = azimuth_deg * kRadPerDegree;
  well.sections = std::move(sections);
  return well;
}

TEST(WellPath, PureBuildSectionIsTheCircularArc) {
  const double build = 3.0 * kPerThirtyMetres;
  const WellPath path(sections_well(10.0, 40.0, {{600.0, build, 0.0}}));
  const double radius = 1.0 / build;
  const double i0 = 10.0 * kRadPerDegree;
  const double a = 40.0 * kRadPerDegree;
  for (double md : {0.0, 1e-3, 17.0, 299.9, 600.0}) {
    const WellPathPoint point = path.at(md);
    const double inclination = i0 + build * md;
    const double horizontal = radius * (std::cos(i0) - std::cos(inclination));
    const Eigen::Vector3d expected(horizontal * std::sin(a), horizontal * std::cos(a),
                                   -radius * (std::sin(inclination) - std::sin(i0)));
    EXPECT_LT((point.offset_enu_m - expected).norm(), 1e-10) << md;
    EXPECT_NEAR(point.inclination_rad, inclination, 1e-15);
    EXPECT_EQ(point.azimuth_rad, a);
    // At the section end the point belongs to the hold that starts there.
    EXPECT_EQ(point.build_rate_rad_per_m, md < 600.0 ? build : 0.0);
  }
  // Beyond the last section: a straight hold along the final tangent.
  const WellPathPoint end = path.at(600.0);
  const WellPathPoint beyond = path.at(900.0);
  EXPECT_LT((beyond.offset_enu_m - end.offset_enu_m -
             300.0 * tangent(end.inclination_rad, end.azimuth_rad))
                .norm(),
            1e-10);
  EXPECT_EQ(beyond.build_rate_rad_per_m, 0.0);
}

TEST(WellPath, PureTurnAtNinetyDegreesIsAHorizontalCircle) {
  const double turn = 5.0 * kPerThirtyMetres;
  const WellPath path(sections_well(90.0, 0.0, {{1000.0, 0.0, turn}}));
  const double radius = 1.0 / turn;
  for (double md : {0.0, 3.0, 250.0, 999.0}) {
    const WellPathPoint point = path.at(md);
    const Eigen::Vector3d expected(radius * (1.0 - std::cos(turn * md)),
                                   radius * std::sin(turn * md), 0.0);
    EXPECT_LT((point.offset_enu_m - expected).norm(), 1e-10) << md;
    EXPECT_NEAR(point.azimuth_rad, turn * md, 1e-15);
    EXPECT_EQ(point.turn_rate_rad_per_m, turn);
  }
}

TEST(WellPath, PlaneFormEqualsItsSections) {
  WellPathConfig plane;
  plane.kickoff_md_m = 500.0;
  plane.build_rate_rad_per_m = 3.0 * kPerThirtyMetres;
  plane.target_inclination_rad = 90.0 * kRadPerDegree;
  plane.azimuth_rad = 60.0 * kRadPerDegree;
  const WellPath original(plane);
  ASSERT_TRUE(original.plane());
  WellPathConfig sections = sections_well(0.0, 60.0, well_sections(plane));
  ASSERT_EQ(sections.sections.size(), 2u);
  const WellPath general(sections);
  ASSERT_FALSE(general.plane());
  for (double md : {100.0, 500.0, 777.0, 1400.0, 2500.0}) {
    EXPECT_LT((original.at(md).offset_enu_m - general.at(md).offset_enu_m).norm(), 1e-9) << md;
    EXPECT_NEAR(original.at(md).inclination_rad, general.at(md).inclination_rad, 1e-14) << md;
  }
}

// Gauss-Legendre (5 nodes) on 1 m pieces of the tangent from md 0.
Eigen::Vector3d integrate_tangent(const WellPath& path, double md_end) {
  static constexpr double kNodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                       0.5384693101056831, 0.9061798459386640};
  static constexpr double kWeights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                         0.4786286704993665, 0.2369268850561891};
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const int pieces = static_cast<int>(std::ceil(md_end));
  const double h = md_end / pieces;
  for (int k = 0; k < pieces; ++k) {
    Eigen::Vector3d piece = Eigen::Vector3d::Zero();
    for (int j = 0; j < 5; ++j) {
      const WellPathPoint p = path.at((k + 0.5) * h + 0.5 * h * kNodes[j]);
      piece += kWeights[j] * tangent(p.inclination_rad, p.azimuth_rad);
    }
    sum += 0.5 * h * piece;
  }
  return sum;
}

TEST(WellPath, BuildAndTurnSectionsMatchAFineIntegrationOverTenKilometres) {
  // Section boundaries fall on whole metres, so no 1 m piece straddles a rate step.
  const WellPath path(sections_well(0.0, 80.0,
                                    {{400.0, 0.0, 0.0},
                                     {900.0, 3.0 * kPerThirtyMetres, 2.0 * kPerThirtyMetres},
                                     {1700.0, 0.5 * kPerThirtyMetres, -1.5 * kPerThirtyMetres},
                                     {3000.0, 0.0, 1e-9},
                                     {2000.0, -1.2 * kPerThirtyMetres, 0.7 * kPerThirtyMetres},
                                     {2000.0, 1.0 * kPerThirtyMetres, -4.0 * kPerThirtyMetres}}));
  for (double md : {400.0, 1300.0, 5000.0, 8000.0, 10000.0}) {
    const Eigen::Vector3d reference = integrate_tangent(path, md);
    EXPECT_LT((path.at(md).offset_enu_m - reference).norm(), 1e-6) << md;
  }
  // The rates are the md-derivatives of the angles, the tangent that of the offset.
  for (double md : {10.0, 777.7, 2345.6, 9000.1}) {
    const double h = 1e-3;
    const WellPathPoint a = path.at(md - h);
    const WellPathPoint b = path.at(md + h);
    const WellPathPoint p = path.at(md);
    EXPECT_NEAR((b.inclination_rad - a.inclination_rad) / (2 * h), p.build_rate_rad_per_m, 1e-10);
    EXPECT_NEAR((b.azimuth_rad - a.azimuth_rad) / (2 * h), p.turn_rate_rad_per_m, 1e-10);
    EXPECT_LT(
        ((b.offset_enu_m - a.offset_enu_m) / (2 * h) - tangent(p.inclination_rad, p.azimuth_rad))
            .norm(),
        1e-8);
  }
}

}  // namespace
}  // namespace stochnav
