// The OWSG stationary gyro tool models (rev 5, 2020-10-08; "3-Axis Accelerometer and 2-Axis
// Gyro Stationary Tool", source OWSG - Gyrodata/SDI, after ISCWSA gyro model / Torkildsen et
// al., SPE 90408): a north-seeking x-y gyrocompass at every survey station, no continuous
// survey.
//
//   GYRO-NS   (OWSG A020Gb) "OWSG Gyrocompass Gyro": a wireline gyrocompass survey;
//   GYRO-MWD  (OWSG A019Gb) "OWSG Gyro MWD": a gyro in the drill string, surveying at the
//             connections while drilling is stopped (larger g-dependent and noise terms).
//
// The two tables differ only in the magnitudes of GXY-G1, GXY-G4 and GXY-RN. One row per error
// source as the OWSG table gives it (1 sigma), in the OWSG order. Tool constants: noise
// reduction factor 1 (the OWSG tables give none for these tools), XCL tortuosity 1 deg / 100
// ft, inclination range 0 to 89 deg ("the tool model fails at 90 deg").
//
// Weighting functions (weighting_functions.cpp): the depth, misalignment and tortuosity rows
// are the ISCWSA MWD Rev5 ones (mwd_models.cpp, the same magnitudes); SAGE is the Rev5 function
// and magnitude; AXYZ-* are GYRO-NS-CT's; GXY-B1R and GXY-B2R are GYRO-NS-CT's bias functions
// with random propagation (the bias is re-estimated at every station); GXY-G1 and GXY-RN are
// new. Every station is a gyrocompass station, so every gyro term has the station's own weight.

#include "mwd_models.hpp"
#include "stochnav/survey_error/tool_models.hpp"

namespace stochnav::survey_error {
namespace {

/// The magnitudes in which GYRO-NS and GYRO-MWD differ (deg/h).
struct StationaryGyroMagnitudes {
  double g_dependent_g1_deg_h;
  double g_dependent_g4_deg_h;
  double rate_noise_deg_h;
};

SurveyErrorModel stationary_gyro_model(std::string_view name, std::string title,
                                       const StationaryGyroMagnitudes& gyro) {
  using enum WeightingFunction;
  using enum PropagationMode;
  using enum MagnitudeUnit;
  SurveyErrorModel model;
  model.name = std::string(name);
  model.title = std::move(title);
  model.default_tortuosity_rad_per_m = kIscwsaDefaultTortuosityRadPerM;
  // The tie-on's direction is exact and the first station's error turns half the first leg (as
  // GYRO-NS-CT here, and Rev4).
  model.first_station_turns_whole_first_leg = false;
  model.noise_reduction_factor = 1.0;
  // clang-format off
  model.sources = joined_sources({iscwsa_depth_sources(), {
      // code        weighting   magnitude                  unit            mode
      {"SAGE",       kSage,      0.2,                       kDegree,        kSystematic},
  }, rev5_misalignment_sources(), {
      {"AXYZ-MIS",   kAxyzMis,   0.0095,                    kDegree,        kSystematic},
      {"AXYZ-SF",    kAxyzSf,    0.000111,                  kDimensionless, kSystematic},
      {"AXYZ-ZB",    kAxyzZb,    0.0017,                    kMetrePerSecond2, kSystematic},
      {"GXY-B1R",    kGxyB1,     0.15,                      kDegreePerHour, kRandom},
      {"GXY-B2R",    kGxyB2,     0.15,                      kDegreePerHour, kRandom},
      {"GXY-G1",     kGxyG1,     gyro.g_dependent_g1_deg_h, kDegreePerHour, kSystematic},
      {"GXY-G4",     kGxyG4,     gyro.g_dependent_g4_deg_h, kDegreePerHour, kSystematic},
      {"GXY-RN",     kGxyRn,     gyro.rate_noise_deg_h,     kDegreePerHour, kRandom},
  }});
  // clang-format on
  return model;
}

}  // namespace

SurveyErrorModel gyro_ns_model() {
  return stationary_gyro_model(
      kGyroNsModelName, "OWSG GYRO-NS (rev 5)",
      {.g_dependent_g1_deg_h = 0.2, .g_dependent_g4_deg_h = 0.6, .rate_noise_deg_h = 0.4});
}

SurveyErrorModel gyro_mwd_model() {
  return stationary_gyro_model(
      kGyroMwdModelName, "OWSG GYRO-MWD (rev 5)",
      {.g_dependent_g1_deg_h = 0.4, .g_dependent_g4_deg_h = 1.0, .rate_noise_deg_h = 0.6});
}

}  // namespace stochnav::survey_error
