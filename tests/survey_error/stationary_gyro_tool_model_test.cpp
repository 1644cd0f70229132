// The OWSG stationary gyro tool models GYRO-NS and GYRO-MWD as a whole (`--model gyro_ns`,
// `--model gyro_mwd`):
//  - their sources, order, modes and magnitudes are the OWSG tables' (welleng's GYRO-NS.json and
//    GYRO-MWD.json);
//  - the covariances of every source whose formulas need neither the previous station nor the
//    TVD (13 of the 18: DRFR, DSFS, SAGE, XYM1, XYM2, AXYZ-*, GXY-B1R, GXY-B2R, GXY-G1, GXY-G4,
//    GXY-RN) equal those of an independent evaluation of the JSONs' own formula strings, with
//    the JSONs' propagation modes (owsg_gyro_reference.py); the other five are the ISCWSA MWD
//    Rev5 rows validated against the ISCWSA workbook (iscwsa_example_test.cpp);
//  - the two models differ only by GXY-G1, GXY-G4 and GXY-RN, in the ratio of their magnitudes;
//  - a gyrocompass station at 90 deg, or a well at a pole, is refused.
// Every term is plain random or systematic (every station is a gyrocompass station; nothing is
// carried between stations), which the ISCWSA propagation validated against the workbook and
// GyroToolMonteCarlo already covers; no Monte Carlo is needed for a correlation of its own.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "stochnav/core/angles.hpp"
#include "stochnav/survey_error/tool_models.hpp"
#include "owsg_reference.hpp"

