// Properties of the ISCWSA error propagation that hold for any well: every covariance symmetric
// positive semi-definite, the total the sum of the sources, zero at the tie-on, closed forms on
// a straight vertical well, the near-vertical forms continuous with the general ones, grid
// north the true-north result rotated, and S, W and G alike within one well.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/survey_error/error_model.hpp"
#include "stochnav/survey_error/error_propagation.hpp"
#include "stochnav/survey_error/weighting_functions.hpp"

namespace stochnav::survey_error {
namespace {

using Eigen::Matrix3d;

WellParameters north_sea_well() {
  WellParameters well;
  well.latitude_rad = 60.0 * kRadPerDeg;
  well.b_total_nT = 50000.0;
  well.dip_rad = 72.0 * kRadPerDeg;
  well.declination_rad = -4.0 * kRadPerDeg;
  well.gravity_m_s2 = 9.80665;
  return well;
}

/// A 3-D well: vertical, a build and turn through north (azimuth wrapping 350 -> 10 deg), a
/// drop, irregular station spacing (5 m to 95 m), a station just off vertical.
std::vector<ListingStation> three_dimensional_well() {
  std::vector<ListingStation> stations;
  double md_m = 0.0;
  for (int k = 0; k < 60; ++k) {
    const double inclination_deg = k < 8 ? (k == 5 ? 0.3 : 0.0) : std::min(85.0, 3.0 * (k - 7));
    const double azimuth_deg = std::fmod(330.0 + 4.0 * k, 360.0);
    stations.push_back({md_m, inclination_deg * kRadPerDeg, azimuth_deg * kRadPerDeg});
    md_m += 5.0 + std::fmod(37.0 * k, 90.0);
  }
  return stations;
}

std::vector<ListingStation> vertical_well(int stations, double spacing_m) {
  std::vector<ListingStation> listing;
  for (int k = 0; k < stations; ++k) listing.push_back({k * spacing_m, 0.0, 0.0});
  return listing;
}

const std::vector<Matrix3d>& covariance_of(const SurveyCovariance& result,
                                           const std::string& code) {
  for (const auto& source : result.sources) {
    if (source.code == code) return source.nev_m2;
  }
  throw std::logic_error("no source " + code);
}

void expect_symmetric_psd(const Matrix3d& c, const std::string& what) {
  EXPECT_LE((c - c.transpose()).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + c.cwiseAbs().maxCoeff()))
      << what;
  const Eigen::SelfAdjointEigenSolver<Matrix3d> solver(c);
  EXPECT_GE(solver.eigenvalues().minCoeff(), -1e-9 * (1.0 + solver.eigenvalues().maxCoeff()))
      << what;
}

class EveryModel : public ::testing::TestWithParam<const char*> {};

TEST_P(EveryModel, CovariancesAreSymmetricPsdAndTheTotalIsTheSumOfTheSources) {
  const SurveyErrorModel& model = survey_error_model(GetParam());
  const auto stations = three_dimensional_well();
  const SurveyCovariance result = propagate_survey_errors(model, stations, north_sea_well());
  ASSERT_EQ(result.sources.size(), model.sources.size());
  ASSERT_EQ(result.total_nev_m2.size(), stations.size());
  for (std::size_t k = 0; k < stations.size(); ++k) {
    Matrix3d sum = Matrix3d::Zero();
    for (const auto& source : result.sources) {
      ASSERT_TRUE(source.nev_m2[k].allFinite()) << source.code << " station " << k;
      expect_symmetric_psd(source.nev_m2[k], source.code + " station " + std::to_string(k));
      sum += source.nev_m2[k];
    }
    expect_symmetric_psd(result.total_nev_m2[k], "TOTAL station " + std::to_string(k));
    EXPECT_LE((sum - result.total_nev_m2[k]).cwiseAbs().maxCoeff(),
              1e-12 * result.total_nev_m2[k].cwiseAbs().maxCoeff())
        << "station " << k;
  }
  // The tie-on is exact; every later station of this well is uncertain in every direction.
  EXPECT_EQ(result.total_nev_m2.front(), Matrix3d::Zero());
  for (std::size_t k = 1; k < stations.size(); ++k) {
    EXPECT_GT(result.total_nev_m2[k].diagonal().minCoeff(), 0.0) << "station " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Models, EveryModel, ::testing::Values("mwd_rev5", "mwd_rev4"));

TEST(VerticalWell, DepthScaleFactorGivesTheVerticalVarianceOfScaleTimesDepth) {
  // An MD scale error s moves the bottom of a vertical hole down by s MD, and nothing sideways.
  const auto stations = vertical_well(41, 30.0);
  const SurveyCovariance result =
      propagate_survey_errors(survey_error_model("mwd_rev5"), stations, north_sea_well());
  const auto& dsfs = covariance_of(result, "DSFS");
  for (std::size_t k = 0; k < stations.size(); ++k) {
    const double expected_sigma_m = 0.00056 * stations[k].md_m;
    EXPECT_NEAR(dsfs[k](2, 2), expected_sigma_m * expected_sigma_m, 1e-15) << "station " << k;
    const Eigen::Matrix2d horizontal = dsfs[k].topLeftCorner(2, 2);
    EXPECT_NEAR(horizontal.cwiseAbs().maxCoeff(), 0.0, 1e-20);
  }
}

TEST(VerticalWell, AccelerometerBiasTiltsTheWholeHoleByBiasOverGravity) {
  // Rev5: the x-y accelerometer bias b (ABXY-TI2S, near-vertical form) tilts the measured
  // vertical by b / G towards the listed azimuth's right-hand side (east at azimuth 0): the
  // station at MD is displaced sideways by MD b / G, the classic closed form.
  const auto stations = vertical_well(41, 30.0);
  const WellParameters well = north_sea_well();
  const SurveyCovariance result =
      propagate_survey_errors(survey_error_model("mwd_rev5"), stations, well);
  const auto& abxy = covariance_of(result, "ABXY-TI2S");
  for (std::size_t k = 0; k < stations.size(); ++k) {
    const double expected_sigma_m = stations[k].md_m * 0.004 / well.gravity_m_s2;
    EXPECT_NEAR(abxy[k](1, 1), expected_sigma_m * expected_sigma_m,
                1e-12 * expected_sigma_m * expected_sigma_m)
        << "station " << k;
    EXPECT_NEAR(abxy[k](0, 0), 0.0, 1e-20);
    EXPECT_NEAR(abxy[k](2, 2), 0.0, 1e-20);
  }
}

TEST(VerticalWell, Rev4LeavesTheHalfLegAtTheTieOnUntilted) {
  // Rev4 takes the tie-on's direction as exact: a systematic misalignment (XYM3, north in the
  // near-vertical form) tilts every leg but the half leg at the tie-on, so the offset at MD is
  // s (MD - dMD_1 / 2).
  const auto stations = vertical_well(21, 30.0);
  const SurveyCovariance result =
      propagate_survey_errors(survey_error_model("mwd_rev4"), stations, north_sea_well());
  const auto& xym3 = covariance_of(result, "XYM3");
  const double s = 0.1 * kRadPerDeg;
  for (std::size_t k = 1; k < stations.size(); ++k) {
    const double expected_sigma_m = s * (stations[k].md_m - 15.0);
    EXPECT_NEAR(xym3[k](0, 0), expected_sigma_m * expected_sigma_m,
                1e-12 * expected_sigma_m * expected_sigma_m)
        << "station " << k;
  }
}

TEST(NearVertical, TheNearVerticalFormsJoinTheGeneralForms) {
  // A station just above the vertical limit (general forms, 1/sin I weights) and one just below
  // it (near-vertical forms) give nearly the same covariance: the singular forms are the limits.
  WellParameters well = north_sea_well();
  well.vertical_inc_limit_rad = 1e-4 * kRadPerDeg;
  auto below = vertical_well(12, 30.0);
  auto above = below;
  for (std::size_t k = 1; k < below.size(); ++k) {
    below[k].azimuth_rad = above[k].azimuth_rad = 40.0 * kRadPerDeg;
    below[k].inclination_rad = 0.5 * well.vertical_inc_limit_rad;
    above[k].inclination_rad = 2.0 * well.vertical_inc_limit_rad;
  }
  for (const char* name : {"mwd_rev5", "mwd_rev4"}) {
    const SurveyErrorModel& model = survey_error_model(name);
    const SurveyCovariance near = propagate_survey_errors(model, below, well);
    const SurveyCovariance off = propagate_survey_errors(model, above, well);
    // The sources with near-vertical forms (1/sin I azimuth weights): the two inclinations
    // differ by O(I tan(dip)), 1e-5 relative. (Sources with sin I weights vanish at vertical and
    // are not compared: tiny either way.)
    const double scale = off.total_nev_m2.back().cwiseAbs().maxCoeff();
    for (std::size_t i = 0; i < model.sources.size(); ++i) {
      if (!has_near_vertical_form(model.sources[i].weighting)) continue;
      const Matrix3d& a = near.sources[i].nev_m2.back();
      const Matrix3d& b = off.sources[i].nev_m2.back();
      EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 1e-4 * b.cwiseAbs().maxCoeff())
          << name << " " << model.sources[i].code;
    }
    // The singular sources are large there: ABXY-TI2S tilts the hole by b / G.
    EXPECT_GT(covariance_of(near, "ABXY-TI2S").back().trace(), 1e-3 * scale);
  }
}

TEST(AzimuthReference, GridNorthIsTheTrueNorthCovarianceRotatedByTheConvergence) {
  const auto true_listing = three_dimensional_well();
  WellParameters true_well = north_sea_well();
  WellParameters grid_well = true_well;
  grid_well.azimuth_reference = AzimuthReference::kGrid;
  grid_well.convergence_rad = 2.5 * kRadPerDeg;
  auto grid_listing = true_listing;
  for (auto& station : grid_listing) station.azimuth_rad -= grid_well.convergence_rad;
  const SurveyErrorModel& model = survey_error_model("mwd_rev5");
  const SurveyCovariance in_true = propagate_survey_errors(model, true_listing, true_well);
  const SurveyCovariance in_grid = propagate_survey_errors(model, grid_listing, grid_well);
  const double c = std::cos(grid_well.convergence_rad);
  const double s = std::sin(grid_well.convergence_rad);
  Matrix3d true_to_grid;
  true_to_grid << c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0;
  for (std::size_t k = 0; k < true_listing.size(); ++k) {
    const Matrix3d expected = true_to_grid * in_true.total_nev_m2[k] * true_to_grid.transpose();
    EXPECT_LE((in_grid.total_nev_m2[k] - expected).cwiseAbs().maxCoeff(),
              1e-9 * (1.0 + expected.cwiseAbs().maxCoeff()))
        << "station " << k;
  }
}

TEST(PropagationModes, SystematicPerWellAndGlobalAgreeWithinOneWellAndRandomDiffers) {
  SurveyErrorModel model = survey_error_model("mwd_rev5");
  model.sources = {model.sources[3]};  // ABXY-TI1S
  const auto stations = three_dimensional_well();
  const WellParameters well = north_sea_well();
  std::vector<Matrix3d> last;
  for (PropagationMode mode : {PropagationMode::kSystematic, PropagationMode::kPerWell,
                               PropagationMode::kGlobal, PropagationMode::kRandom}) {
    model.sources[0].mode = mode;
    last.push_back(propagate_survey_errors(model, stations, well).total_nev_m2.back());
  }
  EXPECT_EQ(last[0], last[1]);
  EXPECT_EQ(last[0], last[2]);
  // A bias the same at every station adds up along the hole; independent errors partly cancel.
  EXPECT_GT(last[0].trace(), 5.0 * last[3].trace());
}

TEST(PropagationModes, TheGeneralCorrelatedPropagationReproducesRandomAndSystematic) {
  // Two implementations of the same equations: an azimuth source (DECR random, DEC-OS global)
  // through the model, and the same errors as loadings (a diagonal, a single column).
  const SurveyErrorModel& model = survey_error_model("mwd_rev5");
  const auto stations = three_dimensional_well();
  const WellParameters well = north_sea_well();
  const SurveyCovariance by_model = propagate_survey_errors(model, stations, well);
  const auto n = static_cast<Eigen::Index>(stations.size());
  const Eigen::MatrixXd random_loadings =
      Eigen::MatrixXd::Identity(n, n) * 0.1 * kRadPerDeg;  // DECR
  const Eigen::MatrixXd global_loadings = Eigen::MatrixXd::Constant(n, 1, 0.24 * kRadPerDeg);
  const auto random = correlated_azimuth_error_covariance(stations, well, random_loadings);
  const auto global = correlated_azimuth_error_covariance(stations, well, global_loadings);
  for (std::size_t k = 0; k < stations.size(); ++k) {
    const Matrix3d& decr = covariance_of(by_model, "DECR")[k];
    const Matrix3d& dec_os = covariance_of(by_model, "DEC-OS")[k];
    EXPECT_LE((random[k] - decr).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + decr.cwiseAbs().maxCoeff()));
    EXPECT_LE((global[k] - dec_os).cwiseAbs().maxCoeff(),
              1e-12 * (1.0 + dec_os.cwiseAbs().maxCoeff()));
  }
}

