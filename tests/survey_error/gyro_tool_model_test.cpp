// The OWSG gyro tool model GYRO-NS-CT as a whole (`--model gyro_ns_ct`):
//  - its sources, order, modes and magnitudes are the OWSG table's;
//  - the covariances of the terms new to it (AXYZ-*, GXY-B1S/B2S/G4 with their carrying into the
//    continuous survey, SAGE at the gyro magnitude) and two shared ones (XYM1, XYM2) equal those
//    of an independent evaluation of the OWSG JSON's own formula strings
//    (owsg_gyro_reference.py, reading welleng's GYRO-NS-CT.json);
//  - Monte Carlo: each group's sensor errors simulated as the model defines them, the perturbed
//    survey turned into positions by exact minimum curvature, the scatter compared with the
//    propagated covariance in 3-D (chi-square along its principal axes); the same check rejects
//    the gyrocompass terms evaluated at every station instead of carried;
//  - the same Monte Carlo for the gyro terms of the stationary gyro tool models GYRO-NS and
//    GYRO-MWD (every station its own gyrocompass: random biases and noise, systematic
//    g-dependent terms).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/minimum_curvature.hpp"
#include "stochnav/sim/normal_generator.hpp"
#include "stochnav/survey_error/tool_models.hpp"
#include "stochnav/survey_error/weighting_functions.hpp"
#include "owsg_reference.hpp"

