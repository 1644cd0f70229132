// The OWSG gyro tool model GYRO-NS-CT ("OWSG XYZ Accel with XY Static and Continuous Gyro", rev 5,
// 2020-10-08; OWSG tool group A021Gc, after ISCWSA gyro model #3 and Torkildsen et al., SPE
// 90408): a stationary north-seeking gyrocompass below the continuous start inclination (15 deg),
// a continuous survey from the first station at or above it. One row per error source as the
// OWSG table gives it (1 sigma); the continuous-gyro terms GXY-RN, GXY-GD and GXY-GRW, whose
// correlation between stations no mode of this table describes, are continuous_gyro.cpp's and
// go between GXY-G4 and SAGE in the output (tool_models.cpp), in the OWSG order.
//
// Weighting functions (weighting_functions.cpp): the depth, misalignment and tortuosity rows are
// the ISCWSA MWD Rev5 ones (mwd_models.cpp, the same magnitudes); AXYZ-* change the inclination
// only; GXY-B1S, GXY-B2S and GXY-G4 are gyrocompass azimuth errors that the continuous survey
// carries forward from its initialising station (SurveyErrorModel::continuous_start_inclination).

#include "mwd_models.hpp"
#include "stochnav/survey_error/tool_models.hpp"

namespace stochnav::survey_error {

SurveyErrorModel gyro_ns_ct_table_model(const ContinuousGyroTerms& terms) {
  using enum WeightingFunction;
  using enum PropagationMode;
  using enum MagnitudeUnit;
  SurveyErrorModel model;
  model.name = std::string(kGyroNsCtModelName);
  model.title = "OWSG GYRO-NS-CT (rev 5)";
  model.default_tortuosity_rad_per_m = kIscwsaDefaultTortuosityRadPerM;
  // The tie-on's direction is exact and the first station's error turns half the first leg, as
  // minimum curvature from an exact tie-on does (and as the continuous-gyro terms propagate).
  model.first_station_turns_whole_first_leg = false;
  model.continuous_start_inclination_rad = terms.continuous_start_inclination_rad;
  // clang-format off
  model.sources = joined_sources({iscwsa_depth_sources(), rev5_misalignment_sources(), {
      // code        weighting   magnitude  unit               mode
      {"AXYZ-MIS",   kAxyzMis,   0.0095,    kDegree,           kSystematic},
      {"AXYZ-SF",    kAxyzSf,    0.000111,  kDimensionless,    kSystematic},
      {"AXYZ-ZB",    kAxyzZb,    0.0017,    kMetrePerSecond2,  kSystematic},
      {"GXY-B1S",    kGxyB1,     0.15,      kDegreePerHour,    kSystematic},
      {"GXY-B2S",    kGxyB2,     0.15,      kDegreePerHour,    kSystematic},
      {"GXY-G4",     kGxyG4,     0.6,       kDegreePerHour,    kSystematic},
      {"SAGE",       kSage,      0.08,      kDegree,           kSystematic},
  }});
  // clang-format on
  return model;
}

}  // namespace stochnav::survey_error