TEST(Listing, RejectsWhatTheModelCannotUse) {
  const SurveyErrorModel& model = survey_error_model("mwd_rev5");
  const WellParameters well = north_sea_well();
  const std::vector<ListingStation> one = {{0.0, 0.0, 0.0}};
  EXPECT_THROW(propagate_survey_errors(model, one, well), std::invalid_argument);
  const std::vector<ListingStation> backwards = {
      {0.0, 0.0, 0.0}, {30.0, 0.1, 0.0}, {20.0, 0.1, 0.0}};
  EXPECT_THROW(propagate_survey_errors(model, backwards, well), std::invalid_argument);
  const std::vector<ListingStation> below_surface = {{500.0, 0.0, 0.0}, {530.0, 0.1, 0.0}};
  EXPECT_THROW(propagate_survey_errors(model, below_surface, well), std::invalid_argument);
  WellParameters tied_on = well;
  tied_on.tie_on_tvd_m = 480.0;
  EXPECT_NO_THROW(propagate_survey_errors(model, below_surface, tied_on));
}

TEST(ModelTable, NamesTheIscwsaSourcesAndRefusesUnknownModels) {
  EXPECT_EQ(survey_error_model("mwd_rev5").sources.size(), 35u);
  EXPECT_EQ(survey_error_model("mwd_rev4").sources.size(), 27u);
  EXPECT_THROW(survey_error_model("mwd_rev9"), ConfigError);
  try {
    survey_error_model("mwd_rev");
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("did you mean"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace stochnav::survey_error