namespace stochnav::survey_error {
namespace {

using Eigen::Matrix3d;

using testing::ReferenceCovariance;
using testing::reference_site;
using testing::reference_well;
using testing::source_named;

/// One row of an OWSG table as the JSON gives it.
struct OwsgRow {
  const char* code;
  double magnitude;  ///< in the JSON's unit
  MagnitudeUnit unit;
  PropagationMode mode;
};

/// GYRO-NS.json (rev 5), in its order; GYRO-MWD.json has the same rows with GXY-G1 0.4, GXY-G4
/// 1.0 and GXY-RN 0.6 deg/h.
std::vector<OwsgRow> owsg_rows(double g1, double g4, double rn) {
  using enum MagnitudeUnit;
  using enum PropagationMode;
  return {{"DRFR", 0.35, kMetre, kRandom},
          {"DSFS", 0.00056, kDimensionless, kSystematic},
          {"DSTG", 2.5e-7, kPerMetre, kGlobal},
          {"SAGE", 0.2, kDegree, kSystematic},
          {"XYM1", 0.1, kDegree, kSystematic},
          {"XYM2", 0.1, kDegree, kSystematic},
          {"XYM3E", 0.3, kDegree, kRandom},
          {"XYM4E", 0.3, kDegree, kRandom},
          {"XCLA", 0.167, kDimensionless, kRandom},
          {"XCLH", 0.167, kDimensionless, kRandom},
          {"AXYZ-MIS", 0.0095, kDegree, kSystematic},
          {"AXYZ-SF", 0.000111, kDimensionless, kSystematic},
          {"AXYZ-ZB", 0.0017, kMetrePerSecond2, kSystematic},
          {"GXY-B1R", 0.15, kDegreePerHour, kRandom},
          {"GXY-B2R", 0.15, kDegreePerHour, kRandom},
          {"GXY-G1", g1, kDegreePerHour, kSystematic},
          {"GXY-G4", g4, kDegreePerHour, kSystematic},
          {"GXY-RN", rn, kDegreePerHour, kRandom}};
}

void expect_owsg_table(const SurveyErrorModel& model, const std::vector<OwsgRow>& rows) {
  ASSERT_EQ(model.sources.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ErrorSource& source = model.sources[i];
    EXPECT_EQ(source.code, rows[i].code);
    EXPECT_EQ(source.magnitude, rows[i].magnitude) << source.code;
    EXPECT_EQ(source.unit, rows[i].unit) << source.code;
    EXPECT_EQ(source.mode, rows[i].mode) << source.code;
  }
  EXPECT_EQ(model.noise_reduction_factor, 1.0);
  EXPECT_FALSE(model.continuous_start_inclination_rad) << "a gyrocompass at every station";
  EXPECT_FALSE(model.first_station_turns_whole_first_leg);
}

TEST(StationaryGyroToolModel, TheOwsgSourcesInTheOwsgOrder) {
  expect_owsg_table(gyro_ns_model(), owsg_rows(0.2, 0.6, 0.4));
  expect_owsg_table(gyro_mwd_model(), owsg_rows(0.4, 1.0, 0.6));
  for (const std::string_view name : {kGyroNsModelName, kGyroMwdModelName}) {
    const SurveyCovariance covariance =
        tool_model_covariance(name, reference_well(), reference_site(), ContinuousGyroTerms{});
    ASSERT_EQ(covariance.sources.size(), 18u) << name;
    EXPECT_TRUE(is_gyro_tool_model(name));
  }
  EXPECT_EQ(tool_model_title(kGyroNsModelName), "OWSG GYRO-NS (rev 5)");
  EXPECT_EQ(tool_model_title(kGyroMwdModelName), "OWSG GYRO-MWD (rev 5)");
  EXPECT_FALSE(is_gyro_tool_model("mwd_rev5"));
}

TEST(StationaryGyroToolModel, TotalIsTheSumSymmetricPositiveDefinite) {
  const auto stations = reference_well();
  for (const std::string_view name : {kGyroNsModelName, kGyroMwdModelName}) {
    const SurveyCovariance covariance =
        tool_model_covariance(name, stations, reference_site(), ContinuousGyroTerms{});
    EXPECT_EQ(covariance.total_nev_m2.front(), Matrix3d::Zero()) << "the tie-on is exact";
    for (std::size_t k = 1; k < stations.size(); ++k) {
      Matrix3d sum = Matrix3d::Zero();
      for (const auto& source : covariance.sources) {
        ASSERT_TRUE(source.nev_m2[k].allFinite()) << name << " " << source.code << " " << k;
        sum += source.nev_m2[k];
      }
      const Matrix3d& total = covariance.total_nev_m2[k];
      EXPECT_LE((sum - total).cwiseAbs().maxCoeff(), 1e-12 * total.cwiseAbs().maxCoeff());
      EXPECT_LE((total - total.transpose()).cwiseAbs().maxCoeff(), 1e-12 * total.norm());
      const Eigen::SelfAdjointEigenSolver<Matrix3d> solver(total);
      EXPECT_GT(solver.eigenvalues().minCoeff(), 0.0) << name << " station " << k;
    }
  }
}

TEST(StationaryGyroToolModel, GyroMwdIsGyroNsWithLargerGDependentAndNoiseTerms) {
  const auto stations = reference_well();
  const SurveyCovariance ns =
      tool_model_covariance(kGyroNsModelName, stations, reference_site(), ContinuousGyroTerms{});
  const SurveyCovariance mwd =
      tool_model_covariance(kGyroMwdModelName, stations, reference_site(), ContinuousGyroTerms{});
  for (std::size_t i = 0; i < ns.sources.size(); ++i) {
    const std::string& code = ns.sources[i].code;
    const double ratio = code == "GXY-G1"   ? 0.4 / 0.2
                         : code == "GXY-G4" ? 1.0 / 0.6
                         : code == "GXY-RN" ? 0.6 / 0.4
                                            : 1.0;
    for (std::size_t k = 0; k < stations.size(); ++k) {
      const Matrix3d expected = ratio * ratio * ns.sources[i].nev_m2[k];
      EXPECT_LE((mwd.sources[i].nev_m2[k] - expected).cwiseAbs().maxCoeff(),
                1e-12 * (1.0 + expected.cwiseAbs().maxCoeff()))
          << code << " station " << k;
    }
  }
}

// owsg_gyro_reference.py's output for GYRO-NS.json and GYRO-MWD.json: NN, EE, VV, NE, NV, EV
// (m^2) at stations 12 (4 deg), 18 (16 deg), 40 (50 deg, in the hold) and 80 (the last).
// clang-format off
const ReferenceCovariance kGyroNsFormulaReference[] = {
{"DRFR", 12, {0.00036333063961312573, 0.00015833091336387031, 0.12212744953419699, 0.00023980442362873125, 0.0053418957857340101, 0.0035133336016102946}},
{"DRFR", 18, {0.0046220489626356527, 0.0046593494430320946, 0.11428436358377934, 0.0046183890886648312, 0.021527596323596198, 0.021559340487944632}},
{"DRFR", 40, {0.0029986029388204185, 0.072538433641544831, 0.051404640720402538, 0.012655214235851335, 0.010605799282659071, 0.058033279301414512}},
{"DRFR", 80, {0.0029986029388204185, 0.072538433641544831, 0.051404640720402538, 0.012655214235851335, 0.010605799282659071, 0.058033279301414512}},
{"DSFS", 12, {9.6628621913832689e-07, 4.0750261258747157e-07, 0.040630184281222434, 6.2750630180591671e-07, 0.00019814234063419132, 0.00012867364238455583}},
{"DSFS", 18, {0.00019865290546238515, 0.00014735369993597815, 0.090388335836035782, 0.00017109132246526863, 0.0042374409180233217, 0.0036495281498428859}},
{"DSFS", 40, {0.0076811593179935385, 0.04547032263710727, 0.34885806187674684, 0.018688627355057112, 0.051765184754251001, 0.12594716601850003}},
{"DSFS", 80, {0.031340738416189395, 0.51868643603598297, 1.0457012491349322, 0.12749908200386895, 0.18103328232847243, 0.73647203210452838}},
{"SAGE", 12, {0.0036741814504376836, 0.0015195297917714357, 1.1948668668933196e-05, 0.0023628432394710496, -0.00020952703114591274, -0.00013474553059174147}},
{"SAGE", 18, {0.12937163834253479, 0.085617326423476137, 0.005643734874711601, 0.10524473283691067, -0.02702108856268267, -0.021981844577190043}},
{"SAGE", 40, {0.95540840196038035, 2.8492609357109382, 1.6315716791923189, 1.6499114634900036, -1.248526047265714, -2.1561014469024813}},
{"SAGE", 80, {2.001831866427374, 17.377702636533321, 18.312391068669321, 5.8980707780689947, -6.0546121256231, -17.838926160373109}},
{"XYM1", 12, {9.3577239177446161e-06, 3.9460671895819028e-06, 3.6543559183285854e-08, 6.0766937820642122e-06, -5.8477734036892198e-07, -3.7974114852581986e-07}},
{"XYM1", 18, {0.0018568879301119534, 0.0013731205663573927, 0.00011665088726744078, 0.0015967877148379906, -0.00046541124245527303, -0.00040021960520539301}},
{"XYM1", 40, {0.051894089407525733, 0.25514717442957846, 0.19269971462331234, 0.11506793767999021, -0.09999988109726364, -0.22173585118226657}},
{"XYM1", 80, {0.16555464690241825, 2.3126551100150752, 2.7822815593878016, 0.61876554537693762, -0.67868965009609294, -2.5366232802327806}},
{"XYM2", 12, {3.9583033929444675e-06, 9.3860846571865916e-06, 0, -6.0953236784444598e-06, 0, -0}},
{"XYM2", 18, {0.0014313298428100306, 0.0019296280451238774, 0, -0.0016619067983822036, 0, -0}},
{"XYM2", 40, {0.44167896551609609, 0.074611445549037855, 0, -0.18153320931928563, 0, -0}},
{"XYM2", 80, {5.0382947647845926, 0.3044303211272264, 0, -1.2384707074359882, 0, -0}},
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
{"GXY-B1R", 12, {7.7226325673221988e-05, 0.00018224345869499893, 0, -0.00011854768934784529, 0, 0}},
{"GXY-B1R", 18, {0.013990302119235701, 0.017117554818188618, 0, -0.015395333049112336, 0, 0}},
{"GXY-B1R", 40, {4.7196920138013114, 0.42822263707195857, 0, -1.2484016171748065, 0, 0}},
{"GXY-B1R", 80, {23.85213215170759, 1.0230732388235499, 0, -4.6219670202772685, 0, 0}},
{"GXY-B2R", 12, {0.00018167834033261623, 0.00043130357579637755, 0, -0.00027972158885623463, 0, 0}},
{"GXY-B2R", 18, {0.016354428606298429, 0.021030977975192381, 0, -0.018430780982119005, 0, 0}},
{"GXY-B2R", 40, {0.2727926715895273, 0.094186225072041954, 0, -0.14346793615049666, 0, 0}},
{"GXY-B2R", 80, {0.51857061097620283, 0.10182775715512278, 0, -0.18680521812729742, 0, 0}},
{"GXY-G1", 12, {1.786390272652832e-06, 4.1329299881530739e-06, 0, -2.7171724141820364e-06, -0, 0}},
{"GXY-G1", 18, {0.0066179614657671838, 0.0082116615397624937, 0, -0.007371869480672498, -0, 0}},
{"GXY-G1", 40, {3.5054682812126372, 0.67447957018404692, 0, -1.5376497454251763, -0, 0}},
{"GXY-G1", 80, {25.75386426053749, 1.9208871211827683, 0, -7.0335102316521612, -0, 0}},
{"GXY-G4", 12, {6.9932545325503515e-06, 1.6136835823746236e-05, 0, -1.0623041008366402e-05, -0, 0}},
{"GXY-G4", 18, {0.051777468874474777, 0.062513751212546598, 0, -0.056892915267494341, -0, 0}},
{"GXY-G4", 40, {611.77783853231415, 54.077061101406088, 0, -181.88773338188065, -0, 0}},
{"GXY-G4", 80, {11990.599606664855, 497.3122907319015, 0, -2441.940326387919, -0, 0}},
{"GXY-RN", 12, {0.0018410998471526277, 0.0043630011341608994, 0, -0.0028321370894512348, 0, 0}},
{"GXY-RN", 18, {0.21578475182602047, 0.27127845541959827, 0, -0.2405412553332007, 0, 0}},
{"GXY-RN", 40, {35.502113318334871, 3.7149074641351159, 0, -9.8977390458688248, 0, 0}},
{"GXY-RN", 80, {173.30277520130716, 7.9992959714039227, 0, -34.195713695321366, 0, 0}},
};

const ReferenceCovariance kGyroMwdFormulaReference[] = {
{"DRFR", 12, {0.00036333063961312573, 0.00015833091336387031, 0.12212744953419699, 0.00023980442362873125, 0.0053418957857340101, 0.0035133336016102946}},
{"DRFR", 18, {0.0046220489626356527, 0.0046593494430320946, 0.11428436358377934, 0.0046183890886648312, 0.021527596323596198, 0.021559340487944632}},
{"DRFR", 40, {0.0029986029388204185, 0.072538433641544831, 0.051404640720402538, 0.012655214235851335, 0.010605799282659071, 0.058033279301414512}},
{"DRFR", 80, {0.0029986029388204185, 0.072538433641544831, 0.051404640720402538, 0.012655214235851335, 0.010605799282659071, 0.058033279301414512}},
{"DSFS", 12, {9.6628621913832689e-07, 4.0750261258747157e-07, 0.040630184281222434, 6.2750630180591671e-07, 0.00019814234063419132, 0.00012867364238455583}},
{"DSFS", 18, {0.00019865290546238515, 0.00014735369993597815, 0.090388335836035782, 0.00017109132246526863, 0.0042374409180233217, 0.0036495281498428859}},
{"DSFS", 40, {0.0076811593179935385, 0.04547032263710727, 0.34885806187674684, 0.018688627355057112, 0.051765184754251001, 0.12594716601850003}},
{"DSFS", 80, {0.031340738416189395, 0.51868643603598297, 1.0457012491349322, 0.12749908200386895, 0.18103328232847243, 0.73647203210452838}},
{"SAGE", 12, {0.0036741814504376836, 0.0015195297917714357, 1.1948668668933196e-05, 0.0023628432394710496, -0.00020952703114591274, -0.00013474553059174147}},
{"SAGE", 18, {0.12937163834253479, 0.085617326423476137, 0.005643734874711601, 0.10524473283691067, -0.02702108856268267, -0.021981844577190043}},
{"SAGE", 40, {0.95540840196038035, 2.8492609357109382, 1.6315716791923189, 1.6499114634900036, -1.248526047265714, -2.1561014469024813}},
{"SAGE", 80, {2.001831866427374, 17.377702636533321, 18.312391068669321, 5.8980707780689947, -6.0546121256231, -17.838926160373109}},
{"XYM1", 12, {9.3577239177446161e-06, 3.9460671895819028e-06, 3.6543559183285854e-08, 6.0766937820642122e-06, -5.8477734036892198e-07, -3.7974114852581986e-07}},
{"XYM1", 18, {0.0018568879301119534, 0.0013731205663573927, 0.00011665088726744078, 0.0015967877148379906, -0.00046541124245527303, -0.00040021960520539301}},
{"XYM1", 40, {0.051894089407525733, 0.25514717442957846, 0.19269971462331234, 0.11506793767999021, -0.09999988109726364, -0.22173585118226657}},
{"XYM1", 80, {0.16555464690241825, 2.3126551100150752, 2.7822815593878016, 0.61876554537693762, -0.67868965009609294, -2.5366232802327806}},
{"XYM2", 12, {3.9583033929444675e-06, 9.3860846571865916e-06, 0, -6.0953236784444598e-06, 0, -0}},
{"XYM2", 18, {0.0014313298428100306, 0.0019296280451238774, 0, -0.0016619067983822036, 0, -0}},
{"XYM2", 40, {0.44167896551609609, 0.074611445549037855, 0, -0.18153320931928563, 0, -0}},
{"XYM2", 80, {5.0382947647845926, 0.3044303211272264, 0, -1.2384707074359882, 0, -0}},
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
{"GXY-B1R", 12, {7.7226325673221988e-05, 0.00018224345869499893, 0, -0.00011854768934784529, 0, 0}},
{"GXY-B1R", 18, {0.013990302119235701, 0.017117554818188618, 0, -0.015395333049112336, 0, 0}},
{"GXY-B1R", 40, {4.7196920138013114, 0.42822263707195857, 0, -1.2484016171748065, 0, 0}},
{"GXY-B1R", 80, {23.85213215170759, 1.0230732388235499, 0, -4.6219670202772685, 0, 0}},
{"GXY-B2R", 12, {0.00018167834033261623, 0.00043130357579637755, 0, -0.00027972158885623463, 0, 0}},
{"GXY-B2R", 18, {0.016354428606298429, 0.021030977975192381, 0, -0.018430780982119005, 0, 0}},
{"GXY-B2R", 40, {0.2727926715895273, 0.094186225072041954, 0, -0.14346793615049666, 0, 0}},
{"GXY-B2R", 80, {0.51857061097620283, 0.10182775715512278, 0, -0.18680521812729742, 0, 0}},
{"GXY-G1", 12, {7.1455610906113282e-06, 1.6531719952612296e-05, 0, -1.0868689656728145e-05, -0, 0}},
{"GXY-G1", 18, {0.026471845863068735, 0.032846646159049975, 0, -0.029487477922689992, -0, 0}},
{"GXY-G1", 40, {14.021873124850549, 2.6979182807361877, 0, -6.1505989817007052, -0, 0}},
{"GXY-G1", 80, {103.01545704214996, 7.6835484847310731, 0, -28.134040926608645, -0, 0}},
{"GXY-G4", 12, {1.9425707034862082e-05, 4.4824543954850662e-05, 0, -2.9508447245462222e-05, -0, 0}},
{"GXY-G4", 18, {0.14382630242909664, 0.17364930892374061, 0, -0.1580358757430399, -0, 0}},
{"GXY-G4", 40, {1699.3828848119842, 150.21405861501697, 0, -505.24370383855751, -0, 0}},
{"GXY-G4", 80, {33307.221129624646, 1381.4230298108407, 0, -6783.1675732997874, -0, 0}},
{"GXY-RN", 12, {0.0041424746560934107, 0.0098167525518620211, 0, -0.006372308451265277, 0, 0}},
{"GXY-RN", 18, {0.48551569160854602, 0.61037652469409598, 0, -0.54121782449970135, 0, 0}},
{"GXY-RN", 40, {79.879754966253458, 8.3585417943040099, 0, -22.269912853204861, 0, 0}},
{"GXY-RN", 80, {389.93124420294038, 17.998415935658805, 0, -76.940355814473094, 0, 0}},
};
// clang-format on

/// The largest error of the library's model `name` against `reference` (owsg_reference.hpp).
double largest_error_against(std::string_view name, std::span<const ReferenceCovariance> reference) {
  const SurveyCovariance covariance =
      tool_model_covariance(name, reference_well(), reference_site(), ContinuousGyroTerms{});
  return testing::largest_error_against(covariance, reference, std::string(name));
}

TEST(OwsgStationaryGyroReference, CovariancesEqualThoseOfTheOwsgFormulaStrings) {
  std::printf(
      "OWSG formula reference: largest error %.2g (GYRO-NS), %.2g (GYRO-MWD) of the "
      "largest variance\n",
      largest_error_against(kGyroNsModelName, kGyroNsFormulaReference),
      largest_error_against(kGyroMwdModelName, kGyroMwdFormulaReference));
}

TEST(StationaryGyroToolModel, AStationAtNinetyDegreesOrAPoleIsRefused) {
  // Every station is a gyrocompass station, not only those below 15 deg as in GYRO-NS-CT.
  const std::vector<ListingStation> horizontal = {
      {0, 0, 0}, {30, 30 * kRadPerDeg, 0}, {60, std::numbers::pi / 2, 0}};
  WellParameters pole = reference_site();
  pole.latitude_rad = std::numbers::pi / 2;
  WellParameters still = reference_site();
  still.earth_rate_rad_s = 0.0;
  for (const std::string_view name : {kGyroNsModelName, kGyroMwdModelName}) {
    EXPECT_THROW(tool_model_covariance(name, horizontal, reference_site(), ContinuousGyroTerms{}),
                 std::invalid_argument);
    EXPECT_THROW(tool_model_covariance(name, reference_well(), pole, ContinuousGyroTerms{}),
                 std::invalid_argument);
    EXPECT_THROW(tool_model_covariance(name, reference_well(), still, ContinuousGyroTerms{}),
                 std::invalid_argument);
  }
  // 89 deg, the top of the OWSG range, is evaluated.
  const std::vector<ListingStation> steep = {{0, 0, 0}, {30, 89 * kRadPerDeg, 0}};
  EXPECT_NO_THROW(
      tool_model_covariance(kGyroNsModelName, steep, reference_site(), ContinuousGyroTerms{}));
}

}  // namespace
}  // namespace stochnav::survey_error
