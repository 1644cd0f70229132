// The ISCWSA MWD error models, one row per error source, magnitudes as the ISCWSA tables give
// them (1 sigma). Sources in the order of the ISCWSA example workbooks; the depth and sensor rows
// are the same in both revisions.
//
// Modes follow the calculations of the example workbooks, which the validation reproduces:
// Rev5 XYM2 is systematic and XYM4E random (the Rev5 workbook's model tab lists XYM2 as R and
// XYM4E as S, but its calculation and expected values use S and R, as welleng also found).
// DEC-U and DBH-U are per-well (W) as in the OWSG MWD tool models; within one well W, S and G
// give the same covariance (error_model.hpp).

#include "mwd_models.hpp"

#include <initializer_list>
#include <numbers>
#include <vector>

namespace stochnav::survey_error {
namespace {

using enum WeightingFunction;
using enum PropagationMode;
using MagnitudeUnit::kDegree;
using MagnitudeUnit::kDegreeNanotesla;
using MagnitudeUnit::kDimensionless;
using MagnitudeUnit::kMetre;
using MagnitudeUnit::kMetrePerSecond2;
using MagnitudeUnit::kNanotesla;
using MagnitudeUnit::kPerMetre;

}  // namespace

std::vector<ErrorSource> iscwsa_depth_sources() {
  // clang-format off
  return {
      // code        weighting   magnitude  unit               mode
      {"DRFR",       kDref,      0.35,      kMetre,            kRandom},
      {"DSFS",       kDsf,       0.00056,   kDimensionless,    kSystematic},
      {"DSTG",       kDst,       2.5e-7,    kPerMetre,         kGlobal},
  };
  // clang-format on
}

std::vector<ErrorSource> rev5_misalignment_sources() {
  // clang-format off
  return {
      // code        weighting   magnitude  unit               mode
      {"XYM1",       kXym1,      0.1,       kDegree,           kSystematic},
      {"XYM2",       kXym2,      0.1,       kDegree,           kSystematic},
      {"XYM3E",      kXym3e,     0.3,       kDegree,           kRandom},
      {"XYM4E",      kXym4e,     0.3,       kDegree,           kRandom},
      {"XCLA",       kXcla,      0.167,     kDimensionless,    kRandom},
      {"XCLH",       kXclh,      0.167,     kDimensionless,    kRandom},
  };
  // clang-format on
}

namespace {

/// The accelerometer and magnetometer biases and scale factors, the same in Rev4 and Rev5.
std::vector<ErrorSource> sensor_sources() {
  // clang-format off
  return {
      // code        weighting   magnitude  unit               mode
      {"ABXY-TI1S",  kAbxyTi1,   0.004,     kMetrePerSecond2,  kSystematic},
      {"ABXY-TI2S",  kAbxyTi2,   0.004,     kMetrePerSecond2,  kSystematic},
      {"ABZ",        kAbz,       0.004,     kMetrePerSecond2,  kSystematic},
      {"ASXY-TI1S",  kAsxyTi1,   0.0005,    kDimensionless,    kSystematic},
      {"ASXY-TI2S",  kAsxyTi2,   0.0005,    kDimensionless,    kSystematic},
      {"ASXY-TI3S",  kAsxyTi3,   0.0005,    kDimensionless,    kSystematic},
      {"ASZ",        kAsz,       0.0005,    kDimensionless,    kSystematic},
      {"MBXY-TI1S",  kMbxyTi1,   70.0,      kNanotesla,        kSystematic},
      {"MBXY-TI2S",  kMbxyTi2,   70.0,      kNanotesla,        kSystematic},
      {"MBZ",        kMbz,       70.0,      kNanotesla,        kSystematic},
      {"MSXY-TI1S",  kMsxyTi1,   0.0016,    kDimensionless,    kSystematic},
      {"MSXY-TI2S",  kMsxyTi2,   0.0016,    kDimensionless,    kSystematic},
      {"MSXY-TI3S",  kMsxyTi3,   0.0016,    kDimensionless,    kSystematic},
      {"MSZ",        kMsz,       0.0016,    kDimensionless,    kSystematic},
  };
  // clang-format on
}

}  // namespace

std::vector<ErrorSource> joined_sources(std::initializer_list<std::vector<ErrorSource>> lists) {
  std::vector<ErrorSource> sources;
  for (const auto& list : lists) sources.insert(sources.end(), list.begin(), list.end());
  return sources;
}

SurveyErrorModel make_mwd_rev5_model() {
  SurveyErrorModel model;
  model.name = "mwd_rev5";
  model.title = "ISCWSA MWD Rev5.11";
  model.default_tortuosity_rad_per_m = kIscwsaDefaultTortuosityRadPerM;
  model.first_station_turns_whole_first_leg = true;
  // clang-format off
  model.sources = joined_sources({iscwsa_depth_sources(), sensor_sources(), {
      // code        weighting   magnitude  unit               mode
      {"DEC-U",      kAzimuth,   0.16,      kDegree,           kPerWell},
      {"DEC-OS",     kAzimuth,   0.24,      kDegree,           kGlobal},
      {"DEC-OH",     kAzimuth,   0.21,      kDegree,           kGlobal},
      {"DEC-OI",     kAzimuth,   0.05,      kDegree,           kGlobal},
      {"DECR",       kAzimuth,   0.1,       kDegree,           kRandom},
      {"DBH-U",      kDbh,       2350.0,    kDegreeNanotesla,  kPerWell},
      {"DBH-OS",     kDbh,       3359.0,    kDegreeNanotesla,  kGlobal},
      {"DBH-OH",     kDbh,       2840.0,    kDegreeNanotesla,  kGlobal},
      {"DBH-OI",     kDbh,       356.0,     kDegreeNanotesla,  kGlobal},
      {"DBHR",       kDbh,       3000.0,    kDegreeNanotesla,  kRandom},
      {"AMIL",       kAmil,      220.0,     kNanotesla,        kSystematic},
      {"SAGE",       kSage,      0.2,       kDegree,           kSystematic},
  }, rev5_misalignment_sources()});
  // clang-format on
  return model;
}

SurveyErrorModel make_mwd_rev4_model() {
  SurveyErrorModel model;
  model.name = "mwd_rev4";
  model.title = "ISCWSA MWD Rev4";
  model.default_tortuosity_rad_per_m = kIscwsaDefaultTortuosityRadPerM;
  model.first_station_turns_whole_first_leg = false;
  // clang-format off
  model.sources = joined_sources({sensor_sources(), {
      // code        weighting   magnitude  unit               mode
      {"DECG",       kAzimuth,   0.36,      kDegree,           kGlobal},
      {"DECR",       kAzimuth,   0.1,       kDegree,           kRandom},
      {"DBHG",       kDbh,       5000.0,    kDegreeNanotesla,  kGlobal},
      {"DBHR",       kDbh,       3000.0,    kDegreeNanotesla,  kRandom},
      {"AMIL",       kAmil,      220.0,     kNanotesla,        kSystematic},
      {"XYM1",       kXym1,      0.1,       kDegree,           kSystematic},
      {"XYM2",       kXym2,      0.1,       kDegree,           kSystematic},
      {"XYM3",       kXym3,      0.1,       kDegree,           kSystematic},
      {"XYM4",       kXym4,      0.1,       kDegree,           kSystematic},
  }, iscwsa_depth_sources(), {
      {"SAG",        kSag,       0.2,       kDegree,           kSystematic},
  }});
  // clang-format on
  return model;
}

}  // namespace stochnav::survey_error