namespace stochnav::survey_error {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// owsg_reference.hpp's well: gyrocompass stations to 14 deg, the continuous survey
// initialised at the 16-deg station (18).
using testing::largest_error_against;
using testing::ReferenceCovariance;
using testing::reference_site;
using testing::reference_well;
using testing::source_named;

TEST(GyroToolModel, TheOwsgSourcesInTheOwsgOrder) {
  const SurveyCovariance covariance = tool_model_covariance(
      kGyroNsCtModelName, reference_well(), reference_site(), owsg_gyro_ns_ct_terms());
  const std::vector<std::string> expected = {"DRFR",    "DSFS",    "DSTG",    "XYM1",    "XYM2",
                                             "XYM3E",   "XYM4E",   "XCLA",    "XCLH",    "AXYZ-MIS",
                                             "AXYZ-SF", "AXYZ-ZB", "GXY-B1S", "GXY-B2S", "GXY-G4",
                                             "GXY-RN",  "GXY-GD",  "GXY-GRW", "SAGE"};
  ASSERT_EQ(covariance.sources.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(covariance.sources[i].code, expected[i]);
  }
  const SurveyErrorModel table = gyro_ns_ct_table_model(owsg_gyro_ns_ct_terms());
  ASSERT_EQ(table.sources.size(), 16u);
  const auto row = [&](const std::string& code) {
    return *std::find_if(table.sources.begin(), table.sources.end(),
                         [&](const ErrorSource& s) { return s.code == code; });
  };
  EXPECT_NEAR(row("AXYZ-MIS").magnitude_si(), 0.0095 * kRadPerDeg, 1e-18);
  EXPECT_EQ(row("AXYZ-SF").magnitude_si(), 0.000111);
  EXPECT_EQ(row("AXYZ-ZB").magnitude_si(), 0.0017);
  EXPECT_NEAR(row("GXY-B1S").magnitude_si(), 0.15 * kRadPerDeg / 3600.0, 1e-20);
  EXPECT_NEAR(row("GXY-G4").magnitude_si(), 0.6 * kRadPerDeg / 3600.0, 1e-20);
  EXPECT_NEAR(row("SAGE").magnitude_si(), 0.08 * kRadPerDeg, 1e-18);
  EXPECT_EQ(row("XYM3E").mode, PropagationMode::kRandom);
  EXPECT_EQ(row("DSTG").mode, PropagationMode::kGlobal);
  EXPECT_EQ(row("GXY-B2S").mode, PropagationMode::kSystematic);
  EXPECT_EQ(source_named(covariance, "GXY-RN").mode, PropagationMode::kRandom);
}

TEST(GyroToolModel, TotalIsTheSumSymmetricPsdWithAVerticalPart) {
  const auto stations = reference_well();
  const SurveyCovariance covariance = tool_model_covariance(
      kGyroNsCtModelName, stations, reference_site(), owsg_gyro_ns_ct_terms());
  EXPECT_EQ(covariance.total_nev_m2.front(), Matrix3d::Zero()) << "the tie-on is exact";
  for (std::size_t k = 1; k < stations.size(); ++k) {
    Matrix3d sum = Matrix3d::Zero();
    for (const auto& source : covariance.sources) {
      ASSERT_TRUE(source.nev_m2[k].allFinite()) << source.code << " station " << k;
      sum += source.nev_m2[k];
    }
    const Matrix3d& total = covariance.total_nev_m2[k];
    EXPECT_LE((sum - total).cwiseAbs().maxCoeff(), 1e-12 * total.cwiseAbs().maxCoeff());
    EXPECT_LE((total - total.transpose()).cwiseAbs().maxCoeff(), 1e-12 * total.norm());
    const Eigen::SelfAdjointEigenSolver<Matrix3d> solver(total);
    EXPECT_GT(solver.eigenvalues().minCoeff(), 0.0) << "station " << k;
  }
  // The depth, inclination and sag terms give the deep stations a vertical uncertainty of
  // metres.
  EXPECT_GT(std::sqrt(covariance.total_nev_m2.back()(2, 2)), 1.0);
}

// owsg_gyro_reference.py's output: NN, EE, VV, NE, NV, EV (m^2) at stations 12 (gyrocompass at
// 4 deg), 18 (initialising), 40 and 80 (continuous).
// clang-format off
constexpr ReferenceCovariance kOwsgFormulaReference[] = {
{"AXYZ-MIS", 12, {0.0024354607981537878, 0.00083478418009218279, 1.2046979562128031e-07, 0.001425862597003464, -1.7128907279719482e-05, -1.0028274007204995e-05}},
{"AXYZ-MIS", 18, {0.005154078150063939, 0.0022750289680248509, 3.0466511838257229e-05, 0.0034242776018978652, -0.00039626605074649771, -0.00026327209686312608}},
{"AXYZ-MIS", 40, {0.011453508860437762, 0.015423047118051817, 0.0048929806314205113, 0.013290899398519108, -0.007486106933241414, -0.0086870403951008236}},
{"AXYZ-MIS", 80, {0.016700290586729907, 0.062570235760929224, 0.049447446492311718, 0.032325549017576137, -0.028736505097060501, -0.055623182080854351}},
{"AXYZ-SF", 12, {6.3772676251462033e-08, 2.6890478244297538e-08, 2.4888619980714949e-10, 4.1411082614688672e-08, -3.9839853217297425e-09, -2.5870193159735093e-09}},
{"AXYZ-SF", 18, {1.2217865028060922e-05, 9.0068700597213672e-06, 7.6014613798838782e-07, 1.049022033681651e-05, -3.04751750044916e-06, -2.6165889037562697e-06}},
{"AXYZ-SF", 40, {0.00025643479347468395, 0.0010532891511689779, 0.0007155673957901852, 0.00051971144488950985, -0.00042836477137677136, -0.00086815861161197976}},
{"AXYZ-SF", 80, {0.00065181808797174921, 0.0074699440385594673, 0.0084762600992844515, 0.0022065911810912773, -0.0023505275261240443, -0.0079572098500623554}},
{"AXYZ-ZB", 12, {9.2314938439067168e-08, 3.892837113861706e-08, 3.6050608524070693e-10, 5.9947228336217454e-08, -5.7688904536232058e-09, -3.7461866856818759e-09}},
{"AXYZ-ZB", 18, {1.8318396274918834e-05, 1.3545979948428644e-05, 1.1507733687821598e-06, 1.5752480078623191e-05, -4.5913312439830465e-06, -3.9482088316993588e-06}},
{"AXYZ-ZB", 40, {0.00051194069317678811, 0.0025170539233054642, 0.0019010031124068877, 0.001135157403297161, -0.00098650942777898172, -0.0021874476776141765}},
{"AXYZ-ZB", 80, {0.0016332141417548648, 0.022814587819480335, 0.027447502526548297, 0.0061041876990377327, -0.0066953453445069621, -0.025024057561022044}},
{"GXY-B1S", 12, {0.00015399814774191215, 0.00036439178543380327, 0, -0.00023688744164512813, -0, 0}},
{"GXY-B1S", 18, {0.083796767218722423, 0.11029514650380601, 0, -0.096137280578006357, -0, 0}},
{"GXY-B1S", 40, {31.915697051444891, 5.2550494900886733, 0, -12.950620352555319, -0, 0}},
{"GXY-B1S", 80, {367.16397775517692, 21.85508038264193, 0, -89.57900561766661, -0, 0}},
{"GXY-B2S", 12, {0.00036327227335565283, 0.00086215216261863062, 0, -0.00055963914810613674, -0, 0}},
{"GXY-B2S", 18, {0.10591567317055869, 0.14495735857610953, 0, -0.12390825724952595, -0, 0}},
{"GXY-B2S", 40, {28.100098150474313, 4.8418606087479299, 0, -11.66433702945573, -0, 0}},
{"GXY-B2S", 80, {318.4077420496057, 19.466604990167262, 0, -78.729395655566577, -0, 0}},
{"GXY-G4", 12, {6.9932545325503515e-06, 1.6136835823746236e-05, 0, -1.0623041008366402e-05, -0, 0}},
{"GXY-G4", 18, {0.051777468874474777, 0.062513751212546598, 0, -0.056892915267494341, -0, 0}},
{"GXY-G4", 40, {37.664299396344013, 5.8145396895587549, 0, -14.798667633252194, -0, 0}},
{"GXY-G4", 80, {442.46747173166136, 25.383633636013712, 0, -105.97845157526008, -0, 0}},
{"SAGE", 12, {0.00058786903207002944, 0.00024312476668342963, 1.9117869870293115e-06, 0.00037805491831536793, -3.352432498334604e-05, -2.1559284894678634e-05}},
{"SAGE", 18, {0.020699462134805582, 0.01369877222775618, 0.00090299757995385588, 0.016839157253905713, -0.0043233741700292282, -0.0035170951323504063}},
{"SAGE", 40, {0.15286534431366103, 0.45588174971374995, 0.26105146867077123, 0.26398583415840066, -0.19976416756251442, -0.34497623150439705}},
{"SAGE", 80, {0.3202930986283789, 2.7804324218453269, 2.9299825709870957, 0.94369132449103699, -0.96873794009969538, -2.8542281856596974}},
{"XYM1", 12, {9.3577239177446161e-06, 3.9460671895819028e-06, 3.6543559183285854e-08, 6.0766937820642122e-06, -5.8477734036892198e-07, -3.7974114852581986e-07}},
{"XYM1", 18, {0.0018568879301119534, 0.0013731205663573927, 0.00011665088726744078, 0.0015967877148379906, -0.00046541124245527303, -0.00040021960520539301}},
{"XYM1", 40, {0.051894089407525733, 0.25514717442957846, 0.19269971462331234, 0.11506793767999021, -0.09999988109726364, -0.22173585118226657}},
{"XYM1", 80, {0.16555464690241825, 2.3126551100150752, 2.7822815593878016, 0.61876554537693762, -0.67868965009609294, -2.5366232802327806}},
{"XYM2", 12, {3.9583033929444675e-06, 9.3860846571865916e-06, 0, -6.0953236784444598e-06, 0, -0}},
{"XYM2", 18, {0.0014313298428100306, 0.0019296280451238774, 0, -0.0016619067983822036, 0, -0}},
{"XYM2", 40, {0.44167896551609609, 0.074611445549037855, 0, -0.18153320931928563, 0, -0}},
{"XYM2", 80, {5.0382947647845926, 0.3044303211272264, 0, -1.2384707074359882, 0, -0}},
};
// clang-format on

TEST(OwsgGyroReference, CovariancesEqualThoseOfTheOwsgFormulaStrings) {
  const SurveyCovariance covariance = tool_model_covariance(
      kGyroNsCtModelName, reference_well(), reference_site(), owsg_gyro_ns_ct_terms());
  std::printf("OWSG formula reference: largest error %.2g of the largest variance\n",
              largest_error_against(covariance, kOwsgFormulaReference, "GYRO-NS-CT"));
}

TEST(GyroToolModel, AGyrocompassStationAtNinetyDegreesIsRefused) {
  const std::vector<ListingStation> stations = {{0, 0, 0}, {30, std::numbers::pi / 2, 0}};
  EXPECT_THROW(tool_model_covariance(kGyroNsCtModelName, stations, reference_site(),
                                     owsg_gyro_ns_ct_terms()),
               std::invalid_argument);
  WellParameters pole = reference_site();
  pole.latitude_rad = std::numbers::pi / 2;
  EXPECT_THROW(propagate_survey_errors(gyro_ns_ct_table_model(owsg_gyro_ns_ct_terms()),
                                       reference_well(), pole),
               std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Monte Carlo.

/// One source as the simulation draws it: the change of a station's MD (m), inclination and
/// sideways hole turn sin(I) dA (rad) per unit of the source, written out here from the OWSG
/// definitions (not taken from the library), and whether it is redrawn at every station.
struct SimulatedSource {
  std::string code;
  bool random = false;
  double magnitude = 0.0;  ///< SI, 1 sigma
  std::function<std::array<double, 3>(std::size_t k)> per_unit;
};

/// The stations' true TVD by minimum curvature (DSTG).
std::vector<double> true_tvd_m(const std::vector<ListingStation>& stations) {
  std::vector<double> tvd = {0.0};
  for (std::size_t k = 1; k < stations.size(); ++k) {
    tvd.push_back(
        tvd.back() +
        minimum_curvature_step(
            hole_direction_nev(stations[k - 1].inclination_rad, stations[k - 1].azimuth_rad),
            hole_direction_nev(stations[k].inclination_rad, stations[k].azimuth_rad),
            stations[k].md_m - stations[k - 1].md_m)
            .z());
  }
  return tvd;
}

/// The simulated definitions of GYRO-NS-CT's table terms at `scale` times the OWSG magnitudes.
/// `carry`: the gyrocompass terms keep the initialising station's azimuth error in the
/// continuous survey (the model) or, false, are evaluated at every station (what it is not).
std::vector<SimulatedSource> simulated_table_sources(const std::vector<ListingStation>& s,
                                                     const WellParameters& well, double scale,
                                                     bool carry) {
  const std::size_t initialising = continuous_initialisation_station(s, owsg_gyro_ns_ct_terms());
  const std::vector<double> tvd = true_tvd_m(s);
  const auto inc = [&s](std::size_t k) { return s[k].inclination_rad; };
  const auto azi = [&s](std::size_t k) { return s[k].azimuth_rad; };
  const double horizontal_rate = well.earth_rate_rad_s * std::cos(well.latitude_rad);
  const auto compass = [initialising, carry](std::size_t k) {
    return carry ? std::min(k, initialising) : k;
  };
  const double deg = kRadPerDeg;
  const double deg_h = kRadPerDeg / 3600.0;
  const auto short_interval = [&s](std::size_t k) {
    return std::max(1.0, std::sqrt(10.0 / (s[k].md_m - s[k - 1].md_m)));
  };
  using Weights = std::array<double, 3>;
  return {
      {"DRFR", true, scale * 0.35,
       [](std::size_t) {
         return Weights{1, 0, 0};
       }},
      {"DSFS", false, scale * 0.00056,
       [&s](std::size_t k) {
         return Weights{s[k].md_m, 0, 0};
       }},
      {"DSTG", false, scale * 2.5e-7,
       [&s, tvd](std::size_t k) {
         return Weights{s[k].md_m * tvd[k], 0, 0};
       }},
      {"XYM1", false, scale * 0.1 * deg,
       [inc](std::size_t k) {
         return Weights{0, std::abs(std::sin(inc(k))), 0};
       }},
      {"XYM2", false, scale * 0.1 * deg,
       [inc](std::size_t k) {
         return Weights{0, 0, -std::sin(inc(k))};
       }},
      {"XYM3E", true, scale * 0.3 * deg,
       [inc, azi, short_interval](std::size_t k) {
         const double f = short_interval(k) * std::abs(std::cos(inc(k)));
         return Weights{0, f * std::cos(azi(k)), -f * std::sin(azi(k))};
       }},
      {"XYM4E", true, scale * 0.3 * deg,
       [inc, azi, short_interval](std::size_t k) {
         const double f = short_interval(k) * std::abs(std::cos(inc(k)));
         return Weights{0, f * std::sin(azi(k)), f * std::cos(azi(k))};
       }},
      {"AXYZ-MIS", false, scale * 0.0095 * deg,
       [](std::size_t) {
         return Weights{0, 1, 0};
       }},
      {"AXYZ-SF", false, scale * 0.000111,
       [inc](std::size_t k) {
         return Weights{0, 1.3 * std::sin(inc(k)) * std::cos(inc(k)), 0};
       }},
      {"AXYZ-ZB", false, scale * 0.0017,
       [inc, well](std::size_t k) {
         return Weights{0, std::sin(inc(k)) / well.gravity_m_s2, 0};
       }},
      {"GXY-B1S", false, scale * 0.15 * deg_h,
       [inc, azi, compass, horizontal_rate](std::size_t k) {
         const std::size_t c = compass(k);
         return Weights{0, 0,
                        std::sin(inc(k)) * std::sin(azi(c)) / (horizontal_rate * std::cos(inc(c)))};
       }},
      {"GXY-B2S", false, scale * 0.15 * deg_h,
       [inc, azi, compass, horizontal_rate](std::size_t k) {
         return Weights{0, 0, std::sin(inc(k)) * std::cos(azi(compass(k))) / horizontal_rate};
       }},
      {"GXY-G4", false, scale * 0.6 * deg_h,
       [inc, azi, compass, horizontal_rate](std::size_t k) {
         const std::size_t c = compass(k);
         return Weights{0, 0,
                        std::sin(inc(k)) * std::sin(azi(c)) * std::tan(inc(c)) / horizontal_rate};
       }},
      {"SAGE", false, scale * 0.08 * deg,
       [inc](std::size_t k) {
         return Weights{0, std::pow(std::sin(inc(k)), 0.25), 0};
       }},
  };
}

/// The continuous-gyro terms' azimuth errors (rad) for one draw, as continuous_gyro.hpp
/// defines them (gyrocompass noise, the initialising error carried on, drift, random walk).
std::vector<double> simulated_continuous_azimuth_errors(const std::vector<ListingStation>& s,
                                                        const ContinuousGyroTerms& terms,
                                                        const WellParameters& well,
                                                        NormalGenerator& normal) {
  const std::size_t initialising = continuous_initialisation_station(s, terms);
  std::vector<double> errors(s.size(), 0.0);
  const double drift_rate = terms.drift_rad_s * normal();
  double carried_rad = 0.0;
  for (std::size_t k = 1; k < s.size(); ++k) {
    const double inc = s[k].inclination_rad;
    if (k <= initialising) {
      const double gain_s =
          terms.noise_reduction_factor *
          std::sqrt(1.0 - std::pow(std::cos(s[k].azimuth_rad) * std::sin(inc), 2)) /
          (well.earth_rate_rad_s * std::cos(well.latitude_rad) * std::cos(inc));
      errors[k] = carried_rad = terms.noise_rad_s * gain_s * normal();
      continue;
    }
    const double time_s = (s[k].md_m - s[k - 1].md_m) / terms.running_speed_m_s;
    const double mean_sine = std::sin((inc + s[k - 1].inclination_rad) / 2.0);
    carried_rad += drift_rate * time_s / mean_sine +
                   terms.random_walk_rad_per_sqrt_s * std::sqrt(time_s) / mean_sine * normal();
    errors[k] = carried_rad;
  }
  return errors;
}

/// Positions (NEV, m) by exact minimum curvature from the tie-on at the origin, of stations at
/// `md_m` with hole directions `direction`.
std::vector<Vector3d> positions_from_directions(const std::vector<double>& md_m,
                                                const std::vector<Vector3d>& direction) {
  std::vector<Vector3d> positions = {Vector3d::Zero()};
  for (std::size_t k = 1; k < md_m.size(); ++k) {
    positions.push_back(positions.back() + minimum_curvature_step(direction[k - 1], direction[k],
                                                                  md_m[k] - md_m[k - 1]));
  }
  return positions;
}

/// Draws `draws` surveys with the sources' errors (and the continuous-gyro terms' when
/// `continuous` is given) and compares the scatter of the position errors at the test stations
/// with `propagated` along its principal axes: an axis with variance lambda >= 1 % of the
/// largest must give sum over draws of (u^T r)^2 / lambda within 5 standard deviations of its
/// chi-square mean; a smaller axis (a single variable moves a station along a line) must hold
/// a mean square within 0.2 % of the largest variance. Reports failures when `expect_pass`.
bool tool_monte_carlo_agrees(const std::vector<SimulatedSource>& sources,
                             const ContinuousGyroTerms* continuous,
                             const std::vector<Matrix3d>& propagated, bool expect_pass) {
  const auto stations = reference_well();
  const WellParameters well = reference_site();
  const std::size_t n = stations.size();
  const std::vector<std::size_t> checked = {
      12, continuous_initialisation_station(stations, owsg_gyro_ns_ct_terms()), 40, n - 1};
  std::vector<double> true_md(n);
  std::vector<Vector3d> true_direction(n);
  for (std::size_t k = 0; k < n; ++k) {
    true_md[k] = stations[k].md_m;
    true_direction[k] = hole_direction_nev(stations[k].inclination_rad, stations[k].azimuth_rad);
  }
  const std::vector<Vector3d> truth = positions_from_directions(true_md, true_direction);
  std::vector<Matrix3d> scatter(checked.size(), Matrix3d::Zero());
  constexpr int kDraws = 20000;
  NormalGenerator normal(20261128);
  std::vector<double> systematic(sources.size());
  for (int draw = 0; draw < kDraws; ++draw) {
    for (double& z : systematic) z = normal();
    std::vector<double> md = true_md;
    std::vector<Vector3d> direction = true_direction;
    const std::vector<double> azimuth_errors =
        continuous ? simulated_continuous_azimuth_errors(stations, *continuous, well, normal)
                   : std::vector<double>(n, 0.0);
    for (std::size_t k = 1; k < n; ++k) {
      const double inc = stations[k].inclination_rad;
      const double azi = stations[k].azimuth_rad;
      const Vector3d d_dinc(std::cos(inc) * std::cos(azi), std::cos(inc) * std::sin(azi),
                            -std::sin(inc));
      const Vector3d sideways(-std::sin(azi), std::cos(azi), 0.0);
      Vector3d turn = std::sin(inc) * azimuth_errors[k] * sideways;
      for (std::size_t i = 0; i < sources.size(); ++i) {
        const double e = sources[i].magnitude * (sources[i].random ? normal() : systematic[i]);
        const std::array<double, 3> w = sources[i].per_unit(k);
        md[k] += e * w[0];
        turn += e * (w[1] * d_dinc + w[2] * sideways);
      }
      direction[k] = (true_direction[k] + turn).normalized();
    }
    const std::vector<Vector3d> positions = positions_from_directions(md, direction);
    for (std::size_t i = 0; i < checked.size(); ++i) {
      const Vector3d r = positions[checked[i]] - truth[checked[i]];
      scatter[i] += r * r.transpose();
    }
  }
  bool all_passed = true;
  double worst_ratio_error = 0.0;  // over the non-degenerate axes: |simulated / propagated - 1|
  for (std::size_t i = 0; i < checked.size(); ++i) {
    const Matrix3d& p = propagated[checked[i]];
    const Eigen::SelfAdjointEigenSolver<Matrix3d> axes(p);
    const double largest = axes.eigenvalues().maxCoeff();
    for (int a = 0; a < 3; ++a) {
      const Vector3d u = axes.eigenvectors().col(a);
      const double variance = axes.eigenvalues()(a);
      const double mean_square = u.dot(scatter[i] * u) / kDraws;
      bool passed = false;
      std::string tolerance;
      if (variance >= 0.01 * largest && variance > 0.0) {
        const double allowed = 5.0 * std::sqrt(2.0 / kDraws);
        worst_ratio_error = std::max(worst_ratio_error, std::abs(mean_square / variance - 1.0));
        passed = std::abs(mean_square / variance - 1.0) <= allowed;
        tolerance = "relative " + std::to_string(allowed);
      } else {
        passed = std::abs(mean_square - variance) <= 2e-3 * largest + 1e-20;
        tolerance = "degenerate axis, 0.2 % of " + std::to_string(largest);
      }
      all_passed = all_passed && passed;
      if (expect_pass) {
        EXPECT_TRUE(passed) << "station " << checked[i] << ", axis variance " << variance
                            << " m^2, simulated " << mean_square << " m^2 (" << tolerance << ")";
      }
    }
  }
  std::printf("Monte Carlo: largest |simulated / propagated - 1| over the axes %.3f\n",
              worst_ratio_error);
  return all_passed;
}

/// A tenth of the OWSG magnitudes (the propagation is linear in them): the simulated exact
/// minimum curvature then stays within the tolerance of its first-order expansion.
constexpr double kMonteCarloScale = 0.1;

SurveyErrorModel scaled_table_model(bool carry) {
  SurveyErrorModel model = gyro_ns_ct_table_model(owsg_gyro_ns_ct_terms());
  for (ErrorSource& source : model.sources) source.magnitude *= kMonteCarloScale;
  if (!carry) model.continuous_start_inclination_rad.reset();
  return model;
}

ContinuousGyroTerms scaled_continuous_terms() {
  ContinuousGyroTerms terms = owsg_gyro_ns_ct_terms();
  terms.noise_rad_s *= kMonteCarloScale;
  terms.drift_rad_s *= kMonteCarloScale;
  terms.random_walk_rad_per_sqrt_s *= kMonteCarloScale;
  return terms;
}

/// The propagated covariance of the named sources of `covariance`, summed per station.
std::vector<Matrix3d> summed_sources(const SurveyCovariance& covariance,
                                     const std::vector<std::string>& codes) {
  std::vector<Matrix3d> sum(covariance.md_m.size(), Matrix3d::Zero());
  for (const std::string& code : codes) {
    const auto& source = source_named(covariance, code);
    for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += source.nev_m2[k];
  }
  return sum;
}

struct SourceGroup {
  std::string name;
  std::vector<std::string> codes;
};

class GyroToolMonteCarlo : public ::testing::TestWithParam<SourceGroup> {};

TEST_P(GyroToolMonteCarlo, SimulatedScatterMatchesThePropagatedCovariance) {
  const auto stations = reference_well();
  const WellParameters well = reference_site();
  const SurveyCovariance propagated =
      propagate_survey_errors(scaled_table_model(true), stations, well);
  std::vector<SimulatedSource> simulated;
  for (SimulatedSource& source : simulated_table_sources(stations, well, kMonteCarloScale, true)) {
    const auto& codes = GetParam().codes;
    if (std::find(codes.begin(), codes.end(), source.code) != codes.end()) {
      simulated.push_back(std::move(source));
    }
  }
  ASSERT_EQ(simulated.size(), GetParam().codes.size());
  EXPECT_TRUE(tool_monte_carlo_agrees(simulated, nullptr,
                                      summed_sources(propagated, GetParam().codes), true));
}

INSTANTIATE_TEST_SUITE_P(
    Groups, GyroToolMonteCarlo,
    ::testing::Values(SourceGroup{"depth", {"DRFR", "DSFS", "DSTG"}},
                      SourceGroup{"accelerometers", {"AXYZ-MIS", "AXYZ-SF", "AXYZ-ZB"}},
                      SourceGroup{"gyrocompass", {"GXY-B1S", "GXY-B2S", "GXY-G4"}},
                      SourceGroup{"gyro_b1", {"GXY-B1S"}},
                      SourceGroup{"misalignment_and_sag",
                                  {"XYM1", "XYM2", "XYM3E", "XYM4E", "SAGE"}}),
    [](const ::testing::TestParamInfo<SourceGroup>& group) { return group.param.name; });

TEST(GyroToolMonteCarloWhole, EverySourceButTheUnseenTortuosityTogether) {
  // XCLA and XCLH bend the path between stations where the survey does not see it; a listing
  // perturbed at its stations cannot simulate them (they are the Rev5 terms, checked against
  // the ISCWSA workbook).
  const auto stations = reference_well();
  const WellParameters well = reference_site();
  const ContinuousGyroTerms continuous = scaled_continuous_terms();
  SurveyCovariance propagated = propagate_survey_errors(scaled_table_model(true), stations, well);
  const auto gyro = continuous_gyro_covariance(continuous, stations, well);
  propagated.sources.insert(propagated.sources.end(), gyro.begin(), gyro.end());
  std::vector<std::string> codes = {"GXY-RN", "GXY-GD", "GXY-GRW"};
  for (const auto& source : simulated_table_sources(stations, well, kMonteCarloScale, true)) {
    codes.push_back(source.code);
  }
  EXPECT_TRUE(
      tool_monte_carlo_agrees(simulated_table_sources(stations, well, kMonteCarloScale, true),
                              &continuous, summed_sources(propagated, codes), true));
}

TEST(GyroToolMonteCarloWhole, GyrocompassTermsEvaluatedAtEveryStationFailTheSameTest) {
  // Without the carrying into the continuous survey, GXY-B1S would follow each continuous
  // station's own inclination and azimuth: a different covariance, which the simulation of the
  // model (the initialising gyrocompass's error kept) rejects.
  const auto stations = reference_well();
  const WellParameters well = reference_site();
  const SurveyCovariance not_carried =
      propagate_survey_errors(scaled_table_model(false), stations, well);
  std::vector<SimulatedSource> simulated;
  for (SimulatedSource& source : simulated_table_sources(stations, well, kMonteCarloScale, true)) {
    if (source.code == "GXY-B1S") simulated.push_back(std::move(source));
  }
  EXPECT_FALSE(
      tool_monte_carlo_agrees(simulated, nullptr, summed_sources(not_carried, {"GXY-B1S"}), false));
}

// ---------------------------------------------------------------------------------------------
// The stationary gyro tool models GYRO-NS and GYRO-MWD (stationary_gyro_tool_model_test.cpp
// checks them against the OWSG formula strings): their gyro terms simulated as the OWSG tables
// define them, with every station its own gyrocompass: GXY-B1R, GXY-B2R and GXY-RN redrawn at
// every station, GXY-G1 and GXY-G4 drawn once per survey.

struct StationaryGyroMagnitudesDegH {
  std::string model;
  double g1, g4, rn;
};

std::vector<SimulatedSource> simulated_stationary_gyro_sources(
    const std::vector<ListingStation>& s, const WellParameters& well,
    const StationaryGyroMagnitudesDegH& magnitudes, double scale) {
  const auto inc = [&s](std::size_t k) { return s[k].inclination_rad; };
  const auto azi = [&s](std::size_t k) { return s[k].azimuth_rad; };
  const double horizontal_rate = well.earth_rate_rad_s * std::cos(well.latitude_rad);
  const double deg_h = kRadPerDeg / 3600.0;
  using Weights = std::array<double, 3>;
  return {
      {"GXY-B1R", true, scale * 0.15 * deg_h,
       [inc, azi, horizontal_rate](std::size_t k) {
         return Weights{0, 0, std::tan(inc(k)) * std::sin(azi(k)) / horizontal_rate};
       }},
      {"GXY-B2R", true, scale * 0.15 * deg_h,
       [inc, azi, horizontal_rate](std::size_t k) {
         return Weights{0, 0, std::sin(inc(k)) * std::cos(azi(k)) / horizontal_rate};
       }},
      {"GXY-G1", false, scale * magnitudes.g1 * deg_h,
       [inc, azi, horizontal_rate](std::size_t k) {
         return Weights{0, 0, std::pow(std::sin(inc(k)), 2) * std::cos(azi(k)) / horizontal_rate};
       }},
      {"GXY-G4", false, scale * magnitudes.g4 * deg_h,
       [inc, azi, horizontal_rate](std::size_t k) {
         return Weights{0, 0,
                        std::sin(inc(k)) * std::sin(azi(k)) * std::tan(inc(k)) / horizontal_rate};
       }},
      {"GXY-RN", true, scale * magnitudes.rn * deg_h,
       [inc, azi, horizontal_rate](std::size_t k) {
         // noise reduction factor 1
         const double across = std::sqrt(1.0 - std::pow(std::cos(azi(k)) * std::sin(inc(k)), 2));
         return Weights{0, 0, std::tan(inc(k)) * across / horizontal_rate};
       }},
  };
}

void PrintTo(const StationaryGyroMagnitudesDegH& m, std::ostream* os) { *os << m.model; }

class StationaryGyroMonteCarlo : public ::testing::TestWithParam<StationaryGyroMagnitudesDegH> {};

TEST_P(StationaryGyroMonteCarlo, GyroTermsMatchThePropagatedCovariance) {
  const auto stations = reference_well();
  const WellParameters well = reference_site();
  SurveyErrorModel model =
      GetParam().model == kGyroNsModelName ? gyro_ns_model() : gyro_mwd_model();
  for (ErrorSource& source : model.sources) source.magnitude *= kMonteCarloScale;
  const SurveyCovariance propagated = propagate_survey_errors(model, stations, well);
  const std::vector<SimulatedSource> simulated =
      simulated_stationary_gyro_sources(stations, well, GetParam(), kMonteCarloScale);
  std::vector<std::string> codes;
  for (const SimulatedSource& source : simulated) codes.push_back(source.code);
  EXPECT_TRUE(tool_monte_carlo_agrees(simulated, nullptr, summed_sources(propagated, codes), true));
}

INSTANTIATE_TEST_SUITE_P(
    Models, StationaryGyroMonteCarlo,
    ::testing::Values(StationaryGyroMagnitudesDegH{std::string(kGyroNsModelName), 0.2, 0.6, 0.4},
                      StationaryGyroMagnitudesDegH{std::string(kGyroMwdModelName), 0.4, 1.0, 0.6}),
    [](const ::testing::TestParamInfo<StationaryGyroMagnitudesDegH>& p) { return p.param.model; });

}  // namespace
}  // namespace stochnav::survey_error
