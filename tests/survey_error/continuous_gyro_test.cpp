// The continuous-gyro terms of the OWSG GYRO-NS-CT model (GXY-RN, GXY-GD, GXY-GRW) checked by
// Monte Carlo: their sensor errors are simulated as the model defines them (independent
// gyrocompass noise, the initialising station's error carried on, one drift rate, a random
// walk), the perturbed listing is turned into positions by exact minimum curvature, and the
// positions' scatter over many seeds is compared with the propagated covariance by chi-square
// statistics that fail when the covariance is off by a few percent. The same test rejects the
// OWSG table's approximation of the random walk as fully correlated (systematic), so it has the
// power to fail.

#include "stochnav/survey_error/continuous_gyro.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/minimum_curvature.hpp"
#include "stochnav/sim/normal_generator.hpp"

namespace stochnav::survey_error {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;
using Eigen::Vector3d;

/// Vertical to 300 m, a build of 2 deg / 30 m turning from azimuth 30 to 78 deg up to 50 deg,
/// a hold to 2400 m: 80 stations, the continuous survey starting at the 16 deg station.
std::vector<ListingStation> gyro_test_well() {
  std::vector<ListingStation> stations;
  for (int k = 0; k <= 80; ++k) {
    const double md_m = 30.0 * k;
    const int build = std::clamp(k - 10, 0, 25);
    stations.push_back({md_m, 2.0 * build * kRadPerDeg, (30.0 + 2.0 * build) * kRadPerDeg});
  }
  return stations;
}

WellParameters gyro_test_site() {
  WellParameters well;
  well.latitude_rad = 60.0 * kRadPerDeg;
  well.earth_rate_rad_s = 15.041 * kRadPerDeg / 3600.0;
  return well;
}

/// Exact minimum-curvature positions (NEV, m) from the first station at the origin.
std::vector<Vector3d> minimum_curvature_positions(const std::vector<ListingStation>& stations) {
  const auto direction = [](const ListingStation& s) {
    return hole_direction_nev(s.inclination_rad, s.azimuth_rad);
  };
  std::vector<Vector3d> positions = {Vector3d::Zero()};
  for (std::size_t k = 1; k < stations.size(); ++k) {
    positions.push_back(positions.back() +
                        minimum_curvature_step(direction(stations[k - 1]), direction(stations[k]),
                                               stations[k].md_m - stations[k - 1].md_m));
  }
  return positions;
}

/// Which terms a simulation draws.
struct GyroTermSwitches {
  bool noise = false;
  bool drift = false;
  bool random_walk = false;
};

/// The stations' azimuth errors (rad) for one draw, from the model's definitions.
std::vector<double> simulated_azimuth_errors(const std::vector<ListingStation>& stations,
                                             const ContinuousGyroTerms& terms,
                                             const WellParameters& well, GyroTermSwitches on,
                                             NormalGenerator& normal) {
  const std::size_t initialising = continuous_initialisation_station(stations, terms);
  std::vector<double> errors(stations.size(), 0.0);
  const double drift_rate = on.drift ? terms.drift_rad_s * normal() : 0.0;
  double carried_rad = 0.0;  // the initialising error plus drift and walk so far
  for (std::size_t k = 1; k < stations.size(); ++k) {
    const ListingStation& s = stations[k];
    if (k <= initialising) {
      const double gain_s =
          terms.noise_reduction_factor *
          std::sqrt(1.0 - std::pow(std::cos(s.azimuth_rad) * std::sin(s.inclination_rad), 2)) /
          (well.earth_rate_rad_s * std::cos(well.latitude_rad) * std::cos(s.inclination_rad));
      errors[k] = on.noise ? terms.noise_rad_s * gain_s * normal() : 0.0;
      carried_rad = errors[k];
      continue;
    }
    const double time_s = (s.md_m - stations[k - 1].md_m) / terms.running_speed_m_s;
    const double mean_sine = std::sin((s.inclination_rad + stations[k - 1].inclination_rad) / 2.0);
    carried_rad += drift_rate * time_s / mean_sine;
    if (on.random_walk) {
      carried_rad += terms.random_walk_rad_per_sqrt_s * std::sqrt(time_s) / mean_sine * normal();
    }
    errors[k] = carried_rad;
  }
  return errors;
}

/// Runs `draws` simulations and compares the scatter of the horizontal position errors at the
/// test stations with the propagated covariance P along P's principal axes: for an axis u
/// with variance lambda >= 1 % of the largest, the sum over draws of (u^T r)^2 / lambda is
/// chi-square with N degrees of freedom when P is right, and must lie within 5 of its standard
/// deviations (a false alarm about once in a million runs; 5 % off in one axis fails); an
/// axis with less (a single variable moves a station along one line only) must hold a mean
/// square within 0.1 % of the largest variance of its own (the first-order, balanced-tangential
/// propagation against exact minimum curvature differs by far less). Returns whether all
/// passed; reports the failures when `expect_pass`.
bool monte_carlo_agrees(const ContinuousGyroTerms& terms, GyroTermSwitches on,
                        const std::vector<Eigen::Matrix3d>& propagated, bool expect_pass) {
  const auto stations = gyro_test_well();
  const WellParameters well = gyro_test_site();
  const std::vector<std::size_t> checked = {continuous_initialisation_station(stations, terms), 40,
                                            stations.size() - 1};
  std::vector<Matrix2d> scatter(checked.size(), Matrix2d::Zero());  // sum of r r^T
  const std::vector<Vector3d> truth = minimum_curvature_positions(stations);
  constexpr int kDraws = 20000;
  NormalGenerator normal(20240527);
  for (int draw = 0; draw < kDraws; ++draw) {
    std::vector<ListingStation> surveyed = stations;
    const auto errors = simulated_azimuth_errors(stations, terms, well, on, normal);
    for (std::size_t k = 0; k < surveyed.size(); ++k) surveyed[k].azimuth_rad += errors[k];
    const std::vector<Vector3d> positions = minimum_curvature_positions(surveyed);
    for (std::size_t i = 0; i < checked.size(); ++i) {
      const Vector2d r = (positions[checked[i]] - truth[checked[i]]).head<2>();
      scatter[i] += r * r.transpose();
    }
  }
  bool all_passed = true;
  const auto report = [&](bool passed, const std::string& what) {
    all_passed = all_passed && passed;
    if (expect_pass) {
      EXPECT_TRUE(passed) << what;
    }
  };
  for (std::size_t i = 0; i < checked.size(); ++i) {
    const Matrix2d p = propagated[checked[i]].topLeftCorner<2, 2>();
    const Eigen::SelfAdjointEigenSolver<Matrix2d> axes(p);
    const double largest = axes.eigenvalues().maxCoeff();
    for (int a = 0; a < 2; ++a) {
      const Vector2d u = axes.eigenvectors().col(a);
      const double variance = axes.eigenvalues()(a);
      const double mean_square = u.dot(scatter[i] * u) / kDraws;
      const std::string where = "station " + std::to_string(checked[i]) + ", axis variance " +
                                std::to_string(variance) + " m^2, simulated " +
                                std::to_string(mean_square) + " m^2";
      if (variance >= 0.01 * largest && variance > 0.0) {
        const double tolerance = 5.0 * std::sqrt(2.0 / kDraws);
        report(std::abs(mean_square / variance - 1.0) <= tolerance,
               where + " (relative tolerance " + std::to_string(tolerance) + ")");
      } else {
        report(std::abs(mean_square - variance) <= 1e-3 * largest + 1e-20,
               where + " (a degenerate axis: tolerance 0.1 % of " + std::to_string(largest) + ")");
      }
    }
  }
  return all_passed;
}

/// A tenth of the OWSG magnitudes: the propagation is linear in them, and the smaller azimuth
/// errors (tenths of a degree) keep the exact minimum curvature of the simulation within 0.1 %
/// of its first-order expansion.
ContinuousGyroTerms scaled_owsg_terms() {
  ContinuousGyroTerms terms = owsg_gyro_ns_ct_terms();
  terms.noise_rad_s *= 0.1;
  terms.drift_rad_s *= 0.1;
  terms.random_walk_rad_per_sqrt_s *= 0.1;
  return terms;
}

std::vector<Eigen::Matrix3d> propagated_sum(const std::vector<SourceCovariance>& sources,
                                            GyroTermSwitches on) {
  std::vector<Eigen::Matrix3d> sum(sources.front().nev_m2.size(), Eigen::Matrix3d::Zero());
  const bool wanted[3] = {on.noise, on.drift, on.random_walk};
  for (std::size_t i = 0; i < 3; ++i) {
    if (!wanted[i]) continue;
    for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += sources[i].nev_m2[k];
  }
  return sum;
}

class ContinuousGyroMonteCarlo : public ::testing::TestWithParam<GyroTermSwitches> {};

TEST_P(ContinuousGyroMonteCarlo, SimulatedScatterMatchesThePropagatedCovariance) {
  const ContinuousGyroTerms terms = scaled_owsg_terms();
  const auto sources = continuous_gyro_covariance(terms, gyro_test_well(), gyro_test_site());
  ASSERT_EQ(sources.size(), 3u);
  EXPECT_EQ(sources[0].code, "GXY-RN");
  EXPECT_EQ(sources[1].code, "GXY-GD");
  EXPECT_EQ(sources[2].code, "GXY-GRW");
  EXPECT_TRUE(monte_carlo_agrees(terms, GetParam(), propagated_sum(sources, GetParam()), true));
}

INSTANTIATE_TEST_SUITE_P(Terms, ContinuousGyroMonteCarlo,
                         ::testing::Values(GyroTermSwitches{true, false, false},
                                           GyroTermSwitches{false, true, false},
                                           GyroTermSwitches{false, false, true},
                                           GyroTermSwitches{true, true, true}),
                         [](const ::testing::TestParamInfo<GyroTermSwitches>& case_info) {
                           const GyroTermSwitches& on = case_info.param;
                           if (on.noise && on.drift && on.random_walk) return std::string("all");
                           return std::string(on.noise ? "noise" : on.drift ? "drift" : "walk");
                         });

TEST(ContinuousGyro, TheFullyCorrelatedRandomWalkOfTheOwsgTableFailsTheSameTest) {
  // The OWSG table marks GXY-GRW systematic: each station's accumulated 1-sigma azimuth error
  // sigma_k, fully correlated along the hole (one variable, loadings sigma_k). The random
  // walk's stations share only the increments up to the earlier one, so that covariance is
  // wrong, and the Monte Carlo check says so.
  const ContinuousGyroTerms terms = scaled_owsg_terms();
  const auto stations = gyro_test_well();
  const WellParameters well = gyro_test_site();
  const std::size_t initialising = continuous_initialisation_station(stations, terms);
  Eigen::MatrixXd fully_correlated =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(stations.size()), 1);
  double variance = 0.0;
  for (std::size_t k = initialising + 1; k < stations.size(); ++k) {
    const double time_s = (stations[k].md_m - stations[k - 1].md_m) / terms.running_speed_m_s;
    const double mean_sine =
        std::sin((stations[k].inclination_rad + stations[k - 1].inclination_rad) / 2.0);
    variance += std::pow(terms.random_walk_rad_per_sqrt_s / mean_sine, 2) * time_s;
    fully_correlated(static_cast<Eigen::Index>(k), 0) = std::sqrt(variance);
  }
  const auto approximation = correlated_azimuth_error_covariance(stations, well, fully_correlated);
  const auto exact = continuous_gyro_covariance(terms, stations, well);
  // Same azimuth variance at every station, different position covariance at the end.
  const double ratio = approximation.back().trace() / exact[2].nev_m2.back().trace();
  EXPECT_GT(std::abs(ratio - 1.0), 0.1) << ratio;
  const GyroTermSwitches walk{false, false, true};
  EXPECT_FALSE(monte_carlo_agrees(terms, walk, approximation, false));
}

TEST(ContinuousGyro, ATermSetToZeroGivesZeroAndTheTieOnIsExact) {
  ContinuousGyroTerms terms = owsg_gyro_ns_ct_terms();
  terms.drift_rad_s = 0.0;
  const auto sources = continuous_gyro_covariance(terms, gyro_test_well(), gyro_test_site());
  for (const auto& c : sources[1].nev_m2) EXPECT_EQ(c, Eigen::Matrix3d::Zero());
  for (const auto& source : sources) EXPECT_EQ(source.nev_m2.front(), Eigen::Matrix3d::Zero());
  // Gyrocompass noise in the inclined part of the static survey moves the stations.
  EXPECT_GT(sources[0].nev_m2[14].trace(), 0.0);
}

}  // namespace
}  // namespace stochnav::survey_error
